"""Step through every slide of the lecture decks in headless Chromium (network off) and
measure what an audience sees: raw MyST roles, lines of code, figures' pixels, slides
that hold a heading alone.

    python -m tests.course.deck_probe DIR           # every DIR/*.slides.html: counts
    python -m tests.course.deck_probe DIR --list    # and every offending slide

Used by tests/course/test_decks.py; the command line reproduces the counts of issue 36.
"""

from __future__ import annotations

import argparse
import json
import re
import sys
import tempfile
from pathlib import Path

from tests._chromium import CHROMIUM, dump_dom

#: a MyST role left as text, e.g. {cite}`key` or {cite:p}`key`
RAW_ROLE = re.compile(r"\{[a-z:-]+\}`")
MAX_CODE_LINES = 15

PROBE = r"""<script>
(function wait() {
  if (!(window.Reveal && Reveal.isReady && Reveal.isReady()
        && document.documentElement.getAttribute("data-shapelab-deck") === "ready")) { return setTimeout(wait, 100); }
  Reveal.configure({transition: "none", backgroundTransition: "none"});
  setTimeout(function () {
    var out = [];
    function visible(el) { return !el.closest("aside.notes"); }
    Reveal.getSlides().forEach(function (s) {
      var ix = Reveal.getIndices(s); Reveal.slide(ix.h, ix.v);
      s.querySelectorAll(".fragment").forEach(function (f) { f.classList.add("visible"); });
      var clone = s.cloneNode(true);
      clone.querySelectorAll("aside.notes, script, style, mjx-container, pre, .jp-OutputArea").forEach(function (n) { n.remove(); });
      var text = clone.textContent;
      var code = 0, cut = 0;
      s.querySelectorAll("pre").forEach(function (p) {
        if (!visible(p) || p.closest(".jp-OutputArea, .output_area, .jp-OutputArea-output")) { return; }
        // the lines as shown: a long line that wraps is two; one cut off at the right edge
        // (overflow) is reported apart, the audience cannot read it
        var cs = getComputedStyle(p), lh = parseFloat(cs.lineHeight) || 1.2 * parseFloat(cs.fontSize);
        var pad = parseFloat(cs.paddingTop) + parseFloat(cs.paddingBottom);
        var shown = Math.round((p.clientHeight - pad) / lh);
        code += Math.max(shown, p.textContent.replace(/\n+$/, "").split("\n").length);
        if (p.scrollWidth > p.clientWidth + 1) { cut += 1; }
      });
      var imgs = Array.from(s.querySelectorAll("img")).filter(visible).map(function (im) {
        var r = im.getBoundingClientRect();
        return {nw: im.naturalWidth, nh: im.naturalHeight, w: r.width * devicePixelRatio, h: r.height * devicePixelRatio,
                src: im.src.slice(0, 30)};
      }).filter(function (i) { return i.w > 0 && i.nw > 0; });
      var bare = s.cloneNode(true);
      bare.querySelectorAll("aside.notes, script, style, h1, h2, h3, h4, h5, h6").forEach(function (n) { n.remove(); });
      var heads = s.querySelectorAll("h1,h2,h3,h4,h5,h6").length;
      var rest = bare.textContent.replace(/[\s¶#]+/g, "");
      var media = bare.querySelectorAll("img, svg, table, pre, canvas, iframe, mjx-container, .jp-OutputArea-output, .widget-area").length;
      var scale = Reveal.getScale(), top = s.getBoundingClientRect().top, bottom = 0;
      Array.from(s.children).forEach(function (c) {
        var r = c.getBoundingClientRect(); if (r.height > 0) { bottom = Math.max(bottom, r.bottom); } });
      var ends = Array.from(s.querySelectorAll("img")).map(function (im) {
        return Math.round((im.getBoundingClientRect().bottom - top) / scale); });
      var title = (s.querySelector("h1,h2,h3") || {}).textContent || "";
      out.push({slide: ix.h + "/" + ix.v, title: title.replace("¶", "").trim().slice(0, 60),
                roles: (text.match(/\{[a-z:-]+\}`?[A-Za-z0-9_]+/g) || []), code: code, cut: cut, imgs: imgs,
                headingOnly: heads > 0 && rest.length === 0 && media === 0,
                height: Math.round((bottom - top) / scale), imgEnds: ends, H: Reveal.getConfig().height});
    });
    var pre = document.createElement("pre"); pre.id = "deckprobe";
    pre.textContent = JSON.stringify(out); document.body.appendChild(pre);
  }, 1500);
})();
</script>"""


def probe(deck: Path, profile: Path) -> list[dict]:
    """Every slide of ``deck`` (all fragments shown) at 1280 x 720: its raw roles, lines of
    code, images (natural and displayed pixels) and whether it is a heading alone."""
    copy = deck.with_name("_probe_" + deck.name)  # beside the deck: vendor/ resolves
    copy.write_text(deck.read_text(encoding="utf-8").replace("</body>", PROBE + "</body>"), encoding="utf-8")
    try:
        dom = dump_dom(copy.as_uri(), profile, budget_ms=40000, window=(1280, 720))
    finally:
        copy.unlink()
    m = re.search(r'<pre id="deckprobe"[^>]*>(.*?)</pre>', dom, re.S)
    if not m:
        raise RuntimeError(f"{deck.name}: the probe did not run")
    text = m.group(1).replace("&quot;", '"').replace("&lt;", "<").replace("&gt;", ">").replace("&amp;", "&")
    return json.loads(text)


def summary(decks: dict[str, list[dict]]) -> dict:
    slides = [(name, s) for name, ss in decks.items() for s in ss]
    imgs = [(name, s, i) for name, s in slides for i in s["imgs"]]
    ratio = lambda i: min(i["nw"] / i["w"], i["nh"] / i["h"]) if i["h"] else i["nw"] / i["w"]  # noqa: E731
    return {
        "decks": len(decks),
        "slides": len(slides),
        "decks with raw roles": len({n for n, s in slides if s["roles"]}),
        "slides with raw roles": [f"{n} #{s['slide']}: {s['roles'][:2]}" for n, s in slides if s["roles"]],
        f"slides with > {MAX_CODE_LINES} code lines": [
            f"{n} #{s['slide']} ({s['title']}): {s['code']} lines" for n, s in slides if s["code"] > MAX_CODE_LINES
        ],
        "slides with code cut at the right edge": [
            f"{n} #{s['slide']} ({s['title']})" for n, s in slides if s.get("cut")
        ],
        "raster figures": len(imgs),
        "figures below 2x": [
            f"{n} #{s['slide']}: {i['nw']}x{i['nh']} shown at {i['w']:.0f}x{i['h']:.0f}"
            for n, s, i in imgs
            if ratio(i) < 2 - 1e-6
        ],
        "figures below 1.5x": [f"{n} #{s['slide']}" for n, s, i in imgs if ratio(i) < 1.5 - 1e-6],
        "heading-only slides": [f"{n} #{s['slide']} ({s['title']})" for n, s in slides if s["headingOnly"]],
    }


def probe_all(folder: Path) -> dict[str, list[dict]]:
    with tempfile.TemporaryDirectory() as tmp:
        return {d.name: probe(d, Path(tmp) / "profile") for d in sorted(folder.glob("*.slides.html"))}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("folder", type=Path)
    ap.add_argument("--list", action="store_true", help="list every offending slide")
    args = ap.parse_args(argv)
    if CHROMIUM is None:
        print("Chromium is not installed", file=sys.stderr)
        return 2
    s = summary(probe_all(args.folder))
    for key, value in s.items():
        if isinstance(value, list):
            print(f"{key}: {len(value)}")
            if args.list:
                for v in value:
                    print(f"    {v}")
        else:
            print(f"{key}: {value}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
