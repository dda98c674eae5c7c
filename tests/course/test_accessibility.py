"""The course is accessible: WCAG 2.1 A and AA under axe-core, every figure described.

axe-core (``book/package.json``, pinned; ``npm ci``) runs in headless Chromium with the
network off (``tests/_chromium.py``; ``tests/_axe.py`` injects it over the DevTools
protocol), at 1280 x 720, on every page of the course site built from the committed
lessons, on every lecture deck, and on a page holding a static explorer.  The tests fail on:

- any serious or critical violation of the rules tagged wcag2a, wcag2aa, wcag21a, wcag21aa;
- a figure whose alt is missing, a file name or a generic word ("explorer frame");
- an explorer control without an accessible name, or that the keyboard cannot reach;
- a formula without MathJax's assistive MathML.

``SHAPELAB_SITE=book/_build/html`` and ``SHAPELAB_DECKS=DIR`` check a site and decks
built before (``python -m course.build --no-execute --only book``,
``python -m course.slides --out DIR``) instead of building them here.  The report, rule by
rule: ``python -m tests._axe book/_build/html DIR``.
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest

from tests import _axe
from tests._chromium import CHROMIUM, SKIP_REASON

ROOT = Path(__file__).resolve().parents[2]


# ------------------------------------------------------------ without a browser
@pytest.mark.parametrize(
    "alt, why",
    [
        (None, "no alt"),
        ("", "a generic word"),
        ("explorer frame", "a generic word"),
        ("Figure", "a generic word"),
        ("No description has been provided for this image", "a generic word"),
        ("../_images/f324d76c0a1b2c3d4e5f60718293a4b5c6d7e8f9.png", "a file name"),
        ("_images/fig23_1i.svg", "a file name"),
        ("f324d76c0a1b2c3d4e5f6071", "a file name"),
        ("The dual complex of the 13 disks at τ = 0: 13 vertices, 10 edges, 2 triangles.", None),
    ],
)
def test_a_text_alternative_is_told_from_a_file_name_or_a_generic_word(alt, why):
    assert _axe.bad_alt(alt) == why


def test_every_plot_function_describes_its_figure():
    """The description is made where the figure is made, with its numbers."""
    import numpy as np

    import shapelab as sl
    from shapelab import datasets, plot

    disks = datasets.figure_23_1()
    F = sl.alpha_filtration(disks)
    figures = {
        "disks": plot.disks(disks),
        "power_diagram": plot.power_diagram(disks),
        "dual_complex": plot.dual_complex(F),
        "filtration": plot.filtration(F),
        "persistence_diagram": plot.persistence_diagram(F),
        "barcode": plot.barcode(F),
        "betti_curve": plot.betti_curve(F),
        "pockets": plot.pockets(sl.alpha_filtration(datasets.figure_23_2()[0])),
        "hausdorff": plot.hausdorff(np.eye(2), np.eye(2) + 0.5),
    }
    K = F.complex_at(0.0)
    n = K.counts()
    assert f"{n[0]} vertices, {n[1]} edges, {n[2]} triangles" in plot.alt_text(figures["dual_complex"])
    for name, fig in figures.items():
        text = plot.alt_text(fig)
        assert _axe.bad_alt(text) is None and len(text) > 30, (name, text)
        assert "$" not in text, (name, text)  # no mathtext in words
    fig, axes = plot.new_figure(1, 2)
    plot.disks(disks, ax=axes[0])
    plot.barcode(F, ax=axes[1])
    assert plot.alt_text(fig).startswith("2 panels. Left: ")
    plot.describe(fig, "The disks and their barcode")
    assert plot.alt_text(fig) == "The disks and their barcode."


def test_descriptions_say_the_units_and_counts_the_figure_shows():
    """Regressions: a diagram in ρ said "τ"; "a mouth of 1 edges", "1 pocket region(s)";
    tunnels "labelled on the figure" with no label drawn."""
    import shapelab as sl
    from shapelab import datasets, plot

    F = sl.alpha_filtration(datasets.figure_23_1())
    text = plot.alt_text(plot.persistence_diagram(F, unit="ρ", tau=0.5))
    assert "death ρ" in text and "alive at ρ = 0.5" in text and "τ" not in text, text
    flask = sl.alpha_filtration(datasets.figure_23_2()[0])
    text = plot.alt_text(plot.pockets(flask))
    assert "a mouth of 1 edge)" in text and "1 edges" not in text, text
    text = plot.alt_text(plot.discrete_flow(flask))
    assert "(s)" not in text.split(": the discrete flow", 1)[1] and "1 pocket (" in text, text
    from types import SimpleNamespace

    from shapelab.plot.topology import _features_text

    tunnel = SimpleNamespace(cycle=[[0, 1], [1, 2], [2, 0]])
    text = _features_text(flask.balls, 0.0, [], [], [tunnel], [], "a tunnel", False, False)
    assert "a cycle of 3 edges" in text and "on the figure" not in text and "lining" not in text, text


def test_a_live_explorer_describes_its_frame_without_a_tooltip():
    """The explorer knows what its frame shows (``alt``, the static player's text), but its
    live Image carries no tooltip: the decks' offline widget manager (html-manager 1.0.15)
    draws an Image with one as an error widget.  The decks name the frame by its status line."""
    import shapelab as sl
    from shapelab import datasets, widgets

    e = widgets.alpha_explorer(sl.alpha_filtration(datasets.figure_23_1()), show_cells=False)
    assert "vertices" in e.alt and not e.image.tooltip
    e.slider.value = 1.0
    assert "τ = 1" in e.alt and not e.image.tooltip


def test_a_figure_shown_in_a_kernel_carries_its_description_as_alt():
    """The notebook output's metadata (what the book and the decks read)."""
    IPython = pytest.importorskip("IPython")
    from IPython.core.interactiveshell import InteractiveShell
    from matplotlib.figure import Figure

    from shapelab import plot

    shell = InteractiveShell.instance()
    try:
        # the PNG formatter matplotlib-inline registers in a kernel (`%matplotlib inline`)
        shell.display_formatter.formatters["image/png"].for_type(Figure, lambda fig: b"\x89PNG")
        plot.register(shell)
        fig, ax = plot.new_figure()
        ax.plot([0, 1], [1, 0])
        plot.describe(ax, "A falling line")
        data, meta = shell.display_formatter.format(fig)
        assert "image/png" in data
        assert meta["image/png"]["alt"] == "A falling line."
    finally:
        InteractiveShell.clear_instance()
    assert IPython


@pytest.mark.parametrize("formats", [[], ["--InlineBackend.figure_formats=retina"]])
def test_a_figure_in_a_real_kernel_keeps_its_alt_at_either_resolution(formats):
    """retina PNGs carry width and height as metadata: the alt must survive beside them
    (the book and the decks are built from copies executed with retina figures)."""
    nbformat = pytest.importorskip("nbformat")
    nbclient = pytest.importorskip("nbclient")
    nb = nbformat.v4.new_notebook()
    nb.cells = [
        nbformat.v4.new_code_cell("%matplotlib inline\nimport numpy as np\nfrom shapelab import Balls, plot"),
        nbformat.v4.new_code_cell("plot.disks(Balls(np.array([[0.0, 0.0], [1.0, 0.0]]), 0.7))"),
    ]
    env = {"PYTHONPATH": str(ROOT)}
    client = nbclient.NotebookClient(nb, kernel_name="python3", extra_arguments=formats, timeout=120)
    import os as _os

    old = _os.environ.get("PYTHONPATH")
    _os.environ["PYTHONPATH"] = env["PYTHONPATH"] + (_os.pathsep + old if old else "")
    try:
        client.execute()
    finally:
        if old is None:
            _os.environ.pop("PYTHONPATH", None)
        else:
            _os.environ["PYTHONPATH"] = old
    (out,) = [o for o in nb.cells[1].outputs if "image/png" in o.get("data", {})]
    md = out["metadata"]["image/png"]
    assert md["alt"].startswith("2 disks")
    if formats:
        assert md["width"] > 0 and md["height"] > 0  # retina: shown at half its pixels


# -------------------------------------------------------------- in Chromium
needs_chromium = pytest.mark.skipif(CHROMIUM is None, reason=SKIP_REASON)


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    if os.environ.get("SHAPELAB_SITE"):
        built = Path(os.environ["SHAPELAB_SITE"]).resolve()
        assert (built / "index.html").exists(), f"SHAPELAB_SITE={built} holds no built site"
        return built
    pytest.importorskip("jupyter_book")
    if not (ROOT / "book" / "node_modules").exists():
        pytest.skip("book/node_modules is missing: run `cd book && npm ci`")
    import course.build as bc

    src = bc.book_copy(tmp_path_factory.mktemp("a11y-book-src"))
    bc.lessons_into_book(execute=False, book=src)
    return bc.build_book(path_output=tmp_path_factory.mktemp("a11y-book"), book=src)


@pytest.fixture(scope="module")
def decks(tmp_path_factory):
    if os.environ.get("SHAPELAB_DECKS"):
        return Path(os.environ["SHAPELAB_DECKS"]).resolve()
    if not (ROOT / "book" / "node_modules" / "reveal.js").exists():
        pytest.skip("book/node_modules is missing: run `cd book && npm ci`")
    out = tmp_path_factory.mktemp("a11y-decks")
    env = dict(os.environ, PYTHONPATH=str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    rc = subprocess.call([sys.executable, "-m", "course.slides", "--out", str(out)], cwd=ROOT, env=env)
    assert rc == 0, "the decks failed to render"
    return out


@pytest.fixture(scope="module")
def explorer_page(tmp_path_factory):
    """A page holding two static explorers (a 2D and a 3D one), as the site shows them."""
    import shapelab as sl
    from shapelab import datasets, widgets
    from shapelab.widgets import static

    disks = datasets.figure_23_1()
    players = [
        static.static_html(widgets.alpha_explorer(sl.alpha_filtration(disks), show_cells=False), frames=4),
        static.static_html(widgets.persistence_explorer(sl.alpha_filtration(disks)), frames=3),
    ]
    page = tmp_path_factory.mktemp("a11y-explorer") / "explorers.html"
    page.write_text(
        '<!DOCTYPE html><html lang="en"><head><meta charset="utf-8"><title>Static explorers</title></head>'
        "<body><main><h1>Static explorers</h1>" + "".join(players) + "</main></body></html>",
        encoding="utf-8",
    )
    return page


@pytest.fixture(scope="module")
def results(site, decks, explorer_page, tmp_path_factory):
    if not _axe.AXE.exists():
        pytest.skip("axe-core is missing from book/node_modules: run `cd book && npm ci`")
    paths = _axe.pages(site, decks) + [explorer_page]
    t0 = time.monotonic()
    out = _axe.audit([p.resolve().as_uri() for p in paths], tmp_path_factory.mktemp("axe-profile"))
    print(f"\naxe-core on {len(paths)} pages and decks: {time.monotonic() - t0:.0f} s\n{_axe.report(out)}")
    return out


def _name(url: str) -> str:
    return "/".join(url.rsplit("/", 2)[-2:])


@needs_chromium
def test_every_page_and_deck_was_measured(results, site, decks):
    pages = [u for u in results if not u.endswith(".slides.html") and "explorers.html" not in u]
    lessons = sorted((ROOT / "lessons").glob("[0-9][0-9]_*.ipynb"))
    assert len([u for u in results if u.endswith(".slides.html")]) == len(lessons)
    assert any(u.endswith("/accessibility.html") for u in pages), "no accessibility statement page"
    assert len(pages) >= len(lessons) + 3


@needs_chromium
def test_a_violation_on_a_later_slide_of_a_deck_is_found(decks, tmp_path):
    """reveal.js hides every slide but the current one and axe judges only what is
    rendered: the probe must show each slide in turn (it once audited the first alone)."""
    import re

    deck = sorted(decks.glob("*.slides.html"))[0]
    page = deck.read_text(encoding="utf-8")
    last = [m.end() for m in re.finditer(r"<section[^>]*>", page)][-1]
    planted = tmp_path / deck.name
    planted.write_text(page[:last] + '<p><img src="planted.png"><input type="text"></p>' + page[last:], "utf-8")
    (tmp_path / "vendor").symlink_to(decks / "vendor")
    out = _axe.audit([planted.as_uri()], tmp_path / "profile")[planted.as_uri()]
    ids = {v["id"] for v in _axe.severe(out)}
    assert {"image-alt", "label"} <= ids, ids
    assert out["slides"] > 1


@needs_chromium
def test_no_serious_or_critical_violation(results):
    found = {
        _name(u): [f"{v['id']} ({v['impact']}, {v['nodes']}): {v['targets']}" for v in _axe.severe(r)]
        for u, r in results.items()
    }
    found = {k: v for k, v in found.items() if v}
    assert not found, "\n".join(f"{k}: {v}" for k, v in found.items())


@needs_chromium
def test_every_figure_says_what_it_shows(results):
    bad = {_name(u): _axe.bad_figures(r) for u, r in results.items()}
    bad = {k: v for k, v in bad.items() if v}
    assert not bad, "\n".join(f"{k}: {len(v)} figure(s), e.g. {v[0]}" for k, v in bad.items())
    assert sum(1 for r in results.values() for m in r["images"] if m["figure"]) > 100


@needs_chromium
def test_explorer_controls_are_named_and_reachable_from_the_keyboard(results):
    controls = [(_name(u), c) for u, r in results.items() for c in r["controls"]]
    assert controls, "no explorer control was found"
    unnamed = [u for u, c in controls if not c["name"]]
    assert not unnamed, f"controls without an accessible name on {sorted(set(unnamed))}"
    unreachable = [u for u, c in controls if c["tabindex"] < 0]
    assert not unreachable, f"controls the Tab key skips on {sorted(set(unreachable))}"


@needs_chromium
def test_formulas_carry_assistive_mathml(results):
    with_math = {u: r["math"] for u, r in results.items() if r["math"]["formulas"]}
    assert with_math, "no page has a formula"
    missing = {_name(u): m for u, m in with_math.items() if m["assistive"] < m["formulas"]}
    assert not missing, f"formulas without MathML for assistive technology: {missing}"


def test_axe_core_is_pinned():
    import json

    pkg = json.loads((ROOT / "book" / "package.json").read_text(encoding="utf-8"))
    version = pkg["dependencies"].get("axe-core", "")
    assert version and version[0].isdigit(), f"axe-core must be pinned to an exact version, got {version!r}"
    assert shutil.which("node") or True  # npm ci installs it; node itself is not needed
