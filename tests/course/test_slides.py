"""The lecture decks (course/slides.py) are reveal.js slide shows that work offline.

Every lesson is rendered into a temporary folder (about 6 s), then: no deck
references an http(s) asset, every local asset exists, the
solutions stay out unless asked for, the lessons' slide metadata makes the slides,
and headless Chromium with the network off shows a slide show (reveal.js ready,
MathJax typeset).  A stock nbconvert deck, which loads reveal.js from a CDN, is the
negative control: under the same flags it never becomes a slide show.
"""

from __future__ import annotations

import re
from pathlib import Path
from urllib.parse import urlsplit

import nbformat
import pytest

from tests._chromium import CHROMIUM, SKIP_REASON, dump_dom

ROOT = Path(__file__).resolve().parents[2]
pytest.importorskip("nbconvert")

LESSONS = sorted((ROOT / "lessons").glob("[0-9][0-9]_*.ipynb"))
# every deck is checked; Chromium opens lesson 00 and the first lesson with stored widgets
DECK_LESSONS = LESSONS
WIDGET_LESSON = next(
    (p for p in LESSONS if "application/vnd.jupyter.widget-state+json" in p.read_text(encoding="utf-8")), None
)

REMOTE = re.compile(r"^(https?:)?//", re.I)
TAG = re.compile(r"<(script|link|img|source|iframe|video|audio|embed)\b[^>]*>", re.I)
ATTR = re.compile(r"\b(src|href|data)\s*=\s*[\"']([^\"']+)[\"']", re.I)
CSS_URL = re.compile(r"(?:url\(\s*[\"']?|@import\s+[\"'])([^\"')\s]+)", re.I)
INLINE_SCRIPT = re.compile(r"<script(?P<attrs>[^>]*)>(?P<body>.*?)</script>", re.S | re.I)
JS_REMOTE = re.compile(r"[\"'`](https?:)?//[a-z0-9.-]+\.[a-z]{2,}[^\"'`]*[\"'`]", re.I)


def _slides():
    import course.slides

    return course.slides


@pytest.fixture(scope="module")
def slides():
    if not (ROOT / "book" / "node_modules" / "reveal.js").exists():
        pytest.skip("book/node_modules is missing: run `cd book && npm ci` (make does it)")
    return _slides()


@pytest.fixture(scope="module")
def decks(slides, tmp_path_factory):
    if not DECK_LESSONS:
        pytest.skip("no lessons yet")
    out = tmp_path_factory.mktemp("slides")
    assert slides.main(["--out", str(out), *map(str, DECK_LESSONS)]) == 0
    found = sorted(out.glob("*.slides.html"))
    assert [p.name for p in found] == sorted(f"{p.stem}.slides.html" for p in DECK_LESSONS)
    return out


def _asset_urls(html: str):
    for tag in TAG.finditer(html):
        text = tag.group(0)
        if tag.group(1).lower() == "link" and not re.search(
            r"rel=[\"']?(stylesheet|preload|icon|modulepreload)", text, re.I
        ):
            continue
        for _, url in ATTR.findall(text):
            yield text, url


def test_no_deck_references_the_network(decks):
    offenders = []
    for deck in [*decks.glob("*.slides.html"), decks / "index.html"]:
        html = deck.read_text(encoding="utf-8")
        offenders += [f"{deck.name}: {tag[:160]}" for tag, url in _asset_urls(html) if REMOTE.match(url)]
        for style in re.findall(r"<style[^>]*>(.*?)</style>", html, re.S | re.I):
            offenders += [f"{deck.name}: inline style {u}" for u in CSS_URL.findall(style) if REMOTE.match(u)]
        for m in INLINE_SCRIPT.finditer(html):
            if "json" in m.group("attrs").lower():
                continue  # data (widget state), not code
            offenders += [f"{deck.name}: script loads {u.group(0)}" for u in JS_REMOTE.finditer(m.group("body"))]
    for css in (decks / "vendor").rglob("*.css"):
        text = css.read_text(encoding="utf-8", errors="replace")
        offenders += [f"{css.relative_to(decks)}: {u}" for u in CSS_URL.findall(text) if REMOTE.match(u)]
    assert not offenders, "remote assets:\n" + "\n".join(offenders[:20])


def test_the_check_above_catches_a_stock_nbconvert_deck():
    """The stock deck loads reveal.js, require.js and MathJax from CDNs (our reason to exist)."""
    from nbconvert.exporters import SlidesExporter

    body, _ = SlidesExporter().from_notebook_node(nbformat.read(LESSONS[0], as_version=4))
    assert any(REMOTE.match(url) for _, url in _asset_urls(body))


def test_local_assets_exist(decks):
    missing = set()
    for deck in decks.glob("*.html"):
        for _tag, url in _asset_urls(deck.read_text(encoding="utf-8")):
            if REMOTE.match(url) or url.startswith(("data:", "#", "mailto:")):
                continue
            if not (deck.parent / urlsplit(url).path).exists():
                missing.add(f"{deck.name} -> {url}")
    # the modules the decks require() and the theme's fonts
    needed = [
        "vendor/reveal.js/dist/reveal.js",
        "vendor/reveal.js/plugin/notes/notes.js",
        "vendor/mathjax/output/chtml/fonts/woff-v2",
        "vendor/html-manager/embed-amd.js",
    ]
    missing |= {n for n in needed if not (decks / n).exists()}
    for css in (decks / "vendor").rglob("*.css"):
        for u in CSS_URL.findall(css.read_text(encoding="utf-8", errors="replace")):
            if not u.startswith(("data:", "#")) and not (css.parent / urlsplit(u).path).exists():
                missing.add(f"{css.relative_to(decks)} -> {u}")
    assert not missing, "missing local assets:\n" + "\n".join(sorted(missing))


def _solution_lines(path: Path) -> list[str]:
    nb = nbformat.read(path, as_version=4)
    lines = []
    for cell in nb.cells:
        if "solution" in cell.metadata.get("tags", []) and cell.cell_type == "code":
            body = cell.source.split("# BEGIN SOLUTION", 1)[-1].split("# END SOLUTION", 1)[0]
            lines += [ln.strip() for ln in body.splitlines() if len(ln.strip()) > 12 and not ln.strip().startswith("#")]
    return lines


def test_solutions_stay_out_unless_asked_for(decks, slides, tmp_path):
    from html import unescape

    lesson = DECK_LESSONS[0]
    lines = _solution_lines(lesson)
    assert lines, f"{lesson.name} has no solution code to test with"
    text = lambda p: unescape(re.sub(r"<[^>]+>", "", p.read_text(encoding="utf-8")))  # noqa: E731
    public = text(decks / f"{lesson.stem}.slides.html")
    assert not [ln for ln in lines if ln in public], "a solution is in the deck"
    assert slides.main(["--out", str(tmp_path), "--with-solutions", str(lesson)]) == 0
    instructor = text(tmp_path / f"{lesson.stem}.slides.html")
    assert all(ln in instructor for ln in lines), "--with-solutions shows every solution"


def test_slide_metadata_makes_the_slides(decks, slides):
    for lesson in DECK_LESSONS:
        nb = nbformat.read(lesson, as_version=4)
        # the deck's own metadata: prepare() leaves solutions out and continues long slides
        # on a sub-slide, never adding horizontal slides but the last, "Works cited"
        deck, _ = slides.prepare(nb, with_solutions=False)
        shown = deck.cells
        kinds = [slides.slide_type(c) for c in shown]
        deck_counts = slides.prepare(nb, with_solutions=False)[1]
        assert kinds.count("slide") == bool(deck_counts["works cited"]) + sum(
            slides.slide_type(c) == "slide" for c in nb.cells if "solution" not in c.metadata.get("tags", [])
        )
        expected = kinds.count("slide") + (kinds[0] != "slide")
        html = (decks / f"{lesson.stem}.slides.html").read_text(encoding="utf-8")
        slides_part = html.split('<div class="slides">', 1)[1]
        # horizontal slides are the <section>s at nesting depth 1
        depth, top = 0, 0
        for m in re.finditer(r"<(/?)section\b", slides_part):
            if m.group(1):
                depth -= 1
            else:
                depth += 1
                top += depth == 1
        assert top == expected, f"{lesson.name}: {top} slides, metadata says {expected}"
        assert top >= 2, f"{lesson.name}: a deck of one slide is a notebook dump"
        assert html.count('class="fragment"') == kinds.count("fragment")
        assert html.count('<aside class="notes"') == kinds.count("notes")


def test_a_bad_slide_type_is_refused(slides):
    nb = nbformat.v4.new_notebook(
        cells=[nbformat.v4.new_markdown_cell("# t", metadata={"slideshow": {"slide_type": "slyde"}})]
    )
    with pytest.raises(ValueError, match="slyde"):
        slides.prepare(nb, with_solutions=False)


def _dump_dom(url: str, profile: Path) -> str:
    return dump_dom(url, profile)


@pytest.mark.skipif(CHROMIUM is None, reason="Chromium is not installed (CI installs it: `apt-get install chromium`)")
def test_a_deck_is_a_slide_show_offline_in_chromium(decks, tmp_path):
    deck = decks / f"{DECK_LESSONS[0].stem}.slides.html"
    dom = _dump_dom(deck.as_uri(), tmp_path / "profile")
    reveal = re.search(r'<div class="(reveal\b[^"]*)"', dom)
    assert reveal, "no .reveal element in the rendered page"
    assert "ready" in reveal.group(1).split(), f"reveal.js did not start: class={reveal.group(1)!r}"
    assert 'data-shapelab-deck="ready"' in dom, "Reveal.initialize() did not resolve"
    assert re.search(r'<section[^>]*class="[^"]*\bpresent\b', dom), "no slide is showing"
    assert re.search(r'<section[^>]*class="[^"]*\bfuture\b', dom), "there is no next slide"
    assert "<mjx-container" in dom, "MathJax did not typeset the formulas"


@pytest.mark.skipif(CHROMIUM is None, reason="Chromium is not installed (CI installs it: `apt-get install chromium`)")
def test_widgets_render_offline_in_chromium(decks, tmp_path):
    if WIDGET_LESSON is None:
        pytest.skip("no lesson stores widget state yet")
    dom = _dump_dom((decks / f"{WIDGET_LESSON.stem}.slides.html").as_uri(), tmp_path / "profile")
    assert re.search(r'class="[^"]*\breveal\b[^"]*\bready\b', dom)
    views = re.findall(r'class="lm-Widget[^"]*\bwidget-(\w+)', dom)
    assert views, "the ipywidgets HTML manager rendered no widget from the stored state"


@pytest.mark.skipif(CHROMIUM is None, reason="Chromium is not installed (CI installs it: `apt-get install chromium`)")
def test_a_stock_cdn_deck_is_not_a_slide_show_offline(tmp_path):
    """Negative control: proves the network is really off and the test above can fail."""
    from nbconvert.exporters import SlidesExporter

    body, _ = SlidesExporter().from_notebook_node(nbformat.read(LESSONS[0], as_version=4))
    deck = tmp_path / "stock.slides.html"
    deck.write_text(body, encoding="utf-8")
    dom = _dump_dom(deck.as_uri(), tmp_path / "profile")
    reveal = re.search(r'<div class="(reveal\b[^"]*)"', dom)
    assert reveal and "ready" not in reveal.group(1).split()


@pytest.mark.parametrize("lesson", LESSONS, ids=[p.stem for p in LESSONS])
def test_figures_reach_the_deck_as_images(lesson):
    """A figure in a lesson's output must be an image: '<Figure size 800x450 ...>' on a slide is not."""
    nb = nbformat.read(lesson, as_version=4)
    textual = []
    for i, cell in enumerate(nb.cells):
        for out in cell.get("outputs", []):
            data = out.get("data", {})
            plain = str(data.get("text/plain", ""))
            if plain.startswith("<Figure size") and not any(k.startswith("image/") for k in data):
                textual.append(f"cell {i}: {plain[:60]}")
    assert not textual, (
        f"{lesson.name}: figures stored as text only (no image/png); IPython has no image formatter for a "
        f"matplotlib Figure unless the inline backend is active: {textual[:3]}"
    )


@pytest.fixture(scope="module")
def probed(decks, tmp_path_factory):
    """Every slide of every deck, stepped through once in headless Chromium at 1280 x 720
    with all fragments shown (tests/course/deck_probe.py): what the tests below measure."""
    if CHROMIUM is None:
        pytest.skip(SKIP_REASON)
    from tests.course.deck_probe import probe

    profile = tmp_path_factory.mktemp("probe") / "profile"
    return {deck.name: probe(deck, profile) for deck in sorted(decks.glob("*.slides.html"))}


@pytest.mark.skipif(CHROMIUM is None, reason=SKIP_REASON)
def test_every_slide_fits_with_all_fragments_shown(probed):
    """At 1280 x 720 with every fragment shown, no slide is taller than the slide and every
    image is whole (headless Chromium, network off)."""
    over, cut, n_slides, n_images = [], [], 0, 0
    for name, found in probed.items():
        for s in found:
            n_slides += 1
            n_images += len(s["imgEnds"])
            if s["height"] > s["H"]:
                over.append(f"{name} #{s['slide']}: {s['height']} px")
            cut += [f"{name} #{s['slide']}: an image ends at {b} px" for b in s["imgEnds"] if b > s["H"]]
    assert n_slides > 0 and n_images > 0
    assert not over, f"{len(over)} of {n_slides} slides overflow:\n" + "\n".join(over[:20])
    assert not cut, f"{len(cut)} of {n_images} images cut:\n" + "\n".join(cut[:20])


@pytest.mark.skipif(CHROMIUM is None, reason=SKIP_REASON)
def test_an_instructor_can_project_every_deck_as_it_is(probed):
    """Issue 36, on every slide of every deck as the audience sees it: no MyST role left
    as text, at most 15 lines of code (a long line wraps: it counts as the lines it
    takes, and none runs off the slide), every raster figure at least 2x its displayed
    pixels, no heading alone on a slide, and a last slide listing the works cited."""
    from tests.course.deck_probe import MAX_CODE_LINES, summary

    s = summary(probed)
    assert s["slides"] > 100 and s["raster figures"] > 20, s
    problems = {
        k: s[k]
        for k in (
            "slides with raw roles",
            f"slides with > {MAX_CODE_LINES} code lines",
            "slides with code cut at the right edge",
            "figures below 2x",
            "heading-only slides",
        )
        if s[k]
    }
    assert not problems, "\n".join(f"{k} ({len(v)}): {v[:5]}" for k, v in problems.items())
    cited = [name for name, found in probed.items() if found[-1]["title"] == "Works cited"]
    assert len(cited) >= 15, f"only {cited} end on their works cited"


def _png(width: int, height: int) -> str:
    """A base64 PNG header of that size (enough for prepare(), which reads the header)."""
    import base64
    import struct

    ihdr = struct.pack(">II", width, height) + bytes([8, 6, 0, 0, 0])
    return base64.b64encode(b"\x89PNG\r\n\x1a\n" + struct.pack(">I", 13) + b"IHDR" + ihdr + b"\0" * 4).decode()


def _md(text, t="-"):
    return nbformat.v4.new_markdown_cell(text, metadata={"slideshow": {"slide_type": t}})


def test_figures_lose_their_code_are_shown_at_half_and_long_slides_continue(slides):
    fig = nbformat.v4.new_code_cell("plot()", metadata={"slideshow": {"slide_type": "fragment"}})
    fig.outputs = [nbformat.v4.new_output("display_data", data={"image/png": _png(800, 450), "text/plain": "<Figure>"})]
    long = [_md("# Title", "slide")] + [
        _md("A paragraph of some length that fills a line of the slide. " * 2) for _ in range(30)
    ]
    nb = nbformat.v4.new_notebook(cells=[_md("# One", "slide"), _md("text"), fig, *long])
    deck, counts = slides.prepare(nb, with_solutions=False)
    f = deck.cells[2]
    # a figure that fits stays beside its sentence, without its code, at half its pixels
    assert slides.slide_type(f) == "fragment" and slides.HIDE_INPUT in f.metadata["tags"]
    assert f.outputs[0].metadata["image/png"] == {"width": 400, "height": 225}
    assert counts["figures without their code"] == 1
    kinds = [slides.slide_type(c) for c in deck.cells[3:]]
    assert kinds[0] == "slide" and kinds.count("subslide") >= 2  # the long slide continues
    assert kinds.count("slide") == 1  # no new horizontal slide
    body, _ = slides.exporter().from_notebook_node(deck, resources={"offline": {"vendor": "vendor"}})
    assert "plot()" not in body and _png(800, 450)[:20] in body


def test_a_code_wall_goes_to_the_speaker_notes_and_no_slide_has_more_than_15_lines(slides):
    wall = nbformat.v4.new_code_cell("\n".join(f"x{i} = {i}" for i in range(40)))
    wall.outputs = [nbformat.v4.new_output("stream", name="stdout", text="done\n")]
    short = [nbformat.v4.new_code_cell("\n".join(f"y{i} = {i}" for i in range(6))) for _ in range(4)]
    nb = nbformat.v4.new_notebook(cells=[_md("## Code", "slide"), wall, *short])
    deck, counts = slides.prepare(nb, with_solutions=False)
    assert slides.HIDE_INPUT in deck.cells[1].metadata["tags"]
    notes = deck.cells[2]
    assert slides.slide_type(notes) == "notes" and "x39 = 39" in notes.source
    assert counts["code moved to the notes"] == 1
    per_slide, lines = [], 0
    for c in deck.cells:
        if slides.slide_type(c) in ("skip", "notes"):
            continue
        if slides.slide_type(c) in ("slide", "subslide"):
            per_slide.append(lines)
            lines = 0
        lines += slides._shown_code_lines(c)
    per_slide.append(lines)
    assert max(per_slide) <= slides.MAX_CODE_LINES, per_slide
    body, _ = slides.exporter().from_notebook_node(deck, resources={"offline": {"vendor": "vendor"}})
    notes_html = body.split('<aside class="notes">', 1)[1].split("</aside>", 1)[0]
    assert "x39" in notes_html and "done" in body


def test_a_citation_missing_from_the_bibliography_is_named(slides, tmp_path):
    from course import build

    nb = nbformat.v4.new_notebook(cells=[_md("Shapes ([Nobody 2099](#cite-nobody2099)).", "slide")])
    with pytest.raises(ValueError, match="nobody2099"):
        slides.prepare(nb, with_solutions=False)
    nbformat.write(nb, tmp_path / "99_bad.ipynb")
    with pytest.raises(SystemExit, match="99_bad.ipynb cites nobody2099"):
        build.site_lessons(tmp_path)


def test_long_lines_count_as_the_lines_they_wrap_to(slides):
    """Ten lines of 200 characters are twenty lines on the slide: over 15, so the code
    goes to the speaker notes; the deck wraps code rather than cutting it at the edge."""
    wide = nbformat.v4.new_code_cell("\n".join(f"x{i} = '" + "a" * 195 + "'" for i in range(10)))
    nb = nbformat.v4.new_notebook(cells=[_md("## Wide", "slide"), wide])
    deck, counts = slides.prepare(nb, with_solutions=False)
    assert slides._code_lines(wide) == 20
    assert slides.HIDE_INPUT in deck.cells[1].metadata["tags"] and counts["code moved to the notes"] == 1
    assert "white-space: pre-wrap" in slides.FIGURE_CSS


def test_a_heading_alone_keeps_its_content_and_citations_become_text(slides):
    fig = nbformat.v4.new_code_cell("plot()", metadata={"slideshow": {"slide_type": "subslide"}})
    fig.outputs = [nbformat.v4.new_output("display_data", data={"image/png": _png(800, 450), "text/plain": "<Figure>"})]
    nb = nbformat.v4.new_notebook(
        cells=[
            _md("# One", "slide"),
            _md("## A figure", "subslide"),
            fig,
            _md("α-shapes ([Edelsbrunner and Mücke 1994](#cite-edelsbrunner1994)).", "slide"),
        ]
    )
    deck, counts = slides.prepare(nb, with_solutions=False)
    assert slides.slide_type(deck.cells[2]) == "-"  # on the heading's slide
    assert counts["headings kept with their content"] >= 1
    assert deck.cells[3].source == "α-shapes (Edelsbrunner and Mücke 1994)."
    last = deck.cells[-1]
    assert slides.slide_type(last) == "slide" and last.source.startswith("## Works cited")
    assert "Three-dimensional alpha shapes" in last.source
