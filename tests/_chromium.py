"""Headless Chromium with the network off, for the tests that open a page (decks, the
course site, the static explorers).  One place for the flags."""

from __future__ import annotations

import json
import os
import queue
import shutil
import subprocess
import threading
import time
from pathlib import Path

CHROMIUM = next((shutil.which(n) for n in ("chromium", "chromium-browser", "google-chrome") if shutil.which(n)), None)
SKIP_REASON = "Chromium is not installed (CI installs it: `apt-get install chromium`)"


# the flags every run shares: headless, no GPU, no background traffic, the network off
# (every connection goes to a closed port and no name resolves)
FLAGS = [
    "--headless",
    "--no-sandbox",
    "--disable-gpu",
    "--disable-dev-shm-usage",
    "--disable-background-networking",
    "--no-first-run",
    "--disable-component-update",
    "--disable-sync",
    "--disable-extensions",
    "--proxy-server=127.0.0.1:9",
    "--host-resolver-rules=MAP * ~NOTFOUND",
]


def dump_dom(url: str, profile: Path, *, budget_ms: int = 8000, window=None, console: bool = False):
    """The page's DOM after load, with the network off: every connection goes to a closed
    port and no name resolves.  With ``console``, also its console messages (a list)."""
    cmd = [CHROMIUM, *FLAGS, f"--user-data-dir={profile}", f"--virtual-time-budget={budget_ms}"]
    if window:
        cmd.append(f"--window-size={window[0]},{window[1]}")
    if console:
        cmd += ["--enable-logging=stderr", "--log-level=0"]
    run = subprocess.run([*cmd, "--dump-dom", url], capture_output=True, text=True, timeout=180)
    assert run.returncode == 0, run.stderr[-2000:]
    if not console:
        return run.stdout
    lines = [line[line.index('"') :] if '"' in line else line for line in run.stderr.splitlines() if ":CONSOLE" in line]
    return run.stdout, lines


def _above(fd: int, low: int) -> int:
    """``fd`` moved to a descriptor number of at least ``low``."""
    import fcntl

    new = fcntl.fcntl(fd, fcntl.F_DUPFD_CLOEXEC, low)
    os.close(fd)
    return new


class DevTools:
    """Chromium driven over the DevTools protocol on a pipe (``--remote-debugging-pipe``:
    the browser reads commands on its fd 3 and writes replies and events on its fd 4,
    each a JSON text ended by a NUL byte), with the network off."""

    def __init__(self, profile: Path):
        to_browser_r, self._to_browser = os.pipe()
        self._from_browser, from_browser_w = os.pipe()
        # the child's ends moved above 3 and 4, so that putting them there never
        # overwrites one with the other (and dup2 makes them inheritable)
        to_browser_r, from_browser_w = (_above(fd, 10) for fd in (to_browser_r, from_browser_w))

        def fds():  # in the child, before exec: the pipes become its fds 3 and 4
            os.dup2(to_browser_r, 3)
            os.dup2(from_browser_w, 4)

        # WebGL (the 3Dmol.js views) on SwiftShader through ANGLE, asked for explicitly: the
        # same software renderer on every machine, and none of the messages a GPU-less
        # fallback logs ("Automatic fallback to software WebGL has been deprecated", the
        # host driver's "GPU stall due to ReadPixels"), which are about the test machine,
        # not about the page
        flags = [f for f in FLAGS if f != "--disable-gpu"] + ["--use-angle=swiftshader", "--enable-unsafe-swiftshader"]
        self.proc = subprocess.Popen(
            [CHROMIUM, *flags, f"--user-data-dir={profile}", "--remote-debugging-pipe", "about:blank"],
            stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            preexec_fn=fds,
            close_fds=False,
        )
        os.close(to_browser_r)
        os.close(from_browser_w)
        self._id = 0
        self._replies: dict = {}
        self.events: queue.Queue = queue.Queue()
        self._cond = threading.Condition()
        threading.Thread(target=self._read, daemon=True).start()

    def _read(self):
        buf = b""
        while True:
            chunk = os.read(self._from_browser, 1 << 16)
            if not chunk:
                break
            buf += chunk
            while b"\0" in buf:
                raw, buf = buf.split(b"\0", 1)
                msg = json.loads(raw)
                if "id" in msg:
                    with self._cond:
                        self._replies[msg["id"]] = msg
                        self._cond.notify_all()
                else:
                    self.events.put(msg)

    def send(self, method: str, params: dict | None = None, session: str | None = None, timeout: float = 60.0):
        """Send a command and wait for its result (raises on a protocol error)."""
        self._id += 1
        msg = {"id": self._id, "method": method, "params": params or {}}
        if session:
            msg["sessionId"] = session
        os.write(self._to_browser, json.dumps(msg).encode() + b"\0")
        with self._cond:
            if not self._cond.wait_for(lambda: self._id in self._replies, timeout=timeout):
                raise TimeoutError(f"Chromium did not answer {method} within {timeout} s")
            reply = self._replies.pop(self._id)
        if "error" in reply:
            raise RuntimeError(f"{method}: {reply['error']}")
        return reply.get("result", {})

    def close(self):
        try:
            self.send("Browser.close", timeout=10)
        except (OSError, RuntimeError, TimeoutError):
            pass
        try:
            self.proc.wait(timeout=20)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait()
        os.close(self._to_browser)


def _describe(event: dict) -> dict | None:
    """A console event as ``{"level", "source", "text"}``: every message of level error or
    warning, from the page's scripts (console.error, console.warn, console.assert), from
    the browser (failed loads, refused scripts, deprecations) and every uncaught exception
    or unhandled rejection; None for anything else (console.log, info, debug)."""
    method, p = event.get("method"), event.get("params", {})
    if method == "Runtime.consoleAPICalled" and p.get("type") in ("error", "warning", "assert"):
        text = " ".join(str(a.get("value", a.get("description", a.get("type", "")))) for a in p.get("args", []))
        frames = (p.get("stackTrace") or {}).get("callFrames") or [{}]
        return {"level": p["type"], "source": frames[0].get("url", ""), "text": text}
    if method == "Runtime.exceptionThrown":
        d = p.get("exceptionDetails", {})
        text = (d.get("exception") or {}).get("description") or d.get("text", "")
        return {"level": "exception", "source": d.get("url", ""), "text": text}
    if method == "Log.entryAdded" and p.get("entry", {}).get("level") in ("error", "warning"):
        e = p["entry"]
        return {"level": e["level"], "source": e.get("url", e.get("source", "")), "text": e.get("text", "")}
    return None


def _failed_load(params: dict, urls: dict) -> dict | None:
    """A ``Network.loadingFailed`` event as a message: a request that never got its file,
    including those the console does not report (a frame whose document is missing or
    remote: Chromium shows its error page and logs nothing).  A load the page itself
    cancelled (``canceled``: an image removed before it arrived) is no failure."""
    if params.get("canceled"):
        return None
    url = urls.get(params.get("requestId"), "")
    return {
        "level": "error",
        "source": url,
        "text": f"failed to load ({params.get('type', '?')}): {params.get('errorText', '')}",
    }


def console_messages(urls, profile: Path, *, late_ms: int = 10_000, load_timeout_s: float = 60.0) -> dict:
    """``{url: [message, ...]}``: each page's console messages of level error or warning,
    its uncaught exceptions (see :func:`_describe`) and its failed loads, from the first
    script to ``late_ms`` milliseconds after its load event, in every frame.

    - Late: after the load event the page runs on virtual time
      (``Emulation.setVirtualTimePolicy``, paused while a fetch is pending) for a budget
      of ``late_ms``; its timers fire as they would in ``late_ms`` of a reader's time,
      in a fraction of it, so an error a ``setTimeout`` logs seconds after the load is
      seen.
    - Frames: a same-process frame's console reaches the page's session; a frame in
      another process (a cross-site iframe) is attached automatically and read too.
    - Failed loads: every ``Network.loadingFailed`` of the page's requests (a missing
      iframe document or a remote one, with the network off, logs nothing otherwise).

    Each page opens in a fresh browser context (its own storage: what one page keeps in
    localStorage cannot hide another page's error), with the network off."""
    browser = DevTools(profile)
    out = {}
    try:
        for url in urls:
            ctx = browser.send("Target.createBrowserContext")["browserContextId"]
            target = browser.send("Target.createTarget", {"url": "about:blank", "browserContextId": ctx})["targetId"]
            session = browser.send("Target.attachToTarget", {"targetId": target, "flatten": True})["sessionId"]
            for domain in ("Runtime", "Log", "Page", "Network"):
                browser.send(f"{domain}.enable", session=session)
            auto = {"autoAttach": True, "waitForDebuggerOnStart": False, "flatten": True}
            browser.send("Target.setAutoAttach", auto, session=session)
            while not browser.events.empty():  # what about:blank said is not this page's
                browser.events.get_nowait()
            browser.send("Page.navigate", {"url": url}, session=session)
            sessions, requests = {session}, {}
            messages, loaded, settled, start = [], False, False, time.monotonic()
            while not settled:
                if time.monotonic() - start > load_timeout_s:
                    what = "finish loading" if not loaded else f"run {late_ms} ms past its load event"
                    messages.append({"level": "error", "source": url, "text": f"the page did not {what}"})
                    break
                try:
                    event = browser.events.get(timeout=0.1)
                except queue.Empty:
                    continue
                method, params = event.get("method"), event.get("params", {})
                if event.get("sessionId") not in sessions:
                    continue
                if method == "Target.attachedToTarget":  # a frame in another process
                    child = params["sessionId"]
                    sessions.add(child)
                    for domain in ("Runtime", "Log", "Network"):
                        browser.send(f"{domain}.enable", session=child)
                    browser.send("Target.setAutoAttach", auto, session=child)
                    browser.send("Runtime.runIfWaitingForDebugger", session=child)
                elif method == "Page.loadEventFired" and event["sessionId"] == session and not loaded:
                    loaded = True
                    policy = {"policy": "pauseIfNetworkFetchesPending", "budget": late_ms}
                    browser.send("Emulation.setVirtualTimePolicy", policy, session=session)
                elif method == "Emulation.virtualTimeBudgetExpired" and event["sessionId"] == session:
                    settled = True
                elif method == "Network.requestWillBeSent":
                    requests[params["requestId"]] = params.get("request", {}).get("url", "")
                elif method == "Network.loadingFailed":
                    failed = _failed_load(params, requests)
                    if failed:
                        messages.append(failed)
                found = _describe(event)
                if found:
                    messages.append(found)
            out[url] = messages
            browser.send("Target.closeTarget", {"targetId": target})
            browser.send("Target.disposeBrowserContext", {"browserContextId": ctx})
    finally:
        browser.close()
    return out
