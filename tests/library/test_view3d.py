"""shapelab.plot.view3d: an interactive 3Dmol.js view that never names the network.

The browser tests open, in headless Chromium with the network off, (1) a page of a
built Jupyter Book whose notebook shows a view (the site: 3Dmol.js from
``vendor/3dmol/``, found through the page's ``data-content_root``) and (2) a bare page
with the view's HTML as a kernel outputs it (3Dmol.js inline, as in JupyterLab); each
must draw into a WebGL canvas (pixels read back are not all one colour) and fetch
nothing.
"""

from __future__ import annotations

import json
import re
import shutil
from pathlib import Path

import nbformat
import numpy as np
import pytest

import shapelab
from shapelab.plot import view3d
from shapelab.plot import viewer3d as V
from tests._chromium import CHROMIUM, SKIP_REASON, dump_dom

ROOT = Path(__file__).resolve().parents[2]
NODE_3DMOL = ROOT / "book" / "node_modules" / "3dmol" / "build" / "3Dmol-min.js"
NO_3DMOL = "book/node_modules lacks 3dmol: run `cd book && npm ci` (make test does)"
CDN = re.compile(r"https?://|3dmol\.org|cdn|unpkg|jsdelivr", re.I)
SCRIPT_SRC = re.compile(r"<script\b[^>]*\bsrc\s*=\s*[\"']([^\"']+)", re.I)


@pytest.fixture(scope="module")
def hvr():
    s = shapelab.datasets.structure("1hvr", probe=1.4)
    F = shapelab.alpha_filtration(s.balls)
    return s, shapelab.voids(F, 0.0), shapelab.pockets(F, 0.0), shapelab.tunnels(F, 0.0)


@pytest.fixture(scope="module")
def view(hvr):
    s, voids, pockets, tunnels = hvr
    return view3d(s, (voids[:2], pockets[:3], tunnels[:1]))


# ------------------------------------------------------------------ the HTML
def test_output_names_only_local_scripts(view):
    html = view.html(library=False)
    assert not CDN.search(html), CDN.search(html)
    assert SCRIPT_SRC.findall(html) == []  # inline only; the site's copy is loaded by a relative path
    assert json.dumps(V.SITE_PATH) in html and not V.SITE_PATH.startswith(("/", "http"))


@pytest.mark.skipif(not NODE_3DMOL.exists(), reason=NO_3DMOL)
def test_inline_library_is_the_local_npm_copy(view):
    html = view.html(library=True)
    assert SCRIPT_SRC.findall(html) == []
    assert 'data-shapelab-library="3Dmol.js 2.5.5"' in html
    assert NODE_3DMOL.read_text(encoding="utf-8")[-2000:] in html
    # without the library, what is left names no host either
    assert not CDN.search(V.without_library(html))
    assert V.without_library(html) == view.html(library=False)


@pytest.mark.skipif(not NODE_3DMOL.exists(), reason=NO_3DMOL)
def test_the_library_is_inlined_once_per_process(view, monkeypatch):
    monkeypatch.setattr(V._Session, "library_sent", False)
    first, second = view._repr_html_(), view._repr_html_()
    assert "data-shapelab-library" in first and "data-shapelab-library" not in second
    assert V.without_library(first) == second


def test_library_path_honours_the_environment(tmp_path, monkeypatch):
    js = tmp_path / "3Dmol-min.js"
    js.write_text("window.$3Dmol = {};")
    monkeypatch.setenv("SHAPELAB_3DMOL_JS", str(js))
    assert V.library_path() == js


def test_features_get_distinct_colours(hvr, view):
    s, voids, pockets, tunnels = hvr
    assert voids and len(pockets) >= 3 and tunnels, "1HVR at tau=0 has voids, pockets and a tunnel"
    legend = {label: colour for colour, label, _ in view.legend}
    kinds = [legend["V1 void"], legend["P1 pocket"], legend["P2 pocket"], legend["P3 pocket"]]
    kinds += [legend["mouth"], legend["T1 tunnel"], V.FEATURE_COLORS["atom"]]
    assert len(set(kinds)) == len(kinds), legend
    assert legend["V1 void"] == legend["V2 void"]  # one colour per kind; pockets each their own
    data = view._data
    assert [p["c"] for p in data["points"]] == [
        legend[k] for k in ("V1 void", "V2 void", "P1 pocket", "P2 pocket", "P3 pocket")
    ]
    assert data["meshes"] and all(m["c"] == legend["mouth"] for m in data["meshes"])
    assert data["tunnels"][0]["c"] == legend["T1 tunnel"]
    # lining atoms carry their feature's colour; the rest are plain
    h = np.array(data["atoms"]["h"])
    assert set(np.unique(h)) <= set(range(len(data["colors"]) + 1))
    assert set(h[np.asarray(voids[0].lining)]) == {1}


def test_van_der_waals_radii_and_free_space_points(hvr, view):
    s = hvr[0]
    r = np.array(view._data["atoms"]["r"])
    np.testing.assert_allclose(r, np.asarray(s.balls.radii) - 1.4, atol=0.006)
    v1 = np.array(view._data["points"][0]["p"]).reshape(-1, 3)
    assert len(v1) > 0
    lo, hi = s.balls.centers[hvr[1][0].cells.ravel()].min(0), s.balls.centers[hvr[1][0].cells.ravel()].max(0)
    assert np.all(v1 >= lo - 0.01) and np.all(v1 <= hi + 0.01)  # inside the void's cells' box


def test_the_html_is_deterministic(hvr, view):
    s, voids, pockets, tunnels = hvr
    again = view3d(s, (voids[:2], pockets[:3], tunnels[:1]))
    assert again.id == view.id and again.html(library=False) == view.html(library=False)
    assert view3d(s, voids[:1]).id != view.id
    assert re.fullmatch(r"shapelab-view3d-[0-9a-f]{12}", view.id)


def test_accepts_balls_a_filtration_and_a_single_feature(hvr):
    s, voids, _, tunnels = hvr
    a = view3d(s.balls, voids[0])
    b = view3d(shapelab.alpha_filtration(s.balls), [tunnels[0]])
    assert a._data["atoms"]["e"] is None and a._data["style"] == "grey"
    assert b._data["tunnels"] and not b._data["points"]
    assert view3d(s)._data["style"] == "element" and view3d(s)._data["opacity"] == 1.0


def test_bad_input_names_the_argument(hvr):
    s, voids, pockets, _ = hvr
    with pytest.raises(TypeError, match="structure_or_balls"):
        view3d(np.zeros((3, 3)))
    with pytest.raises(ValueError, match="structure_or_balls"):
        view3d(shapelab.Balls([[0, 0], [1, 0]], 1.0))
    with pytest.raises(TypeError, match="features"):
        view3d(s, "voids")
    with pytest.raises(TypeError, match="features"):
        view3d(s, [voids[0], 3])
    with pytest.raises(ValueError, match="features"):
        view3d(shapelab.Balls(s.balls.centers[:10], 1.0), voids[0])
    with pytest.raises(ValueError, match="style"):
        view3d(s, style="cartoon")
    with pytest.raises(ValueError, match="opacity"):
        view3d(s, opacity=0)
    with pytest.raises(TypeError, match="opacity"):
        view3d(s, opacity="half")
    with pytest.raises(TypeError, match="width"):
        view3d(s, width=640.0)
    with pytest.raises(ValueError, match="height"):
        view3d(s, height=10)
    with pytest.raises(TypeError, match="library"):
        view3d(s, library="yes")
    with pytest.raises(TypeError, match="html"):
        V.without_library(None)


def test_the_book_build_strips_inline_copies(tmp_path, view):
    import course.build as bc

    html = view.html(library=False).replace("<div", '<script data-shapelab-library="3Dmol.js x">lib</script>\n<div', 1)
    nb = nbformat.v4.new_notebook()
    cell = nbformat.v4.new_code_cell("view3d(s)")
    cell.outputs = [nbformat.v4.new_output("display_data", data={"text/html": html, "text/plain": "View3D"})]
    nb.cells = [cell]
    nbformat.write(nb, tmp_path / "a.ipynb")
    assert bc.strip_inline_libraries(tmp_path) == 1
    out = nbformat.read(tmp_path / "a.ipynb", as_version=4).cells[0].outputs[0]["data"]["text/html"]
    assert out == view.html(library=False)
    assert bc.strip_inline_libraries(tmp_path) == 0
    assert bc.ASSETS["3dmol/build/3Dmol-min.js"] == V.SITE_PATH.removeprefix("vendor/")


# ------------------------------------------------------------------ in a browser
PROBE = """<script>window.addEventListener("load", function () { setTimeout(function () {
  // 3Dmol.js draws with WebGL (into an offscreen WebGL2 canvas when the browser has one)
  // and shows each frame in the view's <canvas>: read that canvas back and count colours
  var jobs = [];
  document.querySelectorAll(".shapelab-view3d").forEach(function (root) {
    var v = root.shapelabViewer, c = root.querySelector("canvas"), r = {viewer: !!v, canvas: !!c};
    r.note = root.querySelector(".shapelab-view3d-note").textContent;
    if (!v || !c) { jobs.push(Promise.resolve(r)); return; }
    var gl = v.renderer && v.renderer._gl;
    r.webgl = !!gl && (gl instanceof WebGLRenderingContext ||
                       (typeof WebGL2RenderingContext !== "undefined" && gl instanceof WebGL2RenderingContext));
    v.render();
    var url = c.toDataURL("image/png");
    jobs.push(new Promise(function (resolve) {
      var img = new Image();
      img.onload = function () {
        var k = document.createElement("canvas"); k.width = img.width; k.height = img.height;
        var g = k.getContext("2d"); g.drawImage(img, 0, 0);
        var px = g.getImageData(0, 0, k.width, k.height).data, seen = {};
        for (var i = 0; i < px.length; i += 4 * 7) seen[px[i] + "," + px[i + 1] + "," + px[i + 2] + "," + px[i + 3]] = 1;
        r.colours = Object.keys(seen).length; r.size = [k.width, k.height]; resolve(r);
      };
      img.onerror = function () { r.colours = -1; resolve(r); };
      img.src = url;
    }));
  });
  Promise.all(jobs).then(function (out) {
    var pre = document.createElement("pre"); pre.id = "probe";
    pre.textContent = JSON.stringify({views: out, requests: performance.getEntriesByType("resource")
      .map(function (e) { return e.name; }).filter(function (u) { return !u.startsWith("file:"); })});
    document.body.appendChild(pre);
  });
}, 1500); });</script>"""


def _probe(page: Path, profile: Path) -> dict:
    copy = page.with_name("_probe_" + page.name)  # beside the page, so its relative paths resolve
    copy.write_text(page.read_text(encoding="utf-8").replace("</body>", PROBE + "</body>"), encoding="utf-8")
    dom = dump_dom(copy.as_uri(), profile, budget_ms=10000, window=(900, 900))
    m = re.search(r'<pre id="probe"[^>]*>(.*?)</pre>', dom, re.S)
    assert m, "the probe did not run"
    return json.loads(m.group(1).replace("&quot;", '"').replace("&amp;", "&").replace("&lt;", "<").replace("&gt;", ">"))


def _assert_drawn(result: dict, n: int):
    assert result["requests"] == [], f"the page fetched {result['requests']}"
    views = result["views"]
    assert len(views) == n, views
    for r in views:
        assert r["viewer"] and r["canvas"] and r["webgl"], r
        assert r["colours"] > 5, f"the WebGL canvas is (nearly) uniform: {r}"


@pytest.mark.skipif(CHROMIUM is None, reason=SKIP_REASON)
@pytest.mark.skipif(not NODE_3DMOL.exists(), reason=NO_3DMOL)
def test_a_kernel_output_draws_offline_with_the_inline_library(tmp_path, hvr, view):
    """As in JupyterLab: no site around, the first output carries 3Dmol.js."""
    s = hvr[0]
    body = view3d(s, width=300, height=240).html(library=True) + view.html(library=False)
    page = tmp_path / "lab.html"
    page.write_text(f'<!DOCTYPE html><html><head><meta charset="utf-8"></head><body>{body}</body></html>')
    _assert_drawn(_probe(page, tmp_path / "profile"), 2)


@pytest.mark.skipif(CHROMIUM is None, reason=SKIP_REASON)
@pytest.mark.skipif(not NODE_3DMOL.exists(), reason=NO_3DMOL)
def test_a_view_without_its_library_says_so(tmp_path, view):
    page = tmp_path / "bare.html"
    page.write_text(f"<!DOCTYPE html><html><body>{view.html(library=False)}</body></html>")
    r = _probe(page, tmp_path / "profile")
    assert r["requests"] == [] and r["views"][0]["viewer"] is False
    assert "3Dmol.js is not loaded" in r["views"][0]["note"]


@pytest.fixture(scope="module")
def built_page(tmp_path_factory, hvr, view):
    """A one-page Jupyter Book (the course's own _config.yml) whose notebook shows a
    view as a kernel outputs it (library inline), built by course.build.build_book."""
    pytest.importorskip("jupyter_book")
    if not NODE_3DMOL.exists():
        pytest.skip(NO_3DMOL)
    import course.build as bc

    src = tmp_path_factory.mktemp("viewer-book")
    shutil.copy(ROOT / "book" / "_config.yml", src / "_config.yml")
    shutil.copy(ROOT / "book" / "references.bib", src / "references.bib")
    (src / "_toc.yml").write_text("format: jb-book\nroot: intro\nchapters:\n  - file: lessons/viewer\n")
    (src / "intro.md").write_text("# A viewer\n\nOne page with a 3D view.\n")
    (src / "lessons").mkdir()
    nb = nbformat.v4.new_notebook()
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3", "language": "python"}
    cell = nbformat.v4.new_code_cell("shapelab.plot.view3d(s, (voids, pockets, tunnels))")
    html = view.html(library=True)
    cell.outputs = [nbformat.v4.new_output("display_data", data={"text/html": html, "text/plain": repr(view)})]
    nb.cells = [nbformat.v4.new_markdown_cell("# Viewer"), cell]
    nbformat.write(nb, src / "lessons" / "viewer.ipynb")
    site = bc.build_book(path_output=tmp_path_factory.mktemp("viewer-site"), gallery=False, book=src)
    return site / "lessons" / "viewer.html"


@pytest.mark.skipif(CHROMIUM is None, reason=SKIP_REASON)
def test_a_built_page_draws_offline_from_the_vendored_library(built_page, tmp_path):
    html = built_page.read_text(encoding="utf-8")
    site = built_page.parent.parent
    assert "data-shapelab-library" not in html, "the site page still carries the inline library"
    assert (site / V.SITE_PATH).is_file() and (site / "vendor" / "3dmol" / "LICENSE").is_file()
    assert 'data-content_root="../"' in html
    assert not [u for u in SCRIPT_SRC.findall(html) if re.match(r"(https?:)?//", u)]
    _assert_drawn(_probe(built_page, tmp_path / "profile"), 1)


@pytest.mark.skipif(CHROMIUM is None, reason=SKIP_REASON)
@pytest.mark.skipif(not NODE_3DMOL.exists(), reason=NO_3DMOL)
def test_a_deck_draws_offline_from_its_vendor_folder_beside_require_js(tmp_path, view):
    """A deck (course/slides.py) has no data-content_root; its scripts come from
    ``vendor/``, require.js among them, whose ``define`` must not swallow 3Dmol.js."""
    import course.slides

    assert course.slides.ASSETS["3dmol/build/3Dmol-min.js"] == "3dmol/3Dmol-min.js"
    (tmp_path / "vendor" / "3dmol").mkdir(parents=True)
    shutil.copy(NODE_3DMOL, tmp_path / "vendor" / "3dmol" / "3Dmol-min.js")
    shutil.copy(ROOT / "book" / "node_modules" / "requirejs" / "require.js", tmp_path / "vendor" / "require.js")
    page = tmp_path / "deck.slides.html"
    page.write_text(
        '<!DOCTYPE html><html><head><meta charset="utf-8"><script src="vendor/require.js"></script></head>'
        f"<body>{view.html(library=False)}</body></html>"
    )
    _assert_drawn(_probe(page, tmp_path / "profile"), 1)
