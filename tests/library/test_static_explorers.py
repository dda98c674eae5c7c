"""Explorers on the static site: precomputed frames swapped by plain JavaScript.

Each of the seven explorers is built on a small example; with ``SHAPELAB_STATIC_EXPLORERS=1``
its display data carries a player whose frames and status lines change along the main
control, which names no URL and leaves the explorer where it was.  Headless Chromium, with
the network off, moves every player's slider and sees the frame and the status change.
"""

from __future__ import annotations

import base64
import json
import re

import numpy as np
import pytest

import shapelab as sl
from shapelab import datasets, widgets
from shapelab.widgets import static
from tests._chromium import CHROMIUM, dump_dom

FRAMES = 5
DATA = re.compile(r'<script type="application/json" class="slx-data">(.*?)</script>', re.S)


def _explorers():
    disks = datasets.figure_23_1()
    F2 = sl.alpha_filtration(disks)
    tube = datasets.nanotube(6, 6, length=6.0)
    rng = np.random.default_rng(0)
    source = rng.normal(size=(40, 3)) * [2.0, 1.0, 0.5]
    theta = 0.4
    rot = np.array([[np.cos(theta), -np.sin(theta), 0.0], [np.sin(theta), np.cos(theta), 0.0], [0.0, 0.0, 1.0]])
    target = source @ rot.T + [0.3, -0.2, 0.1]
    out = {
        "alpha": lambda: widgets.alpha_explorer(F2, show_cells=False),
        "power": lambda: widgets.power_explorer(disks, index=0),
        "complex3d": lambda: widgets.complex3d_explorer(sl.alpha_filtration(tube), resolution=4),
        "pocket": lambda: widgets.pocket_explorer(sl.alpha_filtration(datasets.figure_23_2()[0])),
        "persistence": lambda: widgets.persistence_explorer(F2),
        "icp": lambda: widgets.icp_explorer(source, target, max_iter=6),
    }
    t = np.linspace(0, 2 * np.pi, 61)
    blob = np.c_[(1 + 0.3 * np.cos(3 * t)) * np.cos(t), (1 + 0.3 * np.cos(3 * t)) * np.sin(t)]
    blob[-1] = blob[0]  # closed exactly
    out["critical"] = lambda: widgets.critical_points_explorer(blob)
    return out


EXPLORERS = _explorers()


@pytest.fixture(scope="module")
def players():
    """name -> (explorer, html), rendered once with the static player switched on."""
    mp = pytest.MonkeyPatch()
    mp.setenv("SHAPELAB_STATIC_EXPLORERS", "1")
    try:
        out = {}
        for name, make in EXPLORERS.items():
            w = make()
            out[name] = (w, static.static_html(w, frames=FRAMES))
        return out
    finally:
        mp.undo()


def _payload(html: str) -> dict:
    m = DATA.search(html)
    assert m, "the player carries no frame data"
    return json.loads(m.group(1).replace("<\\/", "</"))


@pytest.mark.parametrize("name", sorted(EXPLORERS))
def test_the_player_has_changing_frames_and_status(players, name):
    w, html = players[name]
    data = _payload(html)
    n = len(data["frames"])
    assert 2 <= n <= FRAMES + 1
    assert len(data["status"]) == len(data["readout"]) == n
    pngs = [base64.b64decode(f) for f in data["frames"]]
    assert all(p.startswith(b"\x89PNG") for p in pngs)
    assert len(set(pngs)) >= 2, "every frame is the same picture"
    assert len(set(data["readout"])) == n, "two frames share a control value"
    if name != "critical":  # its status names the viewpoint's critical points, which may repeat
        assert len(set(data["status"])) >= 2, "the status line never changes"


@pytest.mark.parametrize("name", sorted(EXPLORERS))
def test_every_frame_says_what_it_shows_and_the_control_is_labelled(players, name):
    """WCAG 2.1 (issue 35): each frame's alt is the figure's own description (what is
    drawn, at which value), never a generic word; the range input has a visible label and
    announces the value it stands for."""
    from tests._axe import bad_alt

    w, html = players[name]
    data = _payload(html)
    assert len(data["alt"]) == len(data["frames"])
    for alt in data["alt"]:
        assert bad_alt(alt) is None, alt
        assert len(alt) > 25, f"too short to say what the frame shows: {alt!r}"
    assert len(set(data["alt"])) >= 2 or name == "critical", "the frames' descriptions never change"
    first = re.search(r'<img alt="([^"]*)"', html).group(1)
    start = data["readout"].index(re.search(r"<output[^>]*>([^<]*)</output>", html).group(1))
    assert first == __import__("html").escape(data["alt"][start])
    uid = re.search(r'<input id="([^"]+)"', html).group(1)
    assert f'<label for="{uid}"' in html
    assert re.search(r'<input[^>]+aria-valuetext="[^"]+"', html)


@pytest.mark.parametrize("name", sorted(EXPLORERS))
def test_the_player_names_no_url_and_leaves_the_explorer_as_it_was(players, name):
    w, html = players[name]
    assert not re.search(r"https?://", html)
    control = static._main_control(w)
    before = control.value
    again = static.static_html(w, frames=FRAMES)
    assert control.value == before
    assert again == html, "the player is not deterministic"


def test_the_player_appears_only_when_asked(monkeypatch):
    w = EXPLORERS["alpha"]()
    monkeypatch.delenv("SHAPELAB_STATIC_EXPLORERS", raising=False)
    bundle = w._repr_mimebundle_()
    assert "text/html" not in bundle and "application/vnd.jupyter.widget-view+json" in bundle
    monkeypatch.setenv("SHAPELAB_STATIC_EXPLORERS", "1")
    bundle = w._repr_mimebundle_()
    assert "application/vnd.jupyter.widget-view+json" in bundle
    assert "slx-data" in bundle["text/html"]


def test_control_values_cover_the_range_and_keep_the_current_value():
    import ipywidgets as W

    s = W.FloatSlider(value=0.37, min=-1.0, max=2.0, step=0.01)
    values = static.control_values(s, frames=7)
    assert values[0] == pytest.approx(-1.0) and values[-1] == pytest.approx(2.0)
    assert 0.37 in values and values == sorted(values) and len(values) == 7
    i = W.IntSlider(value=7, min=0, max=40)
    values = static.control_values(i, frames=5)
    assert values[0] == 0 and values[-1] == 40 and 7 in values
    with pytest.raises(ValueError, match="frames"):
        static.control_values(s, frames=1)


def test_frames_keep_their_aspect_ratio():
    """The frame widget bounds only its width: the height follows the picture."""
    for make in EXPLORERS.values():
        layout = make().image.layout
        assert layout.height == "auto" and layout.width == "100%" and layout.max_width.endswith("px")


@pytest.mark.skipif(CHROMIUM is None, reason="Chromium is not installed (CI installs it: `apt-get install chromium`)")
def test_every_player_responds_in_chromium_with_the_network_off(players, tmp_path):
    body = "".join(f'<section data-name="{name}">{html}</section>' for name, (_, html) in sorted(players.items()))
    probe = """
<script>
window.addEventListener("load", function () {
  var out = {};
  document.querySelectorAll("section[data-name]").forEach(function (sec) {
    var i = sec.querySelector("input[type=range]"), m = sec.querySelector("img"),
        s = sec.querySelector(".slx-status"), o = sec.querySelector("output");
    var before = [m.src, s.innerHTML, o.textContent];
    i.value = (+i.value === +i.max) ? i.min : i.max;
    i.dispatchEvent(new Event("input"));
    out[sec.dataset.name] = {frame: m.src !== before[0], status: s.innerHTML !== before[1],
                             readout: o.textContent !== before[2], width: m.naturalWidth};
  });
  out.requests = performance.getEntriesByType("resource").map(function (e) { return e.name; });
  var pre = document.createElement("pre"); pre.id = "result";
  pre.textContent = JSON.stringify(out); document.body.appendChild(pre);
});
</script>"""
    page = tmp_path / "players.html"
    page.write_text(
        f"<!doctype html><html><head><meta charset='utf-8'></head><body>{body}{probe}</body></html>", encoding="utf-8"
    )
    dom = dump_dom(page.as_uri(), tmp_path / "profile", budget_ms=5000)
    m = re.search(r'<pre id="result">(.*?)</pre>', dom, re.S)
    assert m, "the probe did not run"
    result = json.loads(m.group(1).replace("&quot;", '"').replace("&amp;", "&"))
    assert result.pop("requests") == [], "the page made a network request"
    for name in players:
        r = result[name]
        assert r["frame"] and r["readout"], f"{name}: moving the slider changed nothing"
        assert r["width"] > 0, f"{name}: the frame did not decode"
        if name != "critical":
            assert r["status"], f"{name}: the status line did not change"
