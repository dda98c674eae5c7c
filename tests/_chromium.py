"""Headless Chromium with the network off, for the tests that open a page (decks, the
course site, the static explorers).  One place for the flags."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

CHROMIUM = next((shutil.which(n) for n in ("chromium", "chromium-browser", "google-chrome") if shutil.which(n)), None)
SKIP_REASON = "Chromium is not installed (CI installs it: `apt-get install chromium`)"


def dump_dom(url: str, profile: Path, *, budget_ms: int = 8000, window=None, console: bool = False):
    """The page's DOM after load, with the network off: every connection goes to a closed
    port and no name resolves.  With ``console``, also its console messages (a list)."""
    cmd = [
        CHROMIUM,
        "--headless",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-dev-shm-usage",
        "--disable-background-networking",
        "--no-first-run",
        "--disable-component-update",
        "--disable-sync",
        "--disable-extensions",
        f"--user-data-dir={profile}",
        "--proxy-server=127.0.0.1:9",
        "--host-resolver-rules=MAP * ~NOTFOUND",
        f"--virtual-time-budget={budget_ms}",
    ]
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
