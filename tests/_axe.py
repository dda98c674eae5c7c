"""axe-core in headless Chromium (``tests/_chromium.py``, the network off): the WCAG 2.1
A and AA rules on a page, and what axe does not judge (an image's text alternative
that is a file name or a generic word, a form control without an accessible name).

axe-core comes from the npm registry (``book/package.json``, pinned); its script is
injected into each page over the DevTools protocol, after the page has loaded and its
formulas (MathJax) and deck (reveal.js) are ready, at 1280 x 720.

    python -m tests._axe book/_build/html DECKS_DIR     # a report, by rule and by page

is the command that measures the built site and the decks (build them first:
``python -m course.build --no-execute --only book`` and ``python -m course.slides --out DECKS_DIR``).
"""

from __future__ import annotations

import json
import re
import sys
import tempfile
import time
from collections import Counter
from pathlib import Path

from tests._chromium import DevTools

ROOT = Path(__file__).resolve().parent.parent
AXE = ROOT / "book" / "node_modules" / "axe-core" / "axe.min.js"
TAGS = ["wcag2a", "wcag2aa", "wcag21a", "wcag21aa"]
SEVERE = ("serious", "critical")

#: an image's alt text that says nothing about the figure
GENERIC = {
    "",
    "image",
    "figure",
    "plot",
    "png",
    "picture",
    "graph",
    "chart",
    "explorer frame",
    "frame",
    "output",
    "no description has been provided for this image",
    "figure without a description",
}
_FILENAME = re.compile(r"(^|[/\\])[\w.-]*\.(png|jpe?g|svg|gif|webp)$|^[0-9a-f]{16,}", re.IGNORECASE)


def bad_alt(alt: str | None) -> str | None:
    """Why ``alt`` is no text alternative for a figure (None if it is one): missing, a file
    name or path, or a generic word."""
    if alt is None:
        return "no alt"
    text = alt.strip()
    if _FILENAME.search(text):
        return "a file name"
    if text.lower().rstrip(".") in GENERIC:
        return "a generic word"
    return None


# waits for MathJax (when the page has it) and for a deck's reveal.js, then runs axe and
# lists the images and the form controls with what they say
_PROBE = """
(async () => {
  const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
  for (let i = 0; i < 100; i++) {
    const mj = window.MathJax && window.MathJax.startup && window.MathJax.startup.promise;
    const deck = document.querySelector(".reveal") ? document.documentElement.dataset.shapelabDeck === "ready" : true;
    if (deck && (!document.querySelector("script[src*=mathjax]") || mj)) { if (mj) { await mj; } break; }
    await sleep(100);
  }
  const options = {runOnly: {type: "tag", values: %(tags)s}, resultTypes: ["violations"]};
  let result;
  if (window.Reveal && window.Reveal.getSlides && document.querySelector(".reveal")) {
    // axe judges only what is rendered, and reveal.js hides every slide but the current
    // one: each slide is shown in turn, with all its fragments, and audited
    window.Reveal.configure({transition: "none", backgroundTransition: "none", fragments: false});
    const merged = new Map();
    for (const slide of window.Reveal.getSlides()) {
      const ix = window.Reveal.getIndices(slide);
      window.Reveal.slide(ix.h, ix.v);
      await sleep(30);
      for (const v of (await axe.run(document, options)).violations) {
        const seen = merged.get(v.id) || {id: v.id, impact: v.impact, help: v.help, nodes: [], keys: new Set()};
        for (const n of v.nodes) {
          const key = n.target.join(" ");
          if (!seen.keys.has(key)) { seen.keys.add(key); seen.nodes.push(n); }
        }
        merged.set(v.id, seen);
      }
    }
    window.Reveal.slide(0, 0);
    result = {violations: [...merged.values()], slides: window.Reveal.getSlides().length};
  } else {
    result = await axe.run(document, options);
  }
  const images = [...document.querySelectorAll("img")].map((m) => ({
    alt: m.getAttribute("alt"), src: (m.getAttribute("src") || "").slice(0, 80),
    decorative: m.getAttribute("role") === "presentation" || m.getAttribute("aria-hidden") === "true",
    figure: !!m.closest(".cell_output, .output, .jp-RenderedImage, .shapelab-static-explorer, .shapelab-gallery, figure"),
  }));
  const controls = [...document.querySelectorAll(".shapelab-static-explorer input, .shapelab-static-explorer button")].map((c) => {
    const by = (c.getAttribute("aria-labelledby") || "").split(" ").map((i) => document.getElementById(i)).filter(Boolean);
    return {type: c.type, tabindex: c.tabIndex,
            name: c.getAttribute("aria-label") || by.map((e) => e.textContent.trim()).join(" ")
                  || (c.labels && c.labels.length ? c.labels[0].textContent.trim() : "") || c.title || ""};
  });
  return JSON.stringify({
    violations: result.violations.map((v) => ({id: v.id, impact: v.impact, help: v.help, nodes: v.nodes.length,
                                              targets: v.nodes.slice(0, 3).map((n) => n.target.join(" "))})),
    slides: result.slides || 0, images, controls,
    math: {formulas: document.querySelectorAll("mjx-container").length,
           assistive: document.querySelectorAll("mjx-container mjx-assistive-mml math").length},
  });
})()
"""


def audit(urls, profile: Path | None = None, *, width: int = 1280, height: int = 720, timeout_s: float = 90.0) -> dict:
    """``{url: {"violations": [...], "images": [...], "controls": [...], "seconds": s}}``."""
    script = AXE.read_text(encoding="utf-8")
    probe = _PROBE % {"tags": json.dumps(TAGS)}
    tmp = None
    if profile is None:
        tmp = tempfile.TemporaryDirectory(prefix="axe-chromium-")
        profile = Path(tmp.name)
    browser = DevTools(profile)
    out = {}
    try:
        for url in urls:
            t0 = time.monotonic()
            target = browser.send("Target.createTarget", {"url": "about:blank"})["targetId"]
            session = browser.send("Target.attachToTarget", {"targetId": target, "flatten": True})["sessionId"]
            browser.send("Page.enable", session=session)
            metrics = {"width": width, "height": height, "deviceScaleFactor": 1, "mobile": False}
            browser.send("Emulation.setDeviceMetricsOverride", metrics, session=session)
            while not browser.events.empty():
                browser.events.get_nowait()
            browser.send("Page.navigate", {"url": url}, session=session)
            deadline = time.monotonic() + timeout_s
            while time.monotonic() < deadline:
                try:
                    ev = browser.events.get(timeout=0.2)
                except Exception:  # queue.Empty
                    continue
                if ev.get("sessionId") == session and ev.get("method") == "Page.loadEventFired":
                    break
            browser.send("Runtime.evaluate", {"expression": script}, session=session)
            reply = browser.send(
                "Runtime.evaluate",
                {"expression": probe, "awaitPromise": True, "returnByValue": True},
                session=session,
                timeout=timeout_s,
            )
            value = reply.get("result", {}).get("value")
            if value is None:
                raise RuntimeError(f"axe did not run on {url}: {reply}")
            out[url] = json.loads(value)
            out[url]["seconds"] = round(time.monotonic() - t0, 2)
            browser.send("Target.closeTarget", {"targetId": target})
    finally:
        browser.close()
        if tmp is not None:
            tmp.cleanup()
    return out


def severe(result: dict) -> list[dict]:
    """The serious and critical violations of one page."""
    return [v for v in result["violations"] if v["impact"] in SEVERE]


def bad_figures(result: dict) -> list[tuple[str, str]]:
    """``(alt, why)`` for each figure whose alt is no text alternative."""
    out = []
    for m in result["images"]:
        if m["decorative"] or not m["figure"]:
            continue
        why = bad_alt(m["alt"])
        if why:
            out.append((m["alt"], why))
    return out


def pages(site: Path | None, decks: Path | None) -> list[Path]:
    """Every page of the built site (not the search results or the index of names) and
    every deck."""
    found = []
    if site:
        skip = {"search.html", "genindex.html"}
        found += sorted(p for p in site.rglob("*.html") if p.name not in skip and "_static" not in p.parts)
    if decks:
        found += sorted(decks.glob("*.slides.html"))
    return found


def report(results: dict) -> str:
    rules: dict[str, Counter] = {}
    lines = []
    figures = total_figures = 0
    clean = 0
    for url, r in results.items():
        kind = "deck" if url.endswith(".slides.html") else "page"
        s = severe(r)
        clean += not s
        for v in s:
            rules.setdefault(f"{v['id']} ({v['impact']})", Counter())[kind] += 1
        bad = bad_figures(r)
        figures += len(bad)
        total_figures += sum(1 for m in r["images"] if m["figure"] and not m["decorative"])
        unnamed = [c for c in r["controls"] if not c["name"]]
        if s or bad or unnamed:
            name = url.rsplit("/", 2)[-2:]
            lines.append(
                f"  {'/'.join(name)}: {', '.join(v['id'] for v in s) or '-'}; "
                f"{len(bad)} figure(s) without a description; {len(unnamed)} unnamed control(s)"
            )
    head = [f"{len(results)} pages/decks, {clean} free of serious/critical violations"]
    head += [f"  {rule}: {c['page']} pages, {c['deck']} decks" for rule, c in sorted(rules.items())]
    head.append(f"figures whose alt is a file name or a generic word: {figures} of {total_figures}")
    return "\n".join(head + ["by page:"] + lines)


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if not argv:
        print(__doc__)
        return 2
    site = Path(argv[0]) if argv[0] != "-" else None
    decks = Path(argv[1]) if len(argv) > 1 else None
    paths = pages(site, decks)
    t0 = time.monotonic()
    results = audit([p.resolve().as_uri() for p in paths])
    print(report(results))
    print(f"({time.monotonic() - t0:.0f} s)")
    if "--json" in argv:
        Path("axe-results.json").write_text(json.dumps(results, indent=1), encoding="utf-8")
    return 0


if __name__ == "__main__":
    sys.exit(main())
