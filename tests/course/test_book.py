"""The course site builds from the committed lessons and works offline.

This builds the whole book once from a copy of its sources in a temporary directory,
rendering the committed outputs, except lesson 04, executed as ``make course`` executes
every lesson (its explorer carries a static player).  Then it checks every page: no script,
stylesheet or font comes from http(s), every local asset a page references exists, no page
logs an error or a warning to the console (or throws) in headless Chromium with the network
off, and the explorer responds to its slider without a kernel.

``SHAPELAB_SITE=book/_build/html`` checks a site built before (``make book``) instead.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path
from urllib.parse import urlsplit

import pytest

from tests._chromium import CHROMIUM, console_messages, dump_dom

ROOT = Path(__file__).resolve().parents[2]
pytest.importorskip("jupyter_book")
pytestmark = pytest.mark.book

EXPLORER_LESSON = "04_alpha_filtration"
REMOTE = re.compile(r"^(https?:)?//", re.I)
TAG = re.compile(r"<(script|link|img|source|iframe|embed|video|audio|track)\b[^>]*>", re.I)
ATTR = re.compile(r"\b(src|href|poster)\s*=\s*[\"']([^\"']+)[\"']", re.I)
CSS_URL = re.compile(r"(?:url\(\s*[\"']?|@import\s+[\"'])([^\"')\s]+)", re.I)


def _build_course():
    import course.build

    return course.build


@pytest.fixture(scope="module")
def sources(tmp_path_factory):
    """Two copies of the book's sources with the site's lessons: the students' (solutions
    left out, the default build) and the instructors' (``--instructor``)."""
    if shutil.which("npm") is None and not (ROOT / "book" / "node_modules").exists():
        pytest.skip("npm is needed to install the book's offline JavaScript")
    bc = _build_course()
    # a private copy of the book's sources: the working tree's book/ (where `make course`
    # may be building at the same time) is left alone
    src = bc.book_copy(tmp_path_factory.mktemp("book-src"))
    bc.lessons_into_book(execute=False, book=src)
    rc = subprocess.call(
        [
            sys.executable,
            "-m",
            "course.execute",
            "--out",
            str(src / "lessons"),
            str(ROOT / "lessons" / f"{EXPLORER_LESSON}.ipynb"),
        ],
        cwd=ROOT,
    )
    assert rc == 0, f"{EXPLORER_LESSON} failed to execute for the book"
    instructor = tmp_path_factory.mktemp("book-src-instructor")
    shutil.copytree(src, instructor, dirs_exist_ok=True)
    bc.site_lessons(src / "lessons", instructor=False)
    bc.site_lessons(instructor / "lessons", instructor=True)
    return {"student": src, "instructor": instructor}


@pytest.fixture(scope="module")
def site(sources, tmp_path_factory):
    if os.environ.get("SHAPELAB_SITE"):  # a site built before, e.g. by `make book`
        built = Path(os.environ["SHAPELAB_SITE"]).resolve()
        assert (built / "index.html").exists(), f"SHAPELAB_SITE={built} holds no built site"
        return built
    return _build_course().build_book(path_output=tmp_path_factory.mktemp("book"), book=sources["student"])


@pytest.fixture(scope="module")
def instructor_site(sources, tmp_path_factory):
    """The instructors' site (python -m course.build --instructor); about 10 s more."""
    out = tmp_path_factory.mktemp("book-instructor")
    return _build_course().build_book(path_output=out, gallery=False, book=sources["instructor"])


def _pages(site: Path):
    """Every page a reader can open.  The theme copies its Jinja macro files
    (``_static/webpack-macros.html``) into ``_static/`` verbatim; those are not pages,
    and their ``{{ pathto(...) }}`` are template code, not links."""
    return sorted(p for p in site.rglob("*.html") if "_static" not in p.relative_to(site).parts)


def test_every_lesson_has_a_page(site):
    for nb in sorted((ROOT / "lessons").glob("[0-9][0-9]_*.ipynb")):
        assert (site / "lessons" / f"{nb.stem}.html").exists(), f"no page for {nb.name}"
    assert (site / "references.html").exists()


def _solution_lines(lesson: Path) -> list[str]:
    """Lines of ``lesson``'s solutions (code between the markers, model answers) that its
    students' page has no other reason to hold (the exercise's signature stays)."""
    import nbformat

    from course.student import site_notebook

    nb = nbformat.read(lesson, as_version=4)
    page = "\n".join(c.source for c in site_notebook(nb)[0].cells)
    lines = []
    for cell in nb.cells:
        if "solution" not in cell.metadata.get("tags", []):
            continue
        if cell.cell_type == "code":
            body = "\n".join(re.findall(r"# BEGIN SOLUTION\n(.*?)# END SOLUTION", cell.source, re.S))
            found = [ln.strip() for ln in body.splitlines() if not ln.strip().startswith("#")]
            found = [ln for ln in found if len(ln) > 20]
        else:  # a model answer: the runs of plain words between its markup and formulas
            found = [seg.strip() for seg in re.split(r"\$[^$]*\$|\(#cite-[^)]*\)|[*`_\\\[\]{}<>|]", cell.source)]
            found = [seg for seg in found if len(seg) > 40]
        lines += [" ".join(ln.split()) for ln in found if ln not in page]
    return lines


def _text(page: Path) -> str:
    from html import unescape

    text = unescape(re.sub(r"<[^>]+>", "", page.read_text(encoding="utf-8", errors="replace")))
    # MyST's smart quotes: Horn's -> Horn’s
    return " ".join(text.translate(str.maketrans("‘’“”", "''\"\"")).split())


def test_no_solution_on_the_students_site_and_every_one_on_the_instructors(site, instructor_site):
    """The default site publishes no solution (left out, not folded: a toggle still puts
    the answer in the page); the instructors' build shows them all."""
    shown, missing, n = [], [], 0
    for lesson in sorted((ROOT / "lessons").glob("[0-9][0-9]_*.ipynb")):
        lines = _solution_lines(lesson)
        n += len(lines)
        student = _text(site / "lessons" / f"{lesson.stem}.html")
        instructor = _text(instructor_site / "lessons" / f"{lesson.stem}.html")
        shown += [f"{lesson.stem}: {ln[:80]}" for ln in lines if ln in student]
        missing += [f"{lesson.stem}: {ln[:80]}" for ln in lines if ln not in instructor]
    assert n > 50, "the solutions' lines are no longer found"
    assert not shown, f"{len(shown)} solution lines on the students' site:\n" + "\n".join(shown[:10])
    assert not missing, f"{len(missing)} solution lines missing from the instructors' site:\n" + "\n".join(missing[:10])


RAW_ROLE = re.compile(r"\{[a-z:-]+\}(?:`|<code|<span class=\"pre\">)")


def test_no_page_shows_a_raw_role_and_citations_link_to_the_references(site):
    raw, broken = [], []
    ids = set(re.findall(r'id="([^"]+)"', (site / "references.html").read_text(encoding="utf-8")))
    for page in _pages(site):
        html = page.read_text(encoding="utf-8", errors="replace")
        body = re.sub(r"<script\b.*?</script>", "", html, flags=re.S)
        raw += [f"{page.relative_to(site)}: {m.group(0)}" for m in RAW_ROLE.finditer(body)]
        broken += [f"{page.name} -> #{a}" for a in re.findall(r'references\.html#([\w-]+)"', html) if a not in ids]
    assert not raw, "raw MyST roles on the site:\n" + "\n".join(raw[:10])
    assert not broken, "citations that lead nowhere:\n" + "\n".join(broken[:10])
    linked = _text(site / "lessons" / f"{EXPLORER_LESSON}.html")
    assert "Edelsbrunner and Mücke 1994" in linked


def test_speaker_notes_stay_off_the_site(site):
    """Speaker notes (tagged remove-cell) are for the decks; students read the site."""
    pages = [p for p in _pages(site) if "Speaker notes." in p.read_text(encoding="utf-8", errors="replace")]
    assert not pages, f"speaker notes on {[str(p.relative_to(site)) for p in pages]}"
    # nor in the notebooks the pages' download button hands out (lesson 04's notes say
    # the answer to its exercise on attached edges)
    sources = sorted((site / "_sources").rglob("*.ipynb"))
    assert sources, "the site no longer copies its notebooks to _sources/: update this test"
    given = [p for p in sources if "Speaker notes." in p.read_text(encoding="utf-8", errors="replace")]
    assert not given, f"speaker notes in {[str(p.relative_to(site)) for p in given]}"


def test_no_page_references_the_network(site):
    offenders = []
    for page in _pages(site):
        html = page.read_text(encoding="utf-8", errors="replace")
        for tag in TAG.finditer(html):
            text = tag.group(0)
            name = tag.group(1).lower()
            if name == "link" and not re.search(
                r"rel=[\"'](stylesheet|preload|icon|modulepreload|shortcut icon)", text, re.I
            ):
                continue  # <link rel="canonical"/"next"> is navigation, not an asset
            for _, url in ATTR.findall(text):
                if REMOTE.match(url):
                    offenders.append(f"{page.relative_to(site)}: {text[:160]}")
        for style in re.findall(r"<style[^>]*>(.*?)</style>", html, re.S | re.I):
            offenders += [
                f"{page.relative_to(site)}: inline style {u}" for u in CSS_URL.findall(style) if REMOTE.match(u)
            ]
    for css in site.rglob("*.css"):
        text = css.read_text(encoding="utf-8", errors="replace")
        offenders += [f"{css.relative_to(site)}: {u}" for u in CSS_URL.findall(text) if REMOTE.match(u)]
    assert not offenders, "remote assets:\n" + "\n".join(offenders[:20])


def test_local_assets_exist(site):
    missing = set()
    for page in _pages(site):
        html = page.read_text(encoding="utf-8", errors="replace")
        for tag in TAG.finditer(html):
            if tag.group(1).lower() == "link" and "stylesheet" not in tag.group(0).lower():
                continue
            for _, url in ATTR.findall(tag.group(0)):
                if REMOTE.match(url) or url.startswith(("data:", "#", "mailto:")):
                    continue
                target = (page.parent / urlsplit(url).path).resolve()
                if not target.exists():
                    missing.add(f"{page.relative_to(site)} -> {url}")
    assert not missing, "missing local assets:\n" + "\n".join(sorted(missing)[:20])


def test_math_loads_from_the_site_and_nothing_else_is_fetched(site):
    page = (site / "lessons" / "00_start_here.html").read_text(encoding="utf-8")
    assert "vendor/mathjax/tex-mml-chtml.js" in page
    assert (site / "vendor" / "mathjax" / "output" / "chtml" / "fonts" / "woff-v2").is_dir()
    # shapelab.plot.view3d's pages load 3Dmol.js from here (tests/library/test_view3d.py opens one)
    assert (site / "vendor" / "3dmol" / "3Dmol-min.js").is_file()
    for p in _pages(site):
        html = p.read_text(encoding="utf-8", errors="replace")
        # no live-code (thebe) or widget-manager scripts: nothing on a static page could use them
        assert "unpkg.com" not in html and "THEBE_JS_URL" not in html, p.name
        assert "embed-amd.js" not in html and "widget-state+json" not in html, p.name


def _chromium(url: str, profile: Path) -> tuple[str, list[str]]:
    """The page's DOM after load, and its console messages, with the network off."""
    return dump_dom(url, profile, budget_ms=6000, console=True)


NEEDS_CHROMIUM = pytest.mark.skipif(
    CHROMIUM is None, reason="Chromium is not installed (CI installs it: `apt-get install chromium`)"
)


@NEEDS_CHROMIUM
def test_no_page_logs_an_error_or_a_warning_to_the_console(site, tmp_path):
    """Every page, opened as a reader opens it (a fresh profile, the network off), logs
    no console message of level error or warning and throws no uncaught exception: the
    page's and the theme's scripts (console.error/warn/assert), the browser's own
    messages (a failed load, a refused script, a deprecation), unhandled rejections and
    loads that fail without a console message (a frame's document), in every frame, up to
    10 s after the load event (tests/_chromium.py, over the DevTools protocol)."""
    pages = _pages(site)
    found = console_messages([p.as_uri() for p in pages], tmp_path / "profile")
    bad = {}
    for page in pages:
        for m in found[page.as_uri()]:
            source = m["source"].split("?")[0].replace(site.as_uri() + "/", "")
            bad.setdefault(str(page.relative_to(site)), []).append(f"[{m['level']}] {m['text'][:200]} ({source})")
    assert not bad, f"console errors and warnings on {len(bad)} of {len(pages)} pages:\n" + "\n".join(
        f"{k}: {v[:3]}" for k, v in sorted(bad.items())
    )


PROBLEMS_PAGE = """<!doctype html><html><head><title>t</title>
<script>console.error("an error"); console.warn("a warning"); console.assert(false, "an assertion");
console.log("a log line"); console.info("an info line");</script>
<img src="missing.png">
<script>setTimeout(function () { Promise.reject(new Error("a rejection")); }, 10);</script>
<script>window.addEventListener("load", function () { undefinedFunction(); });</script>
<script>window.addEventListener("load", function () {
  setTimeout(function () { console.error("a late error"); }, 5000); });</script>
</head><body>text
<iframe src="missing-frame.html"></iframe>
<iframe src="https://example.invalid/embed"></iframe>
<iframe srcdoc="<script>console.warn('a warning in a frame')</script>"></iframe>
</body></html>"""


@NEEDS_CHROMIUM
def test_the_console_check_sees_errors_warnings_and_exceptions(tmp_path):
    """The check itself can fail: on a page that logs each kind of problem once, it
    finds every one and nothing that is only a log or info line; a quiet page gives none.
    Among them, what a check that stops soon after the load event or reads only the
    console misses: an error logged 5 s after the load event, a warning from a frame, a
    frame whose document is missing and one whose document is remote (neither logs
    anything to the console)."""
    bad, quiet = tmp_path / "bad.html", tmp_path / "quiet.html"
    bad.write_text(PROBLEMS_PAGE, encoding="utf-8")
    quiet.write_text(
        "<!doctype html><html><head><title>q</title></head><body><script>console.log('hi')</script></body></html>"
    )
    found = console_messages([bad.as_uri(), quiet.as_uri()], tmp_path / "profile")
    text = "\n".join(f"[{m['level']}] {m['text']}" for m in found[bad.as_uri()])
    for expected in (
        "[error] an error",
        "[warning] a warning",
        "[assert] an assertion",
        "Failed to load resource",
        "a rejection",
        "undefinedFunction is not defined",
        "a late error",  # 5 s after the load event
        "a warning in a frame",
        "failed to load (Document)",  # the missing frame, and the remote one
    ):
        assert expected in text, f"{expected!r} not seen in:\n{text}"
    assert "a log line" not in text and "an info line" not in text
    frames = [m["source"] for m in found[bad.as_uri()] if "failed to load (Document)" in m["text"]]
    assert any(u.endswith("missing-frame.html") for u in frames) and "https://example.invalid/embed" in frames, frames
    assert found[quiet.as_uri()] == []


@NEEDS_CHROMIUM
def test_the_explorer_responds_on_the_site_without_a_kernel(site, tmp_path):
    page = site / "lessons" / f"{EXPLORER_LESSON}.html"
    html = page.read_text(encoding="utf-8")
    assert "shapelab-static-explorer" in html, "the executed lesson's explorer has no static player"
    probe = """<script>window.addEventListener("load", function () {
      var out = [];
      document.querySelectorAll(".shapelab-static-explorer").forEach(function (root) {
        var i = root.querySelector("input[type=range]"), m = root.querySelector("img"),
            s = root.querySelector(".slx-status");
        var before = [m.src, s.innerHTML];
        i.value = (+i.value === +i.max) ? i.min : i.max;
        i.dispatchEvent(new Event("input"));
        out.push({frame: m.src !== before[0], status: s.innerHTML !== before[1]});
      });
      var pre = document.createElement("pre"); pre.id = "probe";
      pre.textContent = JSON.stringify({players: out, requests: performance.getEntriesByType("resource")
        .map(function (e) { return e.name; }).filter(function (u) { return !u.startsWith("file:"); })});
      document.body.appendChild(pre);
    });</script>"""
    copy = page.with_name("_probe.html")  # beside the page, so its relative assets resolve
    copy.write_text(html.replace("</body>", probe + "</body>"), encoding="utf-8")
    try:
        dom, _ = _chromium(copy.as_uri(), tmp_path / "profile")
    finally:
        copy.unlink()
    m = re.search(r'<pre id="probe"[^>]*>(.*?)</pre>', dom, re.S)
    assert m, "the probe did not run"
    result = json.loads(m.group(1).replace("&quot;", '"').replace("&amp;", "&"))
    assert result["requests"] == [], f"the page fetched {result['requests']}"
    assert result["players"] and all(p["frame"] and p["status"] for p in result["players"]), result
