#!/usr/bin/env python
"""Render the lessons as offline reveal.js decks.

    python -m course.slides                         # every lesson -> book/_build/slides/
    python -m course.slides --out DIR lessons/04_alpha_filtration.ipynb
    python -m course.slides --with-solutions        # instructor decks, solutions included
    python -m course.slides --src book/lessons      # render freshly executed copies
    python -m course.slides --pdf                   # and print each deck to a PDF (Chromium)

Each deck is ``DIR/<lesson>.slides.html``, made by nbconvert's SlidesExporter with a
small template of ours (``course/templates/reveal_offline``) that loads everything
from ``DIR/vendor/``: reveal.js 4, require.js, MathJax 3 and the ipywidgets HTML
manager, copied from ``book/node_modules`` (installed from the npm registry by
``npm ci``).  Nothing is fetched from a CDN, so a deck opened from the disk, offline,
is a slide show.  ``DIR/index.html`` lists the decks.

The lessons' cell metadata ``slideshow.slide_type`` (slide / subslide / fragment /
skip / notes) makes the deck.  Cells tagged ``solution`` are left out unless
``--with-solutions`` is given; then each solution is a sub-slide under its exercise.
"""

from __future__ import annotations

import argparse
import copy
import html
import shutil
import sys
import time
from collections import Counter
from pathlib import Path

import nbformat

from course import citations
from course.notebooks import is_solution, slide_type

ROOT = Path(__file__).resolve().parent.parent
NODE = ROOT / "book" / "node_modules"
TEMPLATES = Path(__file__).resolve().parent / "templates"
TEMPLATE = "reveal_offline"
DEFAULT_OUT = ROOT / "book" / "_build" / "slides"
VENDOR = "vendor"  # relative to the output folder

THEME = "white"  # reveal 4's `white` theme imports only its own local Source Sans Pro

# what a deck needs from the npm packages: source (under book/node_modules) -> target
# (under DIR/vendor).  Directories are copied without source maps.
ASSETS = {
    "requirejs/require.js": "require.js",
    "reveal.js/dist/reveal.js": "reveal.js/dist/reveal.js",
    "reveal.js/dist/reveal.css": "reveal.js/dist/reveal.css",
    f"reveal.js/dist/theme/{THEME}.css": f"reveal.js/dist/theme/{THEME}.css",
    "reveal.js/dist/theme/fonts/source-sans-pro": "reveal.js/dist/theme/fonts/source-sans-pro",
    "reveal.js/plugin/notes/notes.js": "reveal.js/plugin/notes/notes.js",
    "reveal.js/LICENSE": "reveal.js/LICENSE",
    "mathjax/es5/tex-mml-chtml.js": "mathjax/tex-mml-chtml.js",
    "mathjax/es5/input/tex/extensions": "mathjax/input/tex/extensions",
    "mathjax/es5/output/chtml/fonts/woff-v2": "mathjax/output/chtml/fonts/woff-v2",
    "mathjax/es5/ui": "mathjax/ui",
    "mathjax/es5/a11y": "mathjax/a11y",
    "mathjax/LICENSE": "mathjax/LICENSE",
    "@jupyter-widgets/html-manager/dist": "html-manager",
    # shapelab.plot.view3d loads it from here when the lesson's output does not carry it
    "3dmol/build/3Dmol-min.js": "3dmol/3Dmol-min.js",
    "3dmol/LICENSE": "3dmol/LICENSE",
}
IGNORE = shutil.ignore_patterns("*.map", "*.md", "*.d.ts", "embed.js", "libembed-amd.js", "*.LICENSE.txt")

SLIDE_TYPES = ("slide", "subslide", "fragment", "-", "skip", "notes")
HIDE_INPUT = "deck-hide-input"  # set by prepare() on figure cells; removed by the exporter


def vendor(out: Path) -> Path:
    """Copy the decks' JavaScript, CSS and fonts from book/node_modules to ``out/vendor``."""
    missing = [src for src in ASSETS if not (NODE / src).exists()]
    if missing:
        raise SystemExit(
            "book/node_modules lacks " + ", ".join(missing) + ": run `cd book && npm ci` (make does this for you)"
        )
    dest = out / VENDOR
    if dest.exists():
        shutil.rmtree(dest)
    for src, dst in ASSETS.items():
        target = dest / dst
        target.parent.mkdir(parents=True, exist_ok=True)
        if (NODE / src).is_dir():
            shutil.copytree(NODE / src, target, ignore=IGNORE)
        else:
            shutil.copy2(NODE / src, target)
    return dest


def prepare(nb, with_solutions: bool) -> tuple[nbformat.NotebookNode, Counter]:
    """A copy of ``nb`` ready for the deck, and counts of what it holds.

    Besides leaving the solutions out: citations become their author–year text and a
    last slide lists the works cited (course/citations.py); a code cell longer than
    MAX_CODE_LINES shows only its output and its code goes to the speaker notes; no
    slide holds more than MAX_CODE_LINES lines of code or more than BUDGET pixels (a
    continuation sub-slide starts); each PNG figure is shown at half its pixels
    (FIGURE_CSS); a heading alone on a slide takes the next cell with it."""
    nb = copy.deepcopy(nb)
    counts: Counter = Counter()
    cells, works = [], []
    for cell in nb.cells:
        if is_solution(cell):
            if not with_solutions:
                counts["solutions removed"] += 1
                continue
            counts["solutions shown"] += 1
            show = cell.metadata.setdefault("slideshow", {})
            if show.get("slide_type", "-") in ("skip", "-", "notes"):
                show["slide_type"] = "subslide"  # under the exercise it solves
        t = slide_type(cell)
        if t not in SLIDE_TYPES:
            raise ValueError(f"unknown slide_type {t!r} (use one of {', '.join(SLIDE_TYPES)})")
        if _drop_inline_libraries(cell):
            counts["3Dmol.js copies left to vendor/"] += 1
        if cell.cell_type == "markdown" and t != "skip":
            works += citations.cited(cell.source)
            cell.source = citations.for_deck(cell.source)
        cells.append(cell)
        if cell.cell_type != "code" or t in ("skip", "notes"):
            counts[t] += 1
            continue
        if _has_figure(cell):
            # the audience needs the figure, not the code that drew it
            _hide_input(cell)
            _size_figures(cell)
            counts["figures without their code"] += 1
        elif _code_lines(cell) > MAX_CODE_LINES:
            _hide_input(cell)
        if HIDE_INPUT in cell.metadata.get("tags", []) and _code_lines(cell) > MAX_CODE_LINES:
            # the presenter still has it: in the speaker notes (press S)
            cells.append(_notes_cell(cell))
            counts["notes"] += 1
            counts["code moved to the notes"] += 1
        counts[t] += 1
    works = list(dict.fromkeys(works))
    missing = citations.unknown(works)
    if missing:
        raise ValueError(f"cites {', '.join(missing)}, not in {citations.BIB.relative_to(ROOT)}")
    if works:
        cells.append(
            nbformat.v4.new_markdown_cell(citations.works_cited(works), metadata={"slideshow": {"slide_type": "slide"}})
        )
        counts["slide"] += 1
        counts["works cited"] = len(works)
    cells = _merge_lone_headings(cells, counts)
    nb.cells = _split_long_slides(cells, counts)
    return nb, counts


#: no slide shows more lines of code than this; longer cells show their output, and their
#: code goes to the speaker notes
MAX_CODE_LINES = 15


#: the characters of code that one line of a slide holds (1280 px wide, the code's font);
#: a longer line wraps (FIGURE_CSS), and counts as the lines the audience sees
CODE_WIDTH = 105


def _wrapped(lines: list[str]) -> int:
    return sum(max(1, -(-len(line.expandtabs(4)) // CODE_WIDTH)) for line in lines)


def _code_lines(cell) -> int:
    """Lines of a code cell's source as the slide shows them (a long line wraps)."""
    return _wrapped(cell.source.rstrip().splitlines()) if cell.cell_type == "code" else 0


def _shown_code_lines(cell) -> int:
    """Lines of code the audience sees: a code cell's input (unless hidden) and the
    fenced or indented code blocks of a markdown cell."""
    if cell.cell_type == "code":
        return 0 if HIDE_INPUT in cell.metadata.get("tags", []) else _code_lines(cell)
    if cell.cell_type != "markdown":
        return 0
    n, fence = 0, False
    for line in cell.source.splitlines():
        if line.lstrip().startswith(("```", "~~~")):
            fence = not fence
        elif fence:
            n += _wrapped([line])
    return n


def _hide_input(cell) -> None:
    tags = cell.metadata.setdefault("tags", [])
    if HIDE_INPUT not in tags:
        tags.append(HIDE_INPUT)


def _notes_cell(cell):
    code = cell.source.rstrip()
    text = f"**Code of this slide** ({_code_lines(cell)} lines, shown in the notebook):\n\n```python\n{code}\n```"
    return nbformat.v4.new_markdown_cell(text, metadata={"slideshow": {"slide_type": "notes"}})


def _is_heading_only(cell) -> bool:
    lines = [ln for ln in cell.source.splitlines() if ln.strip()]
    return cell.cell_type == "markdown" and bool(lines) and all(ln.lstrip().startswith("#") for ln in lines)


def _merge_lone_headings(cells, counts):
    """A slide that holds headings alone keeps the next shown cell (a sub-slide) with it."""
    alone = False  # the current slide has shown headings only, so far
    for cell in cells:
        t = slide_type(cell)
        if t in ("skip", "notes"):
            continue
        if t == "subslide" and alone:
            cell.metadata.setdefault("slideshow", {})["slide_type"] = "-"
            counts["headings kept with their content"] += 1
            t = "-"
        if t in ("slide", "subslide"):
            alone = _is_heading_only(cell)
        else:
            alone = alone and _is_heading_only(cell)
    return cells


def _png_size(b64) -> tuple[int, int] | None:
    """(width, height) in pixels of a base64 PNG, from its header."""
    import base64

    text = "".join(b64) if isinstance(b64, list) else b64
    head = base64.b64decode(text[:44] + "=" * (-len(text[:44]) % 4))
    if head[:8] != b"\x89PNG\r\n\x1a\n" or len(head) < 24:
        return None
    return int.from_bytes(head[16:20], "big"), int.from_bytes(head[20:24], "big")


def _size_figures(cell) -> None:
    """Each PNG figure shown at most at half its pixels: a sharp figure on the projector
    (``course.execute`` draws every lesson's figures at twice the resolution, "retina",
    so they keep their size; a lesson executed otherwise shows its figures smaller)."""
    for o in cell.get("outputs", []):
        png = o.get("data", {}).get("image/png")
        if png is None:
            continue
        size = _png_size(png)
        if size is None:
            continue
        meta = o.setdefault("metadata", {}).setdefault("image/png", {})
        w, h = size
        if not w:
            continue
        shown = min(int(meta.get("width", w)), w // 2)
        meta["width"] = shown
        meta["height"] = round(h * shown / w)


def _drop_inline_libraries(cell) -> bool:
    """Drop the inline copy of 3Dmol.js that a ``view3d`` output carries in JupyterLab:
    the deck loads it once from ``vendor/3dmol/`` (and the library's own code names
    remote URLs, for features the course never uses).  True if one was dropped."""
    from shapelab.plot.viewer3d import without_library

    dropped = False
    for out in cell.get("outputs", []):
        html = out.get("data", {}).get("text/html")
        if html is None:
            continue
        text = "".join(html) if isinstance(html, list) else html
        if "data-shapelab-library" in text:
            out["data"]["text/html"] = without_library(text)
            dropped = True
    return dropped


#: the height of a slide's content, in the deck's pixels (1280 x 720, title included),
#: above which the next cell starts a continuation sub-slide
BUDGET = 640


def _estimated_height(cell) -> int:
    """A rough height in pixels: wrapped lines of markdown, code and text output."""

    def lines(text: str, width: int) -> int:
        return sum(max(1, -(-len(line) // width)) for line in text.splitlines()) if text else 0

    if cell.cell_type == "markdown":
        head = sum(30 for line in cell.source.splitlines() if line.startswith("#"))
        return 34 * lines(cell.source, 95) + head + 20
    if cell.cell_type != "code":
        return 0
    h = 0 if HIDE_INPUT in cell.metadata.get("tags", []) else 27 * lines(cell.source, 100) + 24
    for o in cell.get("outputs", []):
        if o.get("output_type") == "stream":
            h += 25 * lines("".join(o.get("text", "")), 110)
        elif "image/png" in o.get("data", {}):
            h += int(o.get("metadata", {}).get("image/png", {}).get("height", 600)) + 20
        elif "image/svg+xml" in o.get("data", {}):
            h += 480
        elif "text/plain" in o.get("data", {}):
            h += 25 * lines("".join(o["data"]["text/plain"]), 110)
    return h


def _split_long_slides(cells, counts):
    """Start a continuation sub-slide before a cell that would push its slide past BUDGET
    pixels or MAX_CODE_LINES lines of code."""
    used = code = 0
    for cell in cells:
        t = slide_type(cell)
        if t in ("skip", "notes"):
            continue
        h, c = _estimated_height(cell), _shown_code_lines(cell)
        if t in ("slide", "subslide"):
            used, code = h, c
        elif (used + h > BUDGET and used > 0) or (code + c > MAX_CODE_LINES and code > 0):
            cell.metadata.setdefault("slideshow", {})["slide_type"] = "subslide"
            counts["continuation slides"] += 1
            used, code = h, c
        else:
            used, code = used + h, code + c
    return cells


def _has_figure(cell) -> bool:
    return any(
        o.get("output_type") in ("display_data", "execute_result")
        and ("image/png" in o.get("data", {}) or "image/svg+xml" in o.get("data", {}))
        for o in cell.get("outputs", [])
    )


def exporter():
    from nbconvert.exporters import SlidesExporter

    ex = SlidesExporter(
        template_name=TEMPLATE,
        extra_template_basedirs=[str(TEMPLATES)],
        reveal_url_prefix=f"{VENDOR}/reveal.js",
        reveal_theme=THEME,
        reveal_transition="slide",
        reveal_number="c/t",
        reveal_width="1280",
        reveal_height="720",
        # defaults that point at CDNs; the template no longer uses them, but keep them
        # local so that nothing in the page can reach for the network
        require_js_url=f"{VENDOR}/require.js",
        mathjax_url=f"{VENDOR}/mathjax/tex-mml-chtml.js",
        jquery_url="",
        mermaid_js_url="",
        widget_renderer_url=f"{VENDOR}/html-manager/embed-amd.js",
        jupyter_widgets_base_url=f"{VENDOR}/",
        font_awesome_url="",
    )
    from nbconvert.preprocessors import TagRemovePreprocessor

    ex.register_preprocessor(TagRemovePreprocessor(remove_input_tags={HIDE_INPUT}, enabled=True), enabled=True)
    return ex


#: added to each deck's <head> (the template, course/templates/reveal_offline, is left as
#: it is): code wraps instead of running off the slide's right edge (CODE_WIDTH), and
#: every raster image is shown at most at half its pixels, so that it stays sharp
#: at 1280 x 720 (a projector at 1920 x 1080 still gets 1.3 device pixels per pixel).
#: Figures of a lesson's outputs get that width from prepare() already; this also covers
#: what the page draws itself (widgets' images).  The works-cited slide is set smaller.
FIGURE_CSS = """<style id="shapelab-deck-figures">
.reveal .jp-RenderedImage img { height: auto; max-height: 600px; }
.reveal .slides section .works-cited, .reveal .slides section li .bibtex-protected { font-size: inherit; }
.reveal aside.notes pre { font-size: 0.6em; }
.reveal .jp-InputArea pre { white-space: pre-wrap; overflow-wrap: anywhere; }
</style>
<script>
(function () {
  function half(img) {
    if (!img.naturalWidth || img.dataset.shapelabHalf) { return; }
    img.dataset.shapelabHalf = "1";
    img.style.maxWidth = Math.floor(img.naturalWidth / 2) + "px";
    img.style.maxHeight = Math.floor(img.naturalHeight / 2) + "px";
    if (img.closest(".jp-RenderedImage")) { img.style.width = "auto"; img.style.height = "auto"; }
  }
  document.addEventListener("load", function (e) { if (e.target.tagName === "IMG") { half(e.target); } }, true);
  document.addEventListener("DOMContentLoaded", function () {
    document.querySelectorAll("img").forEach(function (img) { if (img.complete) { half(img); } });
  });
})();
</script>
"""


def render(path: Path, out: Path, ex, with_solutions: bool) -> tuple[Path, Counter]:
    nb = nbformat.read(path, as_version=4)
    deck, counts = prepare(nb, with_solutions)
    has_view3d = any(
        "shapelab-view3d" in "".join(out.get("data", {}).get("text/html", ""))
        for cell in deck.cells
        for out in cell.get("outputs", [])
    )
    resources = {
        "metadata": {"name": path.stem, "path": str(path.parent)},
        # 3Dmol.js is a UMD bundle that defines anonymous AMD modules: loaded after
        # require.js it breaks require's other loads (reveal.js, the widget manager), so
        # decks with a view3d load it first, as a plain script
        "offline": {"vendor": VENDOR, "view3d": has_view3d},
    }
    body, _ = ex.from_notebook_node(deck, resources=resources)
    body = body.replace("</head>", FIGURE_CSS + "</head>", 1)
    target = out / f"{path.stem}.slides.html"
    target.write_text(body, encoding="utf-8")
    return target, counts


def chromium() -> str | None:
    """The Chromium (or Chrome) on this machine, or None."""
    return next((shutil.which(n) for n in ("chromium", "chromium-browser", "google-chrome") if shutil.which(n)), None)


def pdf(deck: Path, browser: str, budget_ms: int = 30000) -> Path:
    """``deck`` printed to ``<lesson>.slides.pdf`` beside it: reveal.js's print layout
    (``?print-pdf``, one page per slide and fragment state), offline, by headless Chromium."""
    import subprocess
    import tempfile

    target = deck.with_suffix(".pdf")
    with tempfile.TemporaryDirectory() as profile:
        cmd = [
            browser,
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-dev-shm-usage",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-extensions",
            # nothing comes from the network: every connection goes to a closed port
            "--proxy-server=127.0.0.1:9",
            "--host-resolver-rules=MAP * ~NOTFOUND",
            f"--user-data-dir={profile}",
            f"--virtual-time-budget={budget_ms}",
            "--run-all-compositor-stages-before-draw",
            "--no-pdf-header-footer",
            f"--print-to-pdf={target}",
            deck.as_uri() + "?print-pdf",
        ]
        run = subprocess.run(cmd, capture_output=True, text=True, timeout=300)
    if run.returncode or not target.exists():
        raise RuntimeError(f"{deck.name}: Chromium did not print: {run.stderr[-500:]}")
    return target


def write_index(out: Path, decks: list[tuple[Path, str]]) -> Path:
    def row(p: Path, title: str) -> str:
        pdf = p.with_suffix(".pdf")
        extra = f' (<a href="{html.escape(pdf.name)}">PDF</a>)' if pdf.exists() else ""
        return f'  <li><a href="{html.escape(p.name)}">{html.escape(title)}</a>{extra}</li>'

    rows = "\n".join(row(p, title) for p, title in decks)
    page = f"""<!DOCTYPE html>
<html lang="en">
<head><meta charset="utf-8"><title>shapelab: lecture decks</title>
<style>body {{ font-family: system-ui, sans-serif; max-width: 40em; margin: 3em auto; }}</style>
</head>
<body>
<h1>shapelab: lecture decks</h1>
<p>Open a deck, then press <kbd>F</kbd> for full screen, <kbd>S</kbd> for the speaker notes,
<kbd>Esc</kbd> for the overview. Everything loads from <code>vendor/</code>, offline.</p>
<ul>
{rows}
</ul>
</body>
</html>
"""
    index = out / "index.html"
    index.write_text(page, encoding="utf-8")
    return index


def _title(nb, fallback: str) -> str:
    for cell in nb.cells:
        if cell.cell_type == "markdown":
            for line in cell.source.splitlines():
                if line.startswith("# "):
                    return line[2:].strip()
    return fallback


def _size(path: Path) -> int:
    return path.stat().st_size if path.is_file() else sum(p.stat().st_size for p in path.rglob("*") if p.is_file())


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("lessons", nargs="*", type=Path, help="notebooks (default: every lesson in --src)")
    ap.add_argument(
        "--out", type=Path, default=DEFAULT_OUT, help=f"output folder (default {DEFAULT_OUT.relative_to(ROOT)})"
    )
    ap.add_argument("--src", type=Path, default=ROOT / "lessons", help="folder of lessons (default lessons/)")
    ap.add_argument("--with-solutions", action="store_true", help="keep cells tagged 'solution'")
    ap.add_argument(
        "--pdf",
        action=argparse.BooleanOptionalAction,
        default=False,
        help="also print each deck to <lesson>.slides.pdf with headless Chromium (offline)",
    )
    args = ap.parse_args(argv)

    paths = args.lessons or sorted(args.src.glob("[0-9][0-9]_*.ipynb"))
    paths = [p for p in paths if not p.name.endswith(".failed.ipynb")]
    if not paths:
        print(f"no lessons found in {args.src}", file=sys.stderr)
        return 1
    t_all = time.perf_counter()
    out = args.out
    out.mkdir(parents=True, exist_ok=True)
    for old in [*out.glob("*.slides.html"), *out.glob("*.slides.pdf")]:
        old.unlink()
    browser = chromium() if args.pdf else None
    if args.pdf and browser is None:
        print("--pdf: Chromium is not installed (apt-get install chromium): no PDF is made", file=sys.stderr)
    vendor(out)
    ex = exporter()
    decks, failures = [], []
    for i, path in enumerate(paths, 1):
        t0 = time.perf_counter()
        print(f"[{i}/{len(paths)}] {path.name} ...", end="", flush=True)
        try:
            target, counts = render(path, out, ex, args.with_solutions)
        except Exception as exc:  # keep going, report all at the end
            print(" FAILED")
            failures.append(f"{path.name}: {type(exc).__name__}: {exc}")
            continue
        slides = counts["slide"] + counts["subslide"]
        detail = f"{counts['slide']} slides, {counts['subslide']} sub-slides, {counts['fragment']} fragments"
        if counts["solutions removed"]:
            detail += f", {counts['solutions removed']} solutions left out"
        if counts["solutions shown"]:
            detail += f", {counts['solutions shown']} solutions shown"
        if browser is not None:
            try:
                detail += f"; PDF {_size(pdf(target, browser)) / 1024:.0f} KiB"
            except Exception as exc:
                failures.append(f"{path.name}: PDF: {exc}")
        print(f" {detail}; {_size(target) / 1024:.0f} KiB, {time.perf_counter() - t0:.1f} s")
        if slides <= 1:
            print(f"    warning: {path.name} has no slide metadata, so its deck is one long slide")
        decks.append((target, _title(nbformat.read(path, as_version=4), path.stem)))
    index = write_index(out, decks)
    total = sum(_size(p) for p, _ in decks)
    print(
        f"slides: {len(decks)}/{len(paths)} decks in {time.perf_counter() - t_all:.1f} s, "
        f"{total / 2**20:.1f} MiB of decks + {_size(out / VENDOR) / 2**20:.1f} MiB of vendored JavaScript "
        f"in {out}; open {index}"
    )
    for f in failures:
        print("  " + f, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
