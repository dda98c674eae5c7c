"""An interactive 3D view of a molecule and its features, drawn by 3Dmol.js, offline.

:func:`view3d` returns a :class:`View3D`, whose ``_repr_html_`` is a ``<div>`` with a
legend and one inline ``<script>`` that draws the atoms (van der Waals spheres) and the
features (voids, pockets, their mouths, tunnels) with 3Dmol.js.  Nothing is ever
fetched from the network: 3Dmol.js is the copy of the npm package ``3dmol`` pinned in
``book/package.json`` (installed into ``book/node_modules`` by ``npm ci``).

Where 3Dmol.js comes from
-------------------------
* **JupyterLab (a kernel, maybe no network).**  The first view shown in a Python
  process carries the library itself, inline, in a ``<script
  data-shapelab-library=...>`` (about 0.5 MB, once per notebook); every later view
  finds ``window.$3Dmol`` already defined.  The file is read from
  ``$SHAPELAB_3DMOL_JS`` if that is set, else from ``book/node_modules`` of the
  source checkout shapelab is installed from (``pip install -e``).  A relative URL
  would not do here: JupyterLab resolves it against ``/lab/tree/...``, not the
  notebook's folder.
* **The course site and the decks (no kernel, no network).**  The book build copies
  ``3Dmol-min.js`` to ``vendor/3dmol/`` at the site's root (``course/build.py``; the
  decks' ``vendor/`` gets it too, ``course/slides.py``) and strips the inline copies
  from the lessons' outputs (:func:`without_library`); a view's script then loads
  ``<root>/vendor/3dmol/3Dmol-min.js`` once per page, the root being read from the
  page itself (Sphinx's ``data-content_root``, else the page's other scripts from
  ``vendor/``).  One copy for the whole site, fetched only by pages with a view.

py3Dmol (PyPI) is not used: its views load 3Dmol.js from a URL (a CDN by default),
its element ids come from the clock, and it ships no copy of the library.
"""

from __future__ import annotations

import hashlib
import html as _html
import json
import os
import re
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ._style import COLORS, PALETTE

if TYPE_CHECKING:
    from collections.abc import Sequence

    from ..balls import Balls
    from ..cavities import Pocket, Tunnel, Void
    from ..filtration import Filtration
    from ..io import PDBStructure

__all__ = ["View3D", "view3d", "library_path", "without_library", "FEATURE_COLORS", "SITE_PATH"]

#: Where the book build puts 3Dmol.js, relative to the site's root.
SITE_PATH = "vendor/3dmol/3Dmol-min.js"

#: One colour per kind of feature (Okabe-Ito, colour-blind safe); pockets cycle
#: through their own four.  No two kinds share a colour, and none is the atoms' grey.
FEATURE_COLORS = {
    "atom": "#A0A0A0",
    "void": COLORS["void"],  # vermillion
    "pocket": (PALETTE[1], PALETTE[2], PALETTE[6], PALETTE[5]),  # orange, green, yellow, sky blue
    "mouth": COLORS["mouth"],  # reddish purple
    "tunnel": PALETTE[0],  # blue
}

STYLES = ("auto", "element", "grey")
_LIBRARY_MARK = "data-shapelab-library"
_LIBRARY_BLOCK = re.compile(r"<script " + _LIBRARY_MARK + r"=[^>]*>.*?</script>\n?", re.S)
_N_SAMPLES = 2000  # candidate points per void/pocket; those in free space are drawn
_ROOT = Path(__file__).resolve().parents[2]


class _Session:
    """Whether this Python process has already shown 3Dmol.js inline (one per kernel)."""

    library_sent = False


# ============================================================================ library
def library_path() -> Path | None:
    """The local ``3Dmol-min.js`` that views shown in a kernel inline, or None.

    ``$SHAPELAB_3DMOL_JS`` if set, else ``book/node_modules/3dmol/build/3Dmol-min.js``
    of the source checkout shapelab is imported from (installed by ``cd book && npm
    ci``; ``make lab`` and ``make test`` run it).

    Returns
    -------
    pathlib.Path or None
        None when neither file exists.

    See Also
    --------
    view3d
        Uses it.
    """
    env = os.environ.get("SHAPELAB_3DMOL_JS")
    candidates = [Path(env)] if env else []
    candidates.append(_ROOT / "book" / "node_modules" / "3dmol" / "build" / "3Dmol-min.js")
    return next((p for p in candidates if p.is_file()), None)


def _library_version(path: Path) -> str:
    meta = path.parent.parent / "package.json"
    try:
        return str(json.loads(meta.read_text(encoding="utf-8"))["version"])
    except (OSError, ValueError, KeyError):
        return "unknown"


def _library_script(path: Path) -> str:
    """3Dmol.js as an inline script that defines ``window.$3Dmol`` once per page.

    The library is a UMD bundle: under require.js (``define``) or CommonJS
    (``exports``/``module``) it would not set the global, so those names are hidden
    from it by the wrapper's parameters."""
    source = path.read_text(encoding="utf-8")
    # an inline script ends at the first "</script"; the minified file has none, but be safe
    source = re.sub(r"</(script)", r"<\\/\1", source, flags=re.I).replace("<!--", "<\\!--")
    return (
        f'<script {_LIBRARY_MARK}="3Dmol.js {_html.escape(_library_version(path))}">\n'
        "if (!window.$3Dmol) { (function (define, exports, module) {\n"
        f"{source}\n"
        "}).call(window); }\n"
        "</script>\n"
    )


def without_library(html: str) -> str:
    """``html`` without the inline copies of 3Dmol.js that :func:`view3d` outputs carry.

    The course site serves the library from ``vendor/3dmol/`` instead; the book build
    applies this to every lesson output (``course/build.py``).

    See Also
    --------
    view3d
        Produces the html.

    Examples
    --------
    >>> without_library('<script data-shapelab-library="3Dmol.js 2.5.5">lib</script>\\n<div></div>')
    '<div></div>'
    """
    if not isinstance(html, str):
        raise TypeError(f"html must be a str, got {type(html).__name__}")
    return _LIBRARY_BLOCK.sub("", html)


# ============================================================================ inputs
def _atoms_of(structure_or_balls):
    """(balls, vdW radii, element symbols or None) from a PDBStructure, Balls or
    anything with a ``.balls`` (a Filtration)."""
    from ..balls import Balls

    name = "structure_or_balls"
    obj = structure_or_balls
    elements = None
    probe = 0.0
    if hasattr(obj, "balls") and hasattr(obj, "elements"):  # a PDBStructure
        elements = np.asarray(obj.elements).astype(str)
        probe = float(getattr(obj, "probe", 0.0) or 0.0)
        obj = obj.balls
    elif hasattr(obj, "balls") and not isinstance(obj, Balls):  # a Filtration
        obj = obj.balls
    if not isinstance(obj, Balls):
        raise TypeError(
            f"{name} must be a shapelab.io.PDBStructure, a shapelab.Balls or a Filtration, "
            f"got {type(structure_or_balls).__name__}"
        )
    if obj.dim != 3:
        raise ValueError(f"{name} must be 3-dimensional, got dim={obj.dim}")
    if len(obj) == 0:
        raise ValueError(f"{name} has no atoms")
    radii = np.asarray(obj.radii, dtype=float) - probe
    radii = np.where(radii > 0, radii, np.asarray(obj.radii, dtype=float))
    return obj, radii, elements


def _features_of(features) -> list:
    """A flat list of Void, Pocket and Tunnel objects (one level of nesting allowed:
    ``features=(voids, pockets)``)."""
    from ..cavities import Pocket, Tunnel, Void

    kinds = (Void, Pocket, Tunnel)
    if features is None:
        return []
    if isinstance(features, kinds):
        return [features]
    if isinstance(features, (str, bytes, dict)) or not hasattr(features, "__iter__"):
        raise TypeError(
            f"features must be a Void, Pocket or Tunnel or a sequence of them, got {type(features).__name__}"
        )
    out = []
    for item in features:
        if isinstance(item, kinds):
            out.append(item)
        elif isinstance(item, (list, tuple)) and all(isinstance(x, kinds) for x in item):
            out.extend(item)
        else:
            raise TypeError(
                f"features must hold Void, Pocket or Tunnel objects (shapelab.voids/pockets/tunnels), "
                f"got {type(item).__name__}"
            )
    return out


def _indices(a, n: int, width: int, what: str) -> np.ndarray:
    a = np.asarray(a, dtype=np.int64).reshape(-1, width)
    if a.size and (a.min() < 0 or a.max() >= n):
        raise ValueError(
            f"features: a {what} names ball {int(a.max() if a.max() >= n else a.min())}, "
            f"but the structure has {n} atoms; were the features computed on these balls?"
        )
    return a


# ============================================================================ payload
def _round(x, nd=3) -> list:
    return np.round(np.asarray(x, dtype=float), nd).ravel().tolist()


def _mouth_mesh(centers: np.ndarray, tri: np.ndarray) -> dict:
    """Triangles as a two-sided mesh for 3Dmol's addCustom: each triangle twice, with
    its own vertices and opposite normals."""
    P = centers[tri]  # (q, 3, 3)
    nrm = np.cross(P[:, 1] - P[:, 0], P[:, 2] - P[:, 0])
    nrm /= np.maximum(np.linalg.norm(nrm, axis=1, keepdims=True), 1e-12)
    q = len(tri)
    verts = np.concatenate([P.reshape(-1, 3), P.reshape(-1, 3)])
    normals = np.concatenate([np.repeat(nrm, 3, axis=0), -np.repeat(nrm, 3, axis=0)])
    front = np.arange(3 * q).reshape(q, 3)
    back = (front + 3 * q)[:, ::-1]
    return {"v": _round(verts), "n": _round(normals), "f": np.concatenate([front, back]).ravel().tolist()}


def _payload(balls, radii, elements, feats, style: str, opacity: float):
    from ..cavities import Pocket, Tunnel, Void
    from ..cavities.freespace import free_points

    n = len(balls)
    centers = np.asarray(balls.centers, dtype=float)
    highlight = np.zeros(n, dtype=np.int64)  # 0: plain atom, k: lining of feature k (1-based)
    colors, legend, points, meshes, tunnels = [], [], [], [], []
    counts = {"void": 0, "pocket": 0, "tunnel": 0}
    rng = np.random.default_rng(0)  # the sample points of a void: a picture, the same every time
    n_mouths = 0
    for f in feats:
        if isinstance(f, Tunnel):
            counts["tunnel"] += 1
            edges = _indices(f.cycle, n, 2, "tunnel cycle edge")
            color = FEATURE_COLORS["tunnel"]
            tunnels.append({"c": color, "e": _round(centers[edges].reshape(-1, 6))})
            legend.append((color, f"T{counts['tunnel']} tunnel", f"cycle of {len(edges)} edges"))
            continue
        kind = "void" if isinstance(f, Void) else "pocket"
        counts[kind] += 1
        k = counts[kind]
        cells = _indices(f.cells, n, 4, f"{kind} cell")
        lining = _indices(f.lining, n, 1, f"{kind} lining atom").ravel()
        color = FEATURE_COLORS["void"] if kind == "void" else FEATURE_COLORS["pocket"][(k - 1) % 4]
        colors.append(color)
        fresh = lining[highlight[lining] == 0]
        highlight[fresh] = len(colors)
        pts = free_points(balls, f.tau, cells, _N_SAMPLES, rng) if len(cells) else np.zeros((0, 3))
        if not len(pts) and len(cells):  # free space too thin to sample: the cells' barycentres
            pts = centers[cells].mean(axis=1)
        points.append({"c": color, "p": _round(pts, 2)})
        label = f"{'V' if kind == 'void' else 'P'}{k} {kind}"
        detail = f"{len(lining)} lining atoms, {len(pts)} free-space samples"
        if kind == "void":
            detail += f", volume {f.volume:.3g} Å³"
        if isinstance(f, Pocket):
            mouth = _indices(f.mouth, n, 3, "pocket mouth triangle")
            detail += f", mouth of {len(mouth)} triangles"
            if len(mouth):
                n_mouths += 1
                meshes.append({"c": FEATURE_COLORS["mouth"], **_mouth_mesh(centers, mouth)})
        legend.append((color, label, detail))
    if n_mouths:
        legend.append((FEATURE_COLORS["mouth"], "mouth", "a pocket's openings to the outside"))
    if style == "auto":
        style = "grey" if feats else "element"
    atoms = {
        "xyz": _round(centers),
        "r": _round(radii, 2),
        "e": elements.tolist() if elements is not None else None,
        "h": highlight.tolist(),
    }
    data = {
        "atoms": atoms,
        "colors": colors,
        "style": style,
        "opacity": opacity,
        "atom_color": FEATURE_COLORS["atom"],
        "points": points,
        "meshes": meshes,
        "tunnels": tunnels,
    }
    atom_word = "element colours" if style == "element" else "grey"
    legend.insert(0, (FEATURE_COLORS["atom"], f"{n} atoms", f"van der Waals spheres, {atom_word}"))
    if colors:
        legend.insert(1, (colors[0], "lining atoms", "in the colour of their feature"))
    return data, legend


# ============================================================================ view
_SCRIPT = """
(function () {
  var root = document.currentScript ? document.currentScript.parentNode : document.getElementById(%(id)s);
  var data = %(data)s;
  var box = root.querySelector(".shapelab-view3d-canvas"), note = root.querySelector(".shapelab-view3d-note");
  function say(text) { note.textContent = text; note.style.display = "block"; }
  function draw() {
    var $3D = window.$3Dmol, v = $3D.createViewer(box, {backgroundColor: "white"});
    var A = data.atoms, n = A.r.length, plain = [], lined = [];
    for (var i = 0; i < n; i++) {
      var a = {elem: A.e ? A.e[i] : "C", x: A.xyz[3 * i], y: A.xyz[3 * i + 1], z: A.xyz[3 * i + 2],
               serial: i, index: i};
      var s = {radius: A.r[i]};
      if (A.h[i]) { s.color = data.colors[A.h[i] - 1]; a.style = {sphere: s}; lined.push(a); continue; }
      if (data.style !== "element") s.color = data.atom_color;
      a.style = {sphere: s};
      plain.push(a);
    }
    function model(atoms, opacity) {
      if (!atoms.length) return;
      var m = v.addModel();
      atoms.forEach(function (a) { a.style.sphere.opacity = opacity; });
      m.addAtoms(atoms);
    }
    model(plain, data.opacity);
    model(lined, Math.min(1, 3 * data.opacity));
    data.points.forEach(function (f) {
      var pts = [];
      for (var j = 0; j < f.p.length; j += 3)
        pts.push({elem: "X", x: f.p[j], y: f.p[j + 1], z: f.p[j + 2], serial: j / 3, index: j / 3,
                  style: {sphere: {radius: 0.5, color: f.c}}});
      model(pts, 1);
    });
    data.meshes.forEach(function (m) {
      var V = [], N = [];
      for (var j = 0; j < m.v.length; j += 3) {
        V.push(new $3D.Vector3(m.v[j], m.v[j + 1], m.v[j + 2]));
        N.push(new $3D.Vector3(m.n[j], m.n[j + 1], m.n[j + 2]));
      }
      v.addCustom({vertexArr: V, normalArr: N, faceArr: m.f, color: m.c, opacity: 0.8});
    });
    data.tunnels.forEach(function (t) {
      for (var j = 0; j < t.e.length; j += 6) {
        var p = {x: t.e[j], y: t.e[j + 1], z: t.e[j + 2]}, q = {x: t.e[j + 3], y: t.e[j + 4], z: t.e[j + 5]};
        v.addCylinder({start: p, end: q, radius: 0.3, color: t.c, fromCap: 2, toCap: 2});
      }
    });
    v.zoomTo();
    v.render();
    root.shapelabViewer = v;
  }
  if (window.$3Dmol) { draw(); return; }
  // the course site and decks: 3Dmol.js is vendored beside their other scripts, at
  // <root>/vendor/3dmol/; the root is read from the page's own markup (Sphinx's
  // data-content_root, else the folder of a script the page loads from <root>/vendor/)
  var base = document.documentElement.getAttribute("data-content_root");
  if (base === null) {
    var vendored = document.querySelector('script[src*="vendor/"]');
    if (vendored) base = vendored.getAttribute("src").replace(/vendor\\/.*$/, "");
  }
  if (base === null) {
    say("3Dmol.js is not loaded on this page: show a view3d(...) with library=True " +
        "(needs book/node_modules, `cd book && npm ci`, or $SHAPELAB_3DMOL_JS).");
    return;
  }
  if (!window.shapelab3Dmol) {
    window.shapelab3Dmol = new Promise(function (resolve, reject) {
      // a UMD bundle: under require.js (the decks) load it as an AMD module, never by
      // hiding the page's define (other scripts load meanwhile and need it)
      if (typeof window.define === "function" && window.define.amd && typeof window.require === "function") {
        window.require([base + %(path)s], function (lib) {
          window.$3Dmol = window.$3Dmol || lib;
          resolve();
        }, reject);
        return;
      }
      var tag = document.createElement("script");
      tag.onload = function () { resolve(); };
      tag.onerror = function () { reject(); };
      tag.src = base + %(path)s;
      document.head.appendChild(tag);
    });
  }
  window.shapelab3Dmol.then(draw, function () { say("3Dmol.js could not be loaded from " + base + %(path)s); });
})();
"""

_CSS = (
    ".shapelab-view3d{font:13px/1.4 sans-serif;margin:.5em 0}"
    ".shapelab-view3d-canvas{position:relative;border:1px solid #ddd}"
    ".shapelab-view3d-note{display:none;background:#fee;color:#000;padding:.4em;margin:.3em 0}"
    ".shapelab-view3d-legend{display:flex;flex-wrap:wrap;gap:.2em 1.2em;margin:.3em 0;padding:0;list-style:none}"
    ".shapelab-view3d-legend span{display:inline-block;width:.9em;height:.9em;border-radius:50%;"
    "margin-right:.35em;vertical-align:-.1em;border:1px solid #0003}"
)


class View3D:
    """An interactive 3D view (3Dmol.js) of atoms and features; made by :func:`view3d`.

    Shown by Jupyter through ``_repr_html_``; :meth:`html` gives the same HTML.

    Attributes
    ----------
    id : str
        The view's element id: a hash of what it draws, so the same view always has
        the same HTML (notebook outputs compare equal from run to run).
    legend : list of (colour, label, detail)
        What the legend under the view says.
    library : bool or None
        Whether the HTML carries 3Dmol.js inline (None: the first view shown in this
        process does).

    See Also
    --------
    view3d
        Produces it.
    """

    def __init__(self, data: dict, legend: list, width: int, height: int, library):
        self._data = data
        self.legend = legend
        self.width = width
        self.height = height
        self.library = library
        blob = json.dumps([data, legend, width, height], sort_keys=True, separators=(",", ":"))
        self.id = "shapelab-view3d-" + hashlib.sha256(blob.encode()).hexdigest()[:12]
        from ._describe import describe

        # the canvas's text alternative (WCAG 1.1.1): what the view draws, from its legend
        describe(self, "Interactive 3D view: " + "; ".join(f"{label} ({detail})" for _, label, detail in legend))

    @property
    def alt(self) -> str:
        """What the view shows, in words (the canvas's ``aria-label``; see
        :func:`shapelab.plot.alt_text`)."""
        from ._describe import alt_text

        return alt_text(self)

    def html(self, *, library: bool | None = None) -> str:
        """The view as HTML: ``<div>`` (canvas, note, legend) and its ``<script>``.

        Parameters
        ----------
        library : bool, optional
            Carry 3Dmol.js inline (True), never (False), or only if no view shown in this
            process has yet (None, default: the attribute ``library`` decides first).

        Returns
        -------
        str
        """
        library = self.library if library is None else library
        if library is None:
            library = not _Session.library_sent
        lib = ""
        if library:
            path = library_path()
            if path is not None:
                lib = _library_script(path)
                _Session.library_sent = True
        data = json.dumps(self._data, separators=(",", ":"), allow_nan=False).replace("</", "<\\/")
        script = _SCRIPT % {"id": json.dumps(self.id), "data": data, "path": json.dumps(SITE_PATH)}
        items = "".join(
            f'<li title="{_html.escape(detail)}"><span style="background:{c}"></span>{_html.escape(label)}'
            f'<small style="color:#666"> ({_html.escape(detail)})</small></li>'
            for c, label, detail in self.legend
        )
        return (
            f"{lib}"
            f'<div class="shapelab-view3d" id="{self.id}"><style>{_CSS}</style>'
            f'<div class="shapelab-view3d-canvas" role="img" aria-label="{_html.escape(self.alt)}" '
            f'style="width:{self.width}px;max-width:100%;height:{self.height}px"></div>'
            f'<div class="shapelab-view3d-note"></div>'
            f'<ul class="shapelab-view3d-legend" aria-label="Legend">{items}</ul>'
            f"<small>Drag to rotate, scroll to zoom, right-drag to move.</small>"
            f"<script>{script}</script></div>"
        )

    def _repr_html_(self) -> str:
        return self.html()

    def __repr__(self) -> str:
        kinds = ", ".join(label for _, label, _ in self.legend[1:])
        return f"View3D({self.id}: {kinds or 'atoms only'})"


def view3d(
    structure_or_balls: PDBStructure | Balls | Filtration,
    features: Void | Pocket | Tunnel | Sequence[Void | Pocket | Tunnel] = (),
    *,
    style: str = "auto",
    opacity: float | None = None,
    width: int = 640,
    height: int = 480,
    library: bool | None = None,
) -> View3D:
    """An interactive 3D view of a molecule and its voids, pockets, mouths and tunnels.

    Drawn in the browser by 3Dmol.js (WebGL), from a local copy only: it works in
    JupyterLab and on the course site with no network, and on the site with no
    kernel (see the module's notes for where the library comes from).

    Parameters
    ----------
    structure_or_balls : shapelab.io.PDBStructure, Balls or Filtration
        The atoms, drawn as spheres of their van der Waals radius (a structure's
        ``balls.radii`` less its ``probe``; a Balls' own radii).  Must be 3D.
    features : Void, Pocket, Tunnel or a sequence of them
        From :func:`shapelab.voids`, :func:`shapelab.pockets` and
        :func:`shapelab.tunnels` on these balls (``(voids, pockets)`` is accepted too).
        A void or pocket is drawn as small spheres in its free space (points of its
        cells that no ball grown to its τ covers) with its lining atoms in its colour;
        a pocket's mouth triangles as a mesh; a tunnel's cycle as cylinders between
        ball centres.  Kinds get distinct colours (:data:`FEATURE_COLORS`).
    style : {"auto", "element", "grey"}
        Atom colours: by element (a structure's elements; a Balls' are all carbon-grey)
        or one light grey; ``"auto"``: grey when there are features, else by element.
    opacity : float in (0, 1], optional
        Of the atoms (lining atoms get three times as much, at most 1).  Default 0.25 with
        features (so that the features inside show through), else 1.
    width, height : int
        Size of the canvas in pixels.
    library : bool, optional
        Carry 3Dmol.js inline in the HTML: None (default) for the first view shown in
        this Python process only, True always, False never (on a page that loads
        3Dmol.js itself, such as the course site).

    Returns
    -------
    View3D
        Displayed by Jupyter (``_repr_html_``); ``.html()`` is its HTML.

    Raises
    ------
    TypeError
        If ``structure_or_balls`` or ``features`` is of the wrong type.
    ValueError
        If the balls are not 3D, a feature names a ball that does not exist, or
        ``style``, ``opacity``, ``width`` or ``height`` is out of range.

    See Also
    --------
    shapelab.plot.topology.pocket_gallery
        A static overview.
    shapelab.report
        The cavities to show.

    References
    ----------
    .. [1] N. Rego and D. Koes, "3Dmol.js: molecular visualization with WebGL",
           *Bioinformatics* 31(8):1322-1324, 2015. doi:10.1093/bioinformatics/btu829

    Examples
    --------
    >>> import shapelab
    >>> s = shapelab.datasets.structure("t4l-l99a")
    >>> v = view3d(s, library=False)
    >>> v.id == view3d(s).id, "https://" in v.html()
    (True, False)
    """
    balls, radii, elements = _atoms_of(structure_or_balls)
    feats = _features_of(features)
    if not isinstance(style, str) or style not in STYLES:
        raise ValueError(f"style must be one of {STYLES}, got {style!r}")
    if opacity is None:
        opacity = 0.25 if feats else 1.0
    if isinstance(opacity, bool) or not isinstance(opacity, (int, float, np.floating, np.integer)):
        raise TypeError(f"opacity must be a number, got {type(opacity).__name__}")
    opacity = float(opacity)
    if not 0 < opacity <= 1:
        raise ValueError(f"opacity must be in (0, 1], got {opacity}")
    for name, value in (("width", width), ("height", height)):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
            raise TypeError(f"{name} must be an int (pixels), got {type(value).__name__}")
        if not 50 <= value <= 4000:
            raise ValueError(f"{name} must be between 50 and 4000 pixels, got {value}")
    if library is not None and not isinstance(library, bool):
        raise TypeError(f"library must be True, False or None, got {type(library).__name__}")
    data, legend = _payload(balls, radii, elements, feats, style, opacity)
    return View3D(data, legend, int(width), int(height), library)
