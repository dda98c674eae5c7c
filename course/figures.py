"""Figures for slides: every figure of the notes and the key figures of each lesson.

    python -m course.figures --out DIR --format pdf|svg|png [--only NAME ...] [--list]

Each figure is a small function registered here under a name (``fig23_1i``,
``l09_barcode``, ...).  It calls a :mod:`shapelab.plot` function on inputs from
:mod:`shapelab.datasets` (and the library's results on them), exactly as the lessons
do, so a figure on a slide is the figure of the lesson.  All share the course style
(:mod:`shapelab.plot._style`: Okabe–Ito colour-blind-safe palette) and are drawn at
the 16:9 slide size :data:`shapelab.plot.SLIDE` (10 × 5.625 in; PNG at 192 dpi is
1920 × 1080 pixels).

PDF and SVG are vector output written **deterministically**: no creation date, a
fixed producer string and a fixed SVG hash salt, so the same input gives the same
bytes (:func:`save`).  A figure that cannot be drawn is reported with its reason and
the command exits with status 1; the others are still written.

The course site's gallery (``book/gallery.md``) shows them all; ``make course``
regenerates its images with ``--gallery``.
"""

from __future__ import annotations

import argparse
import importlib
import sys
import time
import traceback
from collections.abc import Callable
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

__all__ = ["FigureSpec", "FIGURES", "FORMATS", "register", "missing", "build", "save", "main"]

FORMATS = ("pdf", "svg", "png")
#: PNG resolution: 10 in × 192 dpi = 1920 px, a full-HD slide.
PNG_DPI = 192
PRODUCER = "shapelab"


@dataclass(frozen=True)
class FigureSpec:
    """One registered figure.

    Attributes
    ----------
    name : str
        File stem and ``--only`` key.
    caption : str
        What the figure shows (the gallery's caption).
    source : str
        Where it comes from: ``"Notes, Figure 23.1 (i)"`` or ``"Lesson 11"``.
    lesson : str or None
        The lesson that draws it (``"11_persistence"``), for the gallery's link.
    needs : tuple of str
        Library names it calls, as ``"plot.barcode"`` or ``"datasets.ring"``: when
        one is missing (a module still being written) the figure is reported as
        such rather than as a bug.
    draw : callable
        ``draw() -> matplotlib.figure.Figure``.
    """

    name: str
    caption: str
    source: str
    lesson: str | None
    needs: tuple[str, ...]
    draw: Callable = field(repr=False)


#: The registry, in gallery order: the notes' figures first, then lesson by lesson.
FIGURES: dict[str, FigureSpec] = {}


def register(name: str, caption: str, *, source: str, lesson: str | None = None, needs=()):
    """Decorator adding a figure function to :data:`FIGURES`."""

    def deco(fn):
        if name in FIGURES:
            raise ValueError(f"figure {name!r} is registered twice")
        FIGURES[name] = FigureSpec(name, caption, source, lesson, tuple(needs), fn)
        return fn

    return deco


def _resolve(dotted: str):
    obj, path = importlib.import_module("shapelab"), "shapelab"
    for part in dotted.split("."):
        path += "." + part
        try:
            obj = getattr(obj, part)
        except AttributeError:
            try:  # a submodule not re-exported, e.g. "plot.balls.lifting"
                obj = importlib.import_module(path)
            except ModuleNotFoundError:
                raise AttributeError(path) from None
    return obj


def missing(spec: FigureSpec) -> list[str]:
    """The names ``spec`` needs that the library does not provide (yet)."""
    out = []
    for dotted in spec.needs:
        try:
            _resolve(dotted)
        except (AttributeError, ImportError):
            out.append(f"shapelab.{dotted}")
    return out


def _slide(nrows=1, ncols=1, **kw):
    from shapelab.plot import SLIDE, new_figure

    return new_figure(nrows, ncols, size=SLIDE, **kw)


def _legend_below(fig, axes) -> None:
    """One legend for all the panels of ``fig``, below them: none repeated in every
    panel, none over the data.  The entries of the panels' legends, without repeats."""
    handles, labels = [], []
    for ax in np.ravel(axes):
        leg = ax.get_legend()
        if leg is None:
            continue
        for h, t in zip(leg.legend_handles, leg.get_texts()):
            if t.get_text() not in labels:
                handles.append(h)
                labels.append(t.get_text())
        leg.remove()
    if handles:
        fig.legend(handles, labels, loc="outside lower center", ncols=min(len(labels), 4))


def build(name: str):
    """Draw the registered figure ``name`` at the 16:9 slide size; returns the Figure.

    The layout is settled (two passes of the layout engine: a legend placed outside
    its axes moves with them after the first) and then frozen, so that saving the
    figure in several formats draws it the same way each time, and fast.
    """
    from matplotlib.figure import Figure

    from shapelab.plot import SLIDE

    spec = FIGURES[name]
    fig = spec.draw()
    if not isinstance(fig, Figure):
        raise TypeError(f"figure {name!r}: its function returned {type(fig).__name__}, not a Figure")
    fig.set_size_inches(*SLIDE)
    _settle(fig)
    return fig


def _settle(fig) -> None:
    if fig.get_layout_engine() is not None:
        fig.draw_without_rendering()
        fig.draw_without_rendering()
        fig.set_layout_engine("none")


@contextmanager
def _save_style():
    import matplotlib

    from shapelab.plot import RC

    # the course style, but the page size is the figure's size: no tight bbox, so
    # every file is exactly 16:9
    with matplotlib.rc_context({**RC, "savefig.bbox": "standard", "svg.hashsalt": "shapelab"}):
        yield


def description(fig, fallback: str | None = None) -> str | None:
    """What ``fig`` shows, in words: the description its plotting functions wrote
    (:func:`shapelab.plot.alt_text`), else ``fallback`` (the registry's caption)."""
    from shapelab.plot import alt_text

    return alt_text(fig) or fallback


#: the SVG element that carries a figure's text alternative (read by the book's
#: gallery, book/_ext/shapelab_a11y.py)
SVG_TITLE = '<title id="shapelab-alt">'


def _svg_with_title(path: Path, text: str) -> None:
    """Give the SVG at ``path`` its text alternative: a ``<title>`` first inside the root
    (what an SVG viewer and a screen reader read) and ``role="img"``."""
    import html as _html

    svg = path.read_text(encoding="utf-8")
    start = svg.index("<svg")
    end = svg.index(">", start)
    head = svg[start:end]
    if 'role="img"' not in head:
        head += ' role="img" aria-labelledby="shapelab-alt"'
    svg = svg[:start] + head + ">" + f"\n {SVG_TITLE}{_html.escape(text, quote=False)}</title>" + svg[end + 1 :]
    path.write_text(svg, encoding="utf-8")


def save(fig, path, fmt: str | None = None, alt: str | None = None) -> Path:
    """Write ``fig`` to ``path`` deterministically (same figure, same bytes).

    PDF: no ``CreationDate``, a fixed Creator/Producer.  SVG: no ``Date``, a fixed
    hash salt for the element ids.  PNG: a fixed ``Software`` entry, 192 dpi.

    The figure's text alternative (``alt``, default :func:`description`) goes with it:
    the SVG's ``<title>``, the PDF's ``Subject``, the PNG's ``Description``.
    """
    path = Path(path)
    fmt = (fmt or path.suffix.lstrip(".")).lower()
    if fmt not in FORMATS:
        raise ValueError(f"fmt must be one of {', '.join(FORMATS)}, got {fmt!r}")
    alt = alt or description(fig)
    meta = {
        "pdf": {"CreationDate": None, "ModDate": None, "Creator": PRODUCER, "Producer": PRODUCER},
        "svg": {"Date": None, "Creator": PRODUCER},
        "png": {"Software": PRODUCER},
    }[fmt]
    if alt:
        meta.update({"pdf": {"Subject": alt}, "svg": {"Description": alt}, "png": {"Description": alt}}[fmt])
    path.parent.mkdir(parents=True, exist_ok=True)
    with _save_style():
        fig.savefig(path, format=fmt, metadata=meta, dpi=PNG_DPI if fmt == "png" else None, bbox_inches=_page(fig))
    if alt and fmt == "svg":
        _svg_with_title(path, alt)
    return path


def _page(fig):
    """The page to save: the figure, grown to hold anything drawn outside it (a legend
    below the axes, say) and then to 16:9 again, centred.  ``None`` when it all fits."""
    from matplotlib.transforms import Bbox

    _settle(fig)
    w, h = fig.get_size_inches()
    tight = fig.get_tightbbox(fig._get_renderer())
    x0, y0 = min(0.0, tight.x0), min(0.0, tight.y0)
    x1, y1 = max(w, tight.x1), max(h, tight.y1)
    if (x0, y0, x1, y1) == (0.0, 0.0, w, h):
        return None
    pad = 0.05
    x0, y0, x1, y1 = x0 - pad, y0 - pad, x1 + pad, y1 + pad
    ratio = w / h
    bw, bh = x1 - x0, y1 - y0
    if bw / bh < ratio:  # too tall: widen
        grow = bh * ratio - bw
        x0, x1 = x0 - grow / 2, x1 + grow / 2
    else:
        grow = bw / ratio - bh
        y0, y1 = y0 - grow / 2, y1 + grow / 2
    x0, x1, y0 = round(x0, 3), round(x1, 3), round(y0, 3)
    return Bbox.from_extents(x0, y0, x1, y0 + (x1 - x0) / ratio)


def _placeholder(name: str, reason: str):
    """A plain slide-sized figure saying that ``name`` could not be drawn (gallery only)."""
    fig, ax = _slide()
    ax.set_axis_off()
    ax.text(0.5, 0.55, f"{name}: not available", ha="center", va="center", fontsize=18)
    ax.text(0.5, 0.4, reason[:120], ha="center", va="center", fontsize=10, color="#666666", wrap=True)
    from shapelab.plot import describe

    describe(fig, f"Placeholder: the figure {name} is not available ({reason[:120]})")
    return fig


# ============================================================== the figures
# Inputs are seeded or closed-form, and small: the whole set renders in seconds.
def _sl():
    return importlib.import_module("shapelab")


def _datasets():
    return importlib.import_module("shapelab.datasets")


def _plot():
    return importlib.import_module("shapelab.plot")


# --------------------------------------------------------- the notes' figures
@register(
    "fig23_1i",
    "A union of disks, its power cells clipped to the disks, and the dual complex K "
    "drawn on top: edges for pairwise, triangles for triple intersections of the clipped cells.",
    source="Notes, Figure 23.1 (i)",
    lesson="03_dual_complex",
    needs=("datasets.figure_23_1", "plot.dual_complex"),
)
def fig23_1i():
    fig, ax = _slide()
    _plot().dual_complex(_datasets().figure_23_1(), ax=ax)
    return fig


@register(
    "fig23_1ii",
    "The filtration of the Delaunay triangulation: every edge and triangle shaded by "
    "the growth time τ at which it enters the dual complex.",
    source="Notes, Figure 23.1 (ii)",
    lesson="04_alpha_filtration",
    needs=("datasets.figure_23_1", "alpha_filtration", "plot.filtration"),
)
def fig23_1ii():
    fig, ax = _slide()
    _plot().filtration(_sl().alpha_filtration(_datasets().figure_23_1()), ax=ax)
    return fig


@register(
    "fig23_2",
    "Two dents of the same depth around the same chamber, different only in the mouth. "
    "Left: a narrow mouth closes before the chamber fills, so the dent becomes a hole: a pocket. "
    "Right: a mouth as wide as the chamber, widening outwards: the dent fills from the bottom and "
    "never closes: not a pocket.",
    source="Notes, Figure 23.2",
    lesson="08_pockets",
    needs=("datasets.figure_23_2", "plot.pockets", "alpha_filtration"),
)
def fig23_2():
    left, right = _datasets().figure_23_2()
    fig, (a, b) = _slide(1, 2)
    _plot().pockets(_sl().alpha_filtration(left), ax=a, title="a pocket: its mouth closes first")
    _plot().pockets(_sl().alpha_filtration(right), ax=b, title="not a pocket: it fills without closing")
    _legend_below(fig, (a, b))
    return fig


@register(
    "fig23_3",
    "A closed curve C, a viewpoint S inside it, and the critical points of the distance "
    "F(x) = |x − S| along C (left), with F itself along the curve (right): minima and maxima "
    "alternate.",
    source="Notes, Figure 23.3",
    lesson="13_critical_points",
    needs=("datasets.blob_curve", "critical_points", "plot.critical_points"),
)
def fig23_3():
    blob = _datasets().blob_curve
    S = np.array([0.1, 0.05])
    return _plot().critical_points(blob, _sl().critical_points(blob, S))


@register(
    "fig23_4",
    "Rotation in R³ about the unit axis u by the angle θ (right-hand rule): points before "
    "(red) and after (green), their circles about the axis and the swept arcs. As a unit quaternion, "
    "q = cos(θ/2) + sin(θ/2)(u_x i + u_y j + u_z k).",
    source="Notes, Figure 23.4",
    lesson="16_quaternions",
    needs=("Quaternion", "plot.rotation_axis"),
)
def fig23_4():
    q = _sl().Quaternion.from_axis_angle([1.0, 1.0, 2.0], np.radians(100.0))
    return _plot().rotation_axis(q)


# ---------------------------------------------------------- lesson figures
@register(
    "l01_power_diagram",
    "The power diagram of nine disks: each cell is where that disk's power "
    "distance is smallest; its edges lie on the radical axes, and a disk can be hidden, with an "
    "empty cell.",
    source="Lesson 01",
    lesson="01_power_diagrams",
    needs=("Balls", "power_diagram", "plot.power_diagram"),
)
def l01_power_diagram():
    rng = np.random.default_rng(1)  # lesson 01's disks
    disks = _sl().Balls(rng.uniform(0, 6, size=(9, 2)), rng.uniform(0.4, 1.2, size=9))
    fig, ax = _slide()
    _plot().power_diagram(_sl().power_diagram(disks), labels=True, ax=ax)
    return fig


@register(
    "l02_homology_cycle",
    "A triangulated annulus: its inner ring is a 1-cycle that bounds no 2-chain, so "
    "β₁ = 1 (Betti numbers over Z/2 as ranks of the boundary matrices).",
    source="Lesson 02",
    lesson="02_homology",
    needs=("plot.simplicial_complex",),
)
def l02_homology_cycle():
    import numpy as np

    fig, ax = _slide()
    k = 6
    outer = [(np.cos(2 * np.pi * i / k) * 2, np.sin(2 * np.pi * i / k) * 2) for i in range(k)]
    inner = [(np.cos(2 * np.pi * (i + 0.5) / k), np.sin(2 * np.pi * (i + 0.5) / k)) for i in range(k)]
    positions = outer + inner
    triangles = [(i, (i + 1) % k, k + i) for i in range(k)] + [((i + 1) % k, k + i, k + (i + 1) % k) for i in range(k)]
    simplices = sorted({tuple(sorted(f)) for t in triangles for r in (1, 2, 3) for f in _faces(t, r)})
    ring = [tuple(sorted((k + i, k + (i + 1) % k))) for i in range(k)]
    _plot().simplicial_complex(simplices, positions, chain=ring, ax=ax, title="A cycle that bounds nothing")
    return fig


def _faces(simplex, r):
    from itertools import combinations

    return combinations(simplex, r)


@register(
    "l02_growth",
    "The same disks grown: at τ = −0.3 the dual complex has a hole, at τ = 3 the "
    "union is one piece without holes, and so is K: K has the topology of the union.",
    source="Lesson 03",
    lesson="03_dual_complex",
    needs=("datasets.figure_23_1", "alpha_filtration", "plot.dual_complex"),
)
def l02_growth():
    disks = _datasets().figure_23_1()
    F = _sl().alpha_filtration(disks)
    fig, (a, b) = _slide(1, 2)
    _plot().dual_complex(F, -0.3, ax=a, title="τ = −0.3: one hole")
    _plot().dual_complex(F, 3.0, ax=b, title="τ = 3: one piece, no hole")
    _legend_below(fig, (a, b))
    return fig


@register(
    "l03_alpha_complexes",
    "The growth model: the disks grown to radii √(r² + τ) and their dual "
    "complexes at four times τ, a nested sequence of α-complexes (α = √τ).",
    source="Lesson 04",
    lesson="04_alpha_filtration",
    needs=("datasets.figure_23_1", "alpha_filtration", "plot.dual_complex"),
)
def l03_alpha_complexes():
    disks = _datasets().figure_23_1()
    F = _sl().alpha_filtration(disks)
    fig, axes = _slide(2, 2)
    for ax, tau in zip(axes.ravel(), (-0.5, 0.0, 0.6, 1.5)):
        _plot().dual_complex(F, tau, ax=ax, show_cells=False)
    _legend_below(fig, axes)
    return fig


@register(
    "l05_dual_complex_3d",
    "The dual complex of C60 at τ = 0: the 60 carbon balls' vertices, "
    "edges and triangles close a cage around an empty centre.",
    source="Lesson 06",
    lesson="06_dual_complex_3d",
    needs=("datasets.fullerene_c60", "alpha_filtration", "plot.complex3d"),
)
def l05_dual_complex_3d():
    fig, ax = _slide(projection="3d")
    _plot().complex3d(_sl().alpha_filtration(_datasets().fullerene_c60()), tau=0.0, elev=15, azim=30, ax=ax)
    return fig


@register(
    "l06_voids_c60",
    "The one void of C60: the inside of the carbon cage, sealed off once the "
    "hexagons close, drawn inside the see-through balls.",
    source="Lesson 07",
    lesson="07_voids",
    needs=("datasets.fullerene_c60", "plot.voids", "alpha_filtration"),
)
def l06_voids_c60():
    fig, ax = _slide(projection="3d")
    _plot().voids(_sl().alpha_filtration(_datasets().fullerene_c60()), ax=ax)
    return fig


@register(
    "l07_pockets_bowl",
    "A pocket in 3D: a spherical shell with a round opening, its mouth "
    "(the triangles joining it to the outside) and its lining atoms.",
    source="Lesson 08",
    lesson="08_pockets",
    needs=("datasets.bowl", "plot.pockets", "alpha_filtration"),
)
def l07_pockets_bowl():
    fig, ax = _slide(projection="3d")
    _plot().pockets(_sl().alpha_filtration(_datasets().bowl()), ax=ax)
    return fig


@register(
    "l09_pocket_flow",
    "The discrete flow on the empty triangles of the flask of Figure 23.2: arrows across the edges each "
    "triangle's orthocentre lies beyond, the sinks, and the regions that do not drain to infinity (the pockets).",
    source="Lesson 09",
    lesson="09_pocket_flow",
    needs=("plot.discrete_flow", "datasets.figure_23_2", "alpha_filtration"),
)
def l09_pocket_flow():
    fig, ax = _slide()
    flask, _ = _datasets().figure_23_2()
    _plot().discrete_flow(_sl().alpha_filtration(flask), 0.0, ax=ax)
    return fig


@register(
    "l08_tunnels_nanotube",
    "The tunnel of an (8, 8) carbon nanotube: a representative cycle of its H₁ class around the tube.",
    source="Lesson 10",
    lesson="10_tunnels",
    needs=("datasets.nanotube", "plot.tunnels", "alpha_filtration"),
)
def l08_tunnels_nanotube():
    fig, ax = _slide(projection="3d")
    _plot().tunnels(_sl().alpha_filtration(_datasets().nanotube()), ax=ax)
    return fig


def _swiss_cheese_filtration():
    return _sl().alpha_filtration(_datasets().swiss_cheese())


@register(
    "l09_persistence_diagram",
    "The persistence diagram of the Swiss cheese: three round holes "
    "far from the diagonal, and the long thin slit's pieces close to it. Persistence measures "
    "thickness, not area.",
    source="Lesson 11",
    lesson="11_persistence",
    needs=("datasets.swiss_cheese", "alpha_filtration", "plot.persistence_diagram"),
)
def l09_persistence_diagram():
    fig, ax = _slide()
    _plot().persistence_diagram(_swiss_cheese_filtration(), ax=ax)
    return fig


@register(
    "l09_barcode",
    "The barcode of the same filtration: one bar per component and per hole, from its birth to its death.",
    source="Lesson 11",
    lesson="11_persistence",
    needs=("datasets.swiss_cheese", "alpha_filtration", "plot.barcode"),
)
def l09_barcode():
    fig, ax = _slide()
    _plot().barcode(_swiss_cheese_filtration(), ax=ax)
    return fig


@register(
    "l09_betti_curve",
    "Betti numbers β₀ and β₁ as the disks grow: components merge, holes appear and fill.",
    source="Lesson 11",
    lesson="11_persistence",
    needs=("datasets.swiss_cheese", "alpha_filtration", "plot.betti_curve"),
)
def l09_betti_curve():
    fig, ax = _slide()
    _plot().betti_curve(_swiss_cheese_filtration(), ax=ax)
    return fig


@register(
    "l10_globule_pockets",
    "A protein-like globule: its pockets with their mouths, and its buried "
    "void, computed from first principles as CASTp-style tools report them.",
    source="Lesson 12",
    lesson="12_molecule_case_study",
    needs=("datasets.globule", "plot.pocket_gallery", "alpha_filtration"),
)
def l10_globule_pockets():
    F = _sl().alpha_filtration(_datasets().globule())
    # the four pockets that persist (the others are crevices between atoms, gone at once);
    # seen along y, the three at the bottom stand side by side
    return _plot().pocket_gallery(F, min_persistence=0.5, elev=12, azim=-90)


@register(
    "l11_critical_surface",
    "Critical points on a closed surface seen from its centre: minima, "
    "saddles and maxima of F = |x − S|, with #min − #saddles + #max = χ = 2.",
    source="Lesson 13",
    lesson="13_critical_points",
    needs=("datasets.bumpy_sphere", "critical_points", "plot.critical_surface"),
)
def l11_critical_surface():
    V, F = _datasets().bumpy_sphere(3)
    S = np.zeros(3)
    fig, ax = _slide(projection="3d")
    _plot().critical_surface(V, F, _sl().critical_points(V, S, faces=F), ax=ax)
    return fig


@register(
    "l12_hausdorff",
    "The Hausdorff distance of two point sets: the witnesses of h(R, G) and "
    "h(G, R), each certified by an empty disk; the longer one is H(R, G).",
    source="Lesson 14",
    lesson="14_hausdorff",
    needs=("plot.hausdorff",),
)
def l12_hausdorff():
    rng = np.random.default_rng(0)  # lesson 14's R and G
    R = rng.normal(size=(25, 2))
    G = rng.normal(size=(20, 2)) * [1.3, 0.7] + [1.2, 0.3]
    fig, ax = _slide()
    _plot().hausdorff(R, G, labels=("R", "G"), ax=ax)
    return fig


@register(
    "l12_translation",
    "Matching under translation: B moved onto A by aligning the centroids (a "
    "reference point) and by the optimal translation, found by a certified search.",
    source="Lesson 14",
    lesson="14_hausdorff",
    needs=("hausdorff_under_translation", "plot.hausdorff_distance.translation"),
)
def l12_translation():
    rng = np.random.default_rng(12)
    A = rng.normal(size=(40, 2)) * [1.5, 0.6]
    B = A[rng.permutation(40)[:30]] + 0.15 * rng.normal(size=(30, 2)) + [4.0, -2.0]
    return _resolve("plot.hausdorff_distance.translation")(A, B, _sl().hausdorff_under_translation(A, B))


def _icp_example(n=250):
    """Lesson 15's setting: a lumpy shape and an independent sampling of it, moved."""
    sl = _sl()
    sample = sl.datasets.sample_shape
    truth = sl.RigidMotion(sl.Quaternion.from_axis_angle([1.0, 2.0, 3.0], np.radians(30.0)), [0.3, -0.1, 0.2])
    return sample("lumpy", n, seed=1), truth.apply(sample("lumpy", n, seed=2)), truth


@register(
    "l13_icp_step",
    "One ICP iteration: step 1 pairs every source point (red) with its closest "
    "target point (green); steps 2–3 move the source by the best rigid motion for those pairs.",
    source="Lesson 15",
    lesson="15_icp",
    needs=("datasets.sample_shape", "icp", "RigidMotion", "plot.icp_step"),
)
def l13_icp_step():
    source, target, _ = _icp_example()
    result = _sl().icp(source, target, max_iter=40, tol=1e-12, accelerate=False, keep_history=True)
    fig, ax = _slide(projection="3d")
    _plot().icp_step(source, target, result, 0, ax=ax)
    return fig


@register(
    "l13_icp_convergence",
    "ICP's mean squared error falls at every iteration (step 4), and the "
    "rotation error with it; the accelerated variant needs fewer iterations.",
    source="Lesson 15",
    lesson="15_icp",
    needs=("datasets.sample_shape", "icp", "RigidMotion", "plot.icp_convergence"),
)
def l13_icp_convergence():
    source, target, truth = _icp_example(400)
    runs = {
        "plain": _sl().icp(source, target, max_iter=60, tol=1e-10, accelerate=False),
        "accelerated": _sl().icp(source, target, max_iter=60, tol=1e-10),
    }
    fig, ax = _slide()
    _plot().icp_convergence(runs, truth=truth, ax=ax)
    return fig


@register(
    "l15_optimal_rotation",
    "Horn's optimal rotation: paired sets R and G before (left) and after "
    "(right) rotating R by the top eigenvector q of the 4 × 4 matrix A.",
    source="Lesson 17",
    lesson="17_optimal_rotation",
    needs=("Quaternion", "optimal_rotation", "plot.point_sets"),
)
def l15_optimal_rotation():
    sl = _sl()
    rng = np.random.default_rng(0)
    R = rng.normal(size=(40, 3)) * [2.0, 1.2, 0.6]
    R -= R.mean(axis=0)
    q_true = sl.Quaternion.from_axis_angle([1.0, 2.0, 3.0], np.radians(50.0))
    G = q_true.rotate(R) + 0.05 * rng.normal(size=R.shape)
    G -= G.mean(axis=0)
    q = sl.optimal_rotation(R, G)
    fig, (a, b) = _slide(1, 2, projection="3d")
    _plot().point_sets(R, G, pairs=True, ax=a, title=r"paired sets: $r_j \to g_j$")
    _plot().point_sets(q.rotate(R), G, pairs=True, labels=("q R q*", "G"), ax=b, title="after the optimal rotation")
    return fig


@register(
    "l16_docking_landscape",
    "Docking HIV-1 protease's inhibitor (PDB 1HVR): the score (buried solvent-accessible "
    "area minus clashes) over turns about the inhibitor's C2 axis and shifts along it; "
    "the crystal pose and its 180° twin are the two peaks.",
    source="Lesson 18",
    lesson="18_docking",
    needs=("datasets.structure", "Docking", "plot.docking_landscape"),
)
def l16_docking_landscape():
    sl = _sl()
    s = sl.datasets.structure("1hvr")
    lig = s.hetero & (s.residue_names == "XK2")
    protease, inhibitor = s.select(~lig), s.select(lig)
    dock = sl.Docking(protease.balls, inhibitor.balls, probe=1.4)
    c = inhibitor.balls.centers
    axis = np.linalg.eigh(np.cov((c - c.mean(axis=0)).T))[1][:, 0]
    angles, shifts = np.radians(np.arange(-180, 181, 15)), np.arange(-4.0, 4.01, 1.0)
    fig, ax = _slide()
    _plot().docking_landscape(
        angles,
        shifts,
        dock.landscape(angles, shifts, axis=axis, direction=axis),
        marks={"crystal pose": (0.0, 0.0), "turned by 180°": (np.pi, 0.0)},
        ax=ax,
    )
    return fig


@register(
    "l17_shape_classification",
    "Twenty sampled surfaces (spheres, ellipsoids, cubes, tori; each turned, scaled and "
    "blurred) placed in the plane by classical MDS of the 2-Wasserstein distances between "
    "their persistence diagrams: the classes separate without any alignment.",
    source="Lesson 19",
    lesson="19_shape_classification",
    needs=("datasets.shape_family", "alpha_filtration", "classical_mds", "plot.embedding"),
)
def l17_shape_classification():
    sl = _sl()
    from shapelab.diagrams import distance_matrix

    shapes, labels = sl.datasets.shape_family(per_class=5, n=400, seed=0)
    dgms = []
    for X in shapes:
        pairs = sl.alpha_filtration(sl.Balls(X, 0.0)).persistence()
        dgms.append({k: np.sqrt(np.maximum(np.asarray(pairs[k], float), 0.0)) for k in (1, 2)})
    W = np.hypot(*(distance_matrix([d[k] for d in dgms], p=2) for k in (1, 2)))
    fig, ax = _slide()
    _plot().embedding(sl.classical_mds(W).points, labels, ax=ax, title="Shapes by the distance of their diagrams")
    return fig


@register(
    "l18_binding_sites",
    "Does the pocket define the docking site? Ligand sites found (a pocket centre within 4 Å "
    "of a ligand atom) among the first N + k cavities listed, on the 52 test structures of the "
    "binding-site benchmark: ours at the report's defaults (ranked; growth model and discrete "
    "flow) beside fpocket-rs (in its own order and by drug score), pocketeer and pyKVFinder "
    "(committed results, not recomputed).",
    source="Lesson 20",
    lesson="20_binding_sites",
    needs=("report", "ranking.rank_score"),
)
def l18_binding_sites():
    import json

    results = Path(__file__).resolve().parents[1] / "benchmarks" / "results"
    methods = json.loads((results / "pocket_sites.json").read_text(encoding="utf-8"))["methods"]
    fig, ax = _slide()
    k = np.arange(11)
    for name, res in methods.items():
        ax.plot(
            k,
            100 * np.asarray(res["splits"]["test"]["top_n_plus_k"]),
            marker="o",
            lw=2,
            label=name,
            ls="-" if name.startswith("shapelab") else "--",
        )
    ax.axvline(2, color="0.6", lw=1)
    ax.set(
        xlabel="k: the first N + k cavities listed (N = ligand sites)",
        ylabel="sites found, DCA ≤ 4 Å (%)",
        ylim=(0, 100),
        xticks=k,
        title="Binding-site benchmark, test split",
    )
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=3, fontsize=8, frameon=False)
    return fig


# ============================================================== the gallery page
GALLERY_DIR = "_gallery"  # relative to book/, written by course/build.py


def gallery_markdown() -> str:
    """The text of ``book/gallery.md``: one MyST figure per registered figure.

    ``python -m course.figures --write-gallery book/gallery.md`` rewrites it, and a
    test keeps the committed page equal to this text.
    """
    parts = [
        "# Figure gallery",
        "",
        "Every figure of the notes and the key figure of each lesson, drawn by the library's",
        "plotting functions (`shapelab.plot`) on generated inputs (`shapelab.datasets`) in the",
        "course's colour-blind-safe style, at the 16:9 size of a slide. For your own slides:",
        "",
        "```bash",
        "python -m course.figures --out figures --format pdf   # all (or svg, png)",
        "python -m course.figures --list                       # their names",
        "make figures                                            # SVG, book/_build/figures",
        "```",
        "",
        "PDF and SVG files are written deterministically: the same input gives the same bytes.",
        "",
    ]
    section = None
    for spec in FIGURES.values():
        here = "Figures of the notes" if spec.source.startswith("Notes") else "Figures of the lessons"
        if here != section:
            parts += [f"## {here}", ""]
            section = here
        link = f" ([lesson {spec.lesson[:2]}](lessons/{spec.lesson}.ipynb))" if spec.lesson else ""
        parts += [
            f":::{{figure}} {GALLERY_DIR}/{spec.name}.svg",
            f":name: gallery-{spec.name.replace('_', '-')}",
            ":width: 100%",
            "",
            f"**{spec.source}.** {spec.caption}{link}",
            ":::",
            "",
            f"`python -m course.figures --only {spec.name} --format pdf --out figures`",
            "",
        ]
    return "\n".join(parts).rstrip() + "\n"


# ============================================================== command line
def _format_size(n: int) -> str:
    return f"{n / 1024:.0f} KiB" if n < 2**20 else f"{n / 2**20:.1f} MiB"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(
        prog="python -m course.figures",
        description="Export the notes' figures and each lesson's key figures for 16:9 slides.",
    )
    ap.add_argument("--out", type=Path, default=Path("figures"), help="output folder (default ./figures)")
    ap.add_argument(
        "--format",
        dest="formats",
        action="append",
        choices=FORMATS,
        help="pdf, svg or png; repeat for several (default svg)",
    )
    ap.add_argument("--only", action="append", metavar="NAME", help="only this figure (repeatable)")
    ap.add_argument("--list", action="store_true", help="list the figures and whether they can be drawn")
    ap.add_argument(
        "--write-gallery",
        type=Path,
        metavar="PAGE",
        help="write the gallery page (book/gallery.md) for the registered figures and stop",
    )
    ap.add_argument(
        "--gallery",
        action="store_true",
        help="for the book: write a labelled placeholder for a figure that fails (still exit 1)",
    )
    args = ap.parse_args(argv)

    if args.write_gallery:
        args.write_gallery.write_text(gallery_markdown(), encoding="utf-8")
        print(f"wrote {args.write_gallery} ({len(FIGURES)} figures)")
        return 0
    if args.list:
        for spec in FIGURES.values():
            gone = missing(spec)
            state = "ready" if not gone else "needs " + ", ".join(gone)
            print(f"{spec.name:24s} {spec.source:28s} {state}\n{'':24s} {spec.caption}")
        return 0
    names = args.only or list(FIGURES)
    unknown = [n for n in names if n not in FIGURES]
    if unknown:
        ap.error(f"unknown figure {', '.join(unknown)}; known: {', '.join(FIGURES)}")
    formats = args.formats or ["svg"]
    import matplotlib

    matplotlib.use("Agg")
    out = args.out
    out.mkdir(parents=True, exist_ok=True)
    t_all = time.perf_counter()
    failed, total = [], 0
    for i, name in enumerate(names, 1):
        spec = FIGURES[name]
        print(f"[{i}/{len(names)}] {name} ({spec.source}) ...", end="", flush=True)
        t0 = time.perf_counter()
        gone = missing(spec)
        try:
            if gone:
                raise LookupError("needs " + ", ".join(gone) + ", not written yet")
            fig = build(name)
        except Exception as exc:
            reason = (
                str(exc)
                if isinstance(exc, LookupError)
                else (
                    f"{type(exc).__name__}: {exc} ({traceback.extract_tb(exc.__traceback__)[-1].filename.split('/')[-1]}:"
                    f"{traceback.extract_tb(exc.__traceback__)[-1].lineno})"
                )
            )
            print(f" FAILED: {reason}")
            failed.append((name, reason))
            if not args.gallery:
                continue
            fig = _placeholder(name, reason)
        sizes = []
        alt = description(fig, spec.caption)  # the placeholder says what it is
        for fmt in formats:
            path = save(fig, out / f"{name}.{fmt}", fmt, alt=alt)
            sizes.append(path.stat().st_size)
        total += sum(sizes)
        if not (failed and failed[-1][0] == name):
            print(
                f" {time.perf_counter() - t0:.1f} s, "
                + ", ".join(f"{f} {_format_size(s)}" for f, s in zip(formats, sizes))
            )
    ok = len(names) - len(failed)
    print(
        f"figures: {ok}/{len(names)} drawn as {', '.join(formats)} in {time.perf_counter() - t_all:.1f} s, "
        f"{_format_size(total)} in {out}"
    )
    if failed:
        print(f"{len(failed)} figure(s) failed:", file=sys.stderr)
        for name, reason in failed:
            print(f"  {name}: {reason}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
