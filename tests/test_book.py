"""The course site builds from the committed lessons and works offline.

This builds the whole book once (rendering the committed outputs, no execution) from a
copy of its sources in a temporary directory, then checks every page: no script, stylesheet or font comes from
http(s), every local asset a page references exists, and widget state is embedded.
"""
from __future__ import annotations

import importlib.util
import re
import shutil
from pathlib import Path
from urllib.parse import urlsplit

import pytest

ROOT = Path(__file__).resolve().parent.parent
pytest.importorskip("jupyter_book")
pytestmark = pytest.mark.book

REMOTE = re.compile(r"^(https?:)?//", re.I)
TAG = re.compile(r"<(script|link|img|source)\b[^>]*>", re.I)
ATTR = re.compile(r"\b(src|href)\s*=\s*[\"']([^\"']+)[\"']", re.I)
CSS_URL = re.compile(r"(?:url\(\s*[\"']?|@import\s+[\"'])([^\"')\s]+)", re.I)


def _build_course():
    spec = importlib.util.spec_from_file_location("build_course", ROOT / "scripts" / "build_course.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    if shutil.which("npm") is None and not (ROOT / "book" / "node_modules").exists():
        pytest.skip("npm is needed to install the book's offline JavaScript")
    bc = _build_course()
    # a private copy of the book's sources: the working tree's book/ (where `make course`
    # may be building at the same time) is left alone
    src = bc.book_copy(tmp_path_factory.mktemp("book-src"))
    bc.lessons_into_book(execute=False, book=src)
    return bc.build_book(path_output=tmp_path_factory.mktemp("book"), book=src)


def _pages(site: Path):
    """Every page a reader can open.  The theme copies its Jinja macro files
    (``_static/webpack-macros.html``) into ``_static/`` verbatim; those are not pages,
    and their ``{{ pathto(...) }}`` are template code, not links."""
    return sorted(p for p in site.rglob("*.html") if "_static" not in p.relative_to(site).parts)


def test_every_lesson_has_a_page(site):
    for nb in sorted((ROOT / "lessons").glob("[0-9][0-9]_*.ipynb")):
        assert (site / "lessons" / f"{nb.stem}.html").exists(), f"no page for {nb.name}"
    assert (site / "references.html").exists()


def test_speaker_notes_stay_off_the_site(site):
    """Speaker notes (tagged remove-cell) are for the decks; students read the site."""
    pages = [p for p in _pages(site) if "Speaker notes." in p.read_text(encoding="utf-8", errors="replace")]
    assert not pages, f"speaker notes on {[str(p.relative_to(site)) for p in pages]}"


def test_no_page_references_the_network(site):
    offenders = []
    for page in _pages(site):
        html = page.read_text(encoding="utf-8", errors="replace")
        for tag in TAG.finditer(html):
            text = tag.group(0)
            name = tag.group(1).lower()
            if name == "link" and not re.search(r"rel=[\"'](stylesheet|preload|icon|modulepreload|shortcut icon)", text, re.I):
                continue  # <link rel="canonical"/"next"> is navigation, not an asset
            for _, url in ATTR.findall(text):
                if REMOTE.match(url):
                    offenders.append(f"{page.relative_to(site)}: {text[:160]}")
        for style in re.findall(r"<style[^>]*>(.*?)</style>", html, re.S | re.I):
            offenders += [f"{page.relative_to(site)}: inline style {u}" for u in CSS_URL.findall(style) if REMOTE.match(u)]
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


def test_math_and_widgets_load_from_the_site(site):
    page = (site / "lessons" / "00_start_here.html").read_text(encoding="utf-8")
    assert "vendor/mathjax/tex-mml-chtml.js" in page
    assert "vendor/require.min.js" in page and "vendor/html-manager/embed-amd.js" in page
    assert page.count("vendor/html-manager/embed-amd.js") == 1, "the widget manager must load once"
    assert "application/vnd.jupyter.widget-state+json" in page, "widget state is embedded"
    assert (site / "vendor" / "mathjax" / "output" / "chtml" / "fonts" / "woff-v2").is_dir()
