#!/usr/bin/env python
"""Render the lessons as offline reveal.js decks.

    python -m course.slides                         # every lesson -> book/_build/slides/
    python -m course.slides --out DIR lessons/03_alpha_filtration.ipynb
    python -m course.slides --with-solutions        # instructor decks, solutions included
    python -m course.slides --src book/lessons      # render freshly executed copies

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
    """A copy of ``nb`` ready for the deck, and counts of what it holds."""
    nb = copy.deepcopy(nb)
    counts: Counter = Counter()
    cells = []
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
        if cell.cell_type == "code" and t not in ("skip", "notes") and _has_figure(cell):
            # the audience needs the figure, not the code that drew it: the figure gets a
            # slide of its own (a sub-slide where it was a fragment), without the code
            cell.metadata.setdefault("tags", [])
            if HIDE_INPUT not in cell.metadata["tags"]:
                cell.metadata["tags"].append(HIDE_INPUT)
            if t in ("-", "fragment"):
                cell.metadata.setdefault("slideshow", {})["slide_type"] = "subslide"
                t = "subslide"
            counts["figures on their own slide"] += 1
        counts[t] += 1
        cells.append(cell)
    nb.cells = _split_long_slides(cells, counts)
    return nb, counts


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
            h += 600
        elif "text/plain" in o.get("data", {}):
            h += 25 * lines("".join(o["data"]["text/plain"]), 110)
    return h


def _split_long_slides(cells, counts):
    """Start a continuation sub-slide before a cell that would push its slide past BUDGET."""
    used = 0
    for cell in cells:
        t = slide_type(cell)
        if t in ("skip", "notes"):
            continue
        h = _estimated_height(cell)
        if t in ("slide", "subslide"):
            used = h
        elif used + h > BUDGET and used > 0:
            cell.metadata.setdefault("slideshow", {})["slide_type"] = "subslide"
            counts["continuation slides"] += 1
            used = h
        else:
            used += h
    return cells


def _has_figure(cell) -> bool:
    return any(
        o.get("output_type") in ("display_data", "execute_result") and "image/png" in o.get("data", {})
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
    target = out / f"{path.stem}.slides.html"
    target.write_text(body, encoding="utf-8")
    return target, counts


def write_index(out: Path, decks: list[tuple[Path, str]]) -> Path:
    rows = "\n".join(f'  <li><a href="{html.escape(p.name)}">{html.escape(title)}</a></li>' for p, title in decks)
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
    args = ap.parse_args(argv)

    paths = args.lessons or sorted(args.src.glob("[0-9][0-9]_*.ipynb"))
    paths = [p for p in paths if not p.name.endswith(".failed.ipynb")]
    if not paths:
        print(f"no lessons found in {args.src}", file=sys.stderr)
        return 1
    t_all = time.perf_counter()
    out = args.out
    out.mkdir(parents=True, exist_ok=True)
    for old in out.glob("*.slides.html"):
        old.unlink()
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
