"""Figures of the topology of the growth model (Notes §23.1, "Voids and pockets").

* :func:`persistence_diagram`, :func:`barcode` — the pairs (birth, death) of
  :meth:`Filtration.persistence`: "by growing the union of balls, we are able to
  distinguish big voids or tunnels from smaller ones".
* :func:`betti_curve` — :math:`\\beta_k(\\tau)` as the balls grow.
* :func:`voids`, :func:`pockets`, :func:`tunnels` — the features themselves, drawn on
  the balls grown to τ, in 2D (disks) and 3D (balls); the dimension picks the drawing.

Every function returns a :class:`matplotlib.figure.Figure` (or draws into ``ax=`` and
returns its figure) and computes nothing itself beyond calling the library.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from matplotlib.collections import LineCollection, PatchCollection, PolyCollection
from matplotlib.lines import Line2D
from matplotlib.patches import Circle, Patch
from matplotlib.ticker import MaxNLocator

from .._toolkit.validate import as_finite_scalar, as_tau
from ..balls import Balls
from ..filtration import as_filtration
from ._common import axes, grown_radii, set_3d_view
from ._describe import describe
from ._style import COLORS, PALETTE, SLIDE, new_figure, style

if TYPE_CHECKING:
    from collections.abc import Sequence

    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from numpy.typing import ArrayLike

    from ..cavities import ChannelProfile, Pocket, Tunnel, Void
    from ..filtration import Filtration

__all__ = [
    "persistence_diagram",
    "barcode",
    "betti_curve",
    "voids",
    "pockets",
    "pocket_gallery",
    "tunnels",
    "channel_profile",
    "reduced_matrix",
    "voxel_slice",
]

_MARKERS = ("o", "s", "^", "D")
_SUB = "₀₁₂₃"


# ------------------------------------------------------------------ helpers
#: one line style per homology dimension, so that colour is never the only cue
_LINESTYLES = ("-", "--", "-.", ":")


def _g(x: float) -> str:
    return "∞" if np.isinf(x) else f"{x:.3g}"


def _pairs_summary(P: dict, dims, d) -> str:
    """Per dimension: how many pairs, how many never die, and the most persistent
    finite one, e.g. "H₁ holes: 12 pairs, the most persistent born at 0.1, dead at 2.3"."""
    parts = []
    for k in dims:
        a = np.asarray(P[k], dtype=float).reshape(-1, 2)
        text = f"{_dim_label(k, d)}: {len(a)} pair{'s' if len(a) != 1 else ''}"
        inf = int(np.isinf(a[:, 1]).sum())
        if inf:
            text += f", {inf} never dying"
        fin = a[np.isfinite(a[:, 1])]
        if len(fin):
            j = int(np.argmax(fin[:, 1] - fin[:, 0]))
            text += f", the most persistent finite one born at {_g(fin[j, 0])} and dead at {_g(fin[j, 1])}"
        parts.append(text)
    return "; ".join(parts) if parts else "no pairs"


def _dim_color(k: int) -> str:
    return PALETTE[k % len(PALETTE)]


def _dim_label(k: int, d: int | None) -> str:
    name = {0: "components", 1: "holes" if d == 2 else ("tunnels" if d == 3 else "loops"), 2: "voids"}.get(
        k, f"{k}-cycles"
    )
    return f"H{_SUB[k] if k < 4 else k} {name}"


def _pairs_of(obj, dim=None):
    """Normalise a Filtration, Balls or a dict {k: (p, 2)} to (dict of float arrays, ambient d)."""
    if isinstance(obj, Balls):  # the one input rule: the balls stand for their filtration
        obj = as_filtration(obj, "pairs_or_filtration")
    if hasattr(obj, "persistence") and callable(obj.persistence):
        d = getattr(getattr(obj, "balls", None), "dim", None)
        P = obj.persistence()
    elif isinstance(obj, dict):
        P, d = obj, None
    else:
        raise TypeError(
            "pairs_or_filtration must be a Filtration, Balls or a dict {k: (p, 2) array of (birth, death)}, "
            f"got {type(obj).__name__}"
        )
    out = {}
    for k, a in P.items():
        if isinstance(k, bool) or not isinstance(k, (int, np.integer)) or k < 0:
            raise ValueError(f"pairs_or_filtration keys must be homology dimensions 0, 1, ...; got {k!r}")
        arr = np.asarray(a, dtype=np.float64).reshape(-1, 2) if np.size(a) else np.zeros((0, 2))
        if np.any(np.isnan(arr)):
            raise ValueError(f"pairs in dimension {k} contain NaN")
        if np.any(arr[:, 1] < arr[:, 0]):
            raise ValueError(f"pairs in dimension {k} must have death >= birth")
        out[int(k)] = arr
    if dim is not None:
        d = int(dim)
    return out, d


def _select(P: dict, dims, d=None):
    if dims is None:  # every dimension, but not the always-empty H_d of a complex in R^d
        return [k for k in sorted(P) if len(P[k]) or d is None or k < d]
    dims = [dims] if isinstance(dims, (int, np.integer)) else list(dims)
    for k in dims:
        if k not in P:
            raise ValueError(f"dims: no pairs of dimension {k} (available: {sorted(P)})")
    return dims


def _range(P: dict, dims, tau=None):
    vals = [P[k][np.isfinite(P[k])] for k in dims if len(P[k])]
    vals = np.concatenate(vals) if vals else np.zeros(0)
    if tau is not None:
        vals = np.append(vals, tau)
    if len(vals) == 0:
        return 0.0, 1.0
    lo, hi = float(vals.min()), float(vals.max())
    if hi - lo < 1e-12:
        lo, hi = lo - 0.5, hi + 0.5
    return lo, hi


def _field(obj, *names):
    for n in names:
        if hasattr(obj, n):
            return getattr(obj, n)
    raise AttributeError(f"{type(obj).__name__} has none of the fields {names}")


def _check_tau(tau, name="tau"):
    if isinstance(tau, (list, tuple)):
        raise TypeError(
            f"{name} must be a real number, got a {type(tau).__name__}; computed features are "
            "passed by keyword: plot.voids(F, tau, voids=V), plot.pockets(F, tau, pockets=P)"
        )
    # drawing needs balls of finite radius
    return as_tau(tau, name, finite=True)


# ------------------------------------------------------------- persistence
def persistence_diagram(
    pairs_or_filtration: Filtration | Balls | dict[int, ArrayLike],
    *,
    dims: int | Sequence[int] | None = None,
    tau: float | None = None,
    min_persistence: float | None = None,
    ax: Axes | None = None,
    title: str = "Persistence diagram",
    dim: int | None = None,
    scale: str = "τ",
    unit: str | None = None,
) -> Figure:
    """The persistence diagram: one point (birth, death) per feature (Notes §23.1).

    Parameters
    ----------
    pairs_or_filtration : Filtration, Balls or dict
        A :class:`~shapelab.Filtration` (its :meth:`persistence` is called: pairs
        over :math:`\\mathbb{Z}/2`), :class:`~shapelab.Balls` (their filtration,
        built once and kept with them) or the dict ``{k: (p, 2) array}`` it returns (over
        any field, ``F.persistence(field=p)``).  Deaths may be ``inf`` (drawn on a
        dashed "∞" line at the top).
    dims : int or sequence of int, optional
        Homology dimensions to draw (default: all).
    tau : float, optional
        Shade the quadrant birth ≤ τ < death: the features *alive* at τ.
    min_persistence : float, optional
        Draw the band death − birth < ``min_persistence`` and grey out the points in
        it: what topological simplification removes.
    ax : Axes, optional
    title : str
    dim : int, optional
        Ambient dimension (names H₁ "holes" in 2D, "tunnels" in 3D); taken from the
        filtration's balls if not given.
    scale : str
        The name of the axes' quantity: ``"τ"`` (the growth time, default) or, for
        diagrams converted to radii, ``"ρ"``.
    unit : str, optional
        The same as ``scale``, under the name the other plots use
        (``plot.distance_matrix(..., unit="ρ")``); it wins when both are given.

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    barcode
        The same pairs as bars.
    shapelab.persistence.persistence
        The pairs drawn.

    References
    ----------
    .. [1] H. Edelsbrunner and J. L. Harer, *Computational Topology: An Introduction*,
           American Mathematical Society, 2010. doi:10.1090/mbk/069

    Examples
    --------
    >>> import shapelab as sl
    >>> fig = persistence_diagram(sl.alpha_filtration(sl.datasets.figure_23_1()))
    >>> type(fig).__name__
    'Figure'
    >>> print(sl.plot.alt_text(fig))
    Persistence diagram: birth against death τ, one marker shape per dimension. H₀ components: 13 pairs, 1 never dying, the most persistent finite one born at -0.64 and dead at 0.89; H₁ holes: 8 pairs, the most persistent finite one born at 0.482 and dead at 1.18.
    """
    P, d = _pairs_of(pairs_or_filtration, dim)
    dims = _select(P, dims, d)
    if tau is not None:
        tau = _check_tau(tau)
    if min_persistence is not None:
        min_persistence = as_finite_scalar(min_persistence, "min_persistence", nonnegative=True)
    fig, ax = axes(ax, size=(5.6, 5.0))
    with style():
        lo, hi = _range(P, dims, tau)
        pad = 0.06 * (hi - lo)
        inf_y = hi + 2 * pad
        lo_, hi_ = lo - pad, inf_y + pad
        xs = np.array([lo_, hi_])
        ax.fill_between(xs, lo_, xs, color="#eeeeee", zorder=0, lw=0)
        ax.plot(xs, xs, color=COLORS["muted"], lw=1, zorder=1)
        if min_persistence:
            ax.fill_between(
                xs,
                xs,
                xs + min_persistence,
                color=COLORS["muted"],
                alpha=0.25,
                lw=0,
                zorder=1,
                label=f"persistence < {min_persistence:g}",
            )
        if any(np.isinf(P[k][:, 1]).any() for k in dims):
            ax.axhline(inf_y, color=COLORS["muted"], ls="--", lw=1, zorder=1)
            ax.text(lo_, inf_y, " ∞", va="bottom", ha="left", color=COLORS["muted"])
        if tau is not None:
            ax.fill_between(
                [lo_, tau],
                tau,
                hi_,
                color=COLORS["accent"],
                alpha=0.12,
                lw=0,
                zorder=0,
                label=f"alive at {unit or scale} = {tau:g}",
            )
            ax.axvline(tau, color=COLORS["accent"], lw=1, ls=":")
            ax.axhline(tau, color=COLORS["accent"], lw=1, ls=":")
        for k in dims:
            a = P[k]
            y = np.where(np.isinf(a[:, 1]), inf_y, a[:, 1])
            small = (a[:, 1] - a[:, 0] < min_persistence) if min_persistence else np.zeros(len(a), bool)
            ax.scatter(
                a[~small, 0],
                y[~small],
                s=28,
                marker=_MARKERS[k % 4],
                color=_dim_color(k),
                edgecolor="white",
                linewidth=0.5,
                zorder=3,
                label=f"{_dim_label(k, d)} ({len(a)})",
            )
            if small.any():
                ax.scatter(
                    a[small, 0], y[small], s=14, marker=_MARKERS[k % 4], color=COLORS["muted"], alpha=0.6, zorder=2
                )
        ax.set_xlim(lo_, hi_)
        ax.set_ylim(lo_, hi_)
        ax.set_aspect("equal")
        ax.set_xlabel(f"birth {unit or scale}")
        ax.set_ylabel(f"death {unit or scale}")
        ax.set_title(title)
        ax.legend(loc="lower right", fontsize=9)
        describe(
            ax,
            f"{title}: birth against death {unit or scale}, one marker shape per dimension. "
            f"{_pairs_summary(P, dims, d)}"
            + (f"; features alive at {unit or scale} = {tau:g} shaded" if tau is not None else "")
            + (f"; pairs with persistence below {min_persistence:g} greyed" if min_persistence else ""),
        )
    return fig


def barcode(
    pairs_or_filtration: Filtration | Balls | dict[int, ArrayLike],
    *,
    dims: int | Sequence[int] | None = None,
    tau: float | None = None,
    min_persistence: float = 0.0,
    max_bars: int = 60,
    ax: Axes | None = None,
    title: str = "Barcode",
    dim: int | None = None,
) -> Figure:
    """The barcode: one horizontal bar [birth, death) per feature (Notes §23.1).

    Bars are grouped by homology dimension, longest first within a group is not
    imposed: they are sorted by birth, so the growth reads from left to right.

    Parameters
    ----------
    pairs_or_filtration : Filtration or dict
        As for :func:`persistence_diagram`.
    dims : int or sequence of int, optional
    tau : float, optional
        A vertical line at τ; the bars it crosses are the features alive at τ.
    min_persistence : float
        Leave out bars shorter than this (topological simplification).
    max_bars : int
        At most this many bars per dimension, the most persistent ones; the title
        says how many were left out.
    ax, title, dim
        As for :func:`persistence_diagram`.

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    persistence_diagram
        The same pairs as points.

    References
    ----------
    .. [1] H. Edelsbrunner and J. L. Harer, *Computational Topology: An Introduction*,
           American Mathematical Society, 2010. doi:10.1090/mbk/069

    Examples
    --------
    >>> import shapelab as sl
    >>> fig = barcode(sl.alpha_filtration(sl.datasets.figure_23_1()), tau=0.0)
    >>> type(fig).__name__
    'Figure'
    >>> print(sl.plot.alt_text(fig))
    Barcode: one horizontal bar per feature along the growth time τ, grouped and labelled by dimension. H₀ components: 13 pairs, 1 never dying, the most persistent finite one born at -0.64 and dead at 0.89; H₁ holes: 8 pairs, the most persistent finite one born at 0.482 and dead at 1.18; a dashed line at τ = 0.
    """
    P, d = _pairs_of(pairs_or_filtration, dim)
    dims = _select(P, dims, d)
    if tau is not None:
        tau = _check_tau(tau)
    min_persistence = as_finite_scalar(min_persistence, "min_persistence", nonnegative=True)
    if isinstance(max_bars, bool) or not isinstance(max_bars, (int, np.integer)) or max_bars < 1:
        raise ValueError(f"max_bars must be a positive integer, got {max_bars!r}")
    fig, ax = axes(ax)
    with style():
        lo, hi = _range(P, dims, tau)
        pad = 0.05 * (hi - lo)
        right = hi + 2 * pad
        y = 0
        hidden = 0
        yticks, ylabels, separators = [], [], []
        for k in dims:
            a = P[k]
            pers = a[:, 1] - a[:, 0]
            keep = pers >= min_persistence if min_persistence > 0 else np.ones(len(a), bool)
            a, pers = a[keep], pers[keep]
            if len(a) > max_bars:
                top = np.argsort(-pers, kind="stable")[:max_bars]
                hidden += len(a) - max_bars
                a = a[np.sort(top)]
            hidden += int((~keep).sum())
            order = np.lexsort((-a[:, 1], a[:, 0]))
            a = a[order]
            start = y
            finite = np.isfinite(a[:, 1])
            ends = np.where(finite, a[:, 1], right)
            ys = y + np.arange(len(a))
            ax.hlines(ys, a[:, 0], ends, color=_dim_color(k), lw=2.2)
            if (~finite).any():
                ax.scatter(ends[~finite], ys[~finite], marker=">", color=_dim_color(k), s=22, zorder=3)
            y += len(a)
            if len(a):
                yticks.append(0.5 * (start + y - 1))
                ylabels.append(_dim_label(k, d))
                separators.append(y)
            y += 1
        if tau is not None:
            ax.axvline(tau, color=COLORS["accent"], lw=1.2, ls="--", label=f"τ = {tau:g}")
            ax.legend(loc="lower right", fontsize=9)
        for s_ in separators[:-1]:  # a thin line between the groups of bars
            ax.axhline(s_, color="#dddddd", lw=0.8)
        ax.set_yticks(yticks, ylabels)
        ax.set_ylim(max(y - 1.5, 0.5), -1)
        ax.set_xlim(lo - pad, right + pad)
        ax.set_xlabel("growth time τ")
        ax.spines["left"].set_visible(False)
        ax.tick_params(axis="y", length=0)
        note = f" ({hidden} short bars not shown)" if hidden else ""
        ax.set_title(title + note)
        describe(
            ax,
            f"{title}: one horizontal bar per feature along the growth time τ, grouped and labelled by dimension. "
            f"{_pairs_summary(P, dims, d)}"
            + (f"; {hidden} short bars not shown" if hidden else "")
            + (f"; a dashed line at τ = {tau:g}" if tau is not None else ""),
        )
    return fig


def betti_curve(
    F_or_curve: Filtration | Balls | tuple[ArrayLike, ArrayLike],
    *,
    taus: ArrayLike | None = None,
    tau: float | None = None,
    log: bool | None = None,
    ax: Axes | None = None,
    title: str = "Betti numbers as the balls grow",
) -> Figure:
    """:math:`\\beta_k(\\tau)` against the growth time τ, one step curve per k.

    Parameters
    ----------
    F_or_curve : Filtration, Balls or (taus, curve)
        A filtration (its :meth:`betti_curve` is evaluated at ``taus``), the balls
        (their filtration, built once and kept with them) or a pair of
        arrays ``taus`` (m,) and ``curve`` (m, d + 1) already computed.
    taus : array_like, optional
        Where to evaluate; default: every entry time of the filtration up to the
        last finite death (so that every change shows), plus a margin.
    tau : float, optional
        Mark one τ with a vertical line.
    log : bool, optional
        A symmetric-log y axis, so that a few features late in the growth stay
        visible next to hundreds of tiny ones early on; default: when some
        :math:`\\beta_k > 20`.
    ax, title

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.persistence.betti_curve
        The numbers drawn.

    Examples
    --------
    >>> import shapelab as sl
    >>> fig = betti_curve(sl.alpha_filtration(sl.datasets.ring(12)))
    >>> type(fig).__name__
    'Figure'
    >>> print(sl.plot.alt_text(fig))
    Betti numbers as the balls grow: step curves of the Betti numbers against the growth time τ from -1.72 to 8.72, one line style per dimension. β₀ peaks at 12 (τ = -1) and ends at 1; β₁ peaks at 5 (τ = 8) and ends at 0.
    """
    if isinstance(F_or_curve, Balls):
        F_or_curve = as_filtration(F_or_curve, "plot.betti_curve")
    if isinstance(F_or_curve, tuple) and len(F_or_curve) == 2:
        t = np.asarray(F_or_curve[0], dtype=np.float64).reshape(-1)
        curve = np.asarray(F_or_curve[1])
        if curve.ndim != 2 or curve.shape[0] != len(t):
            raise ValueError(f"curve must have shape (len(taus), d + 1) = ({len(t)}, ...), got {curve.shape}")
        d = curve.shape[1] - 1
    elif hasattr(F_or_curve, "betti_curve"):
        F = F_or_curve
        d = F.balls.dim
        if taus is None:
            vals = (
                np.concatenate([np.asarray(F.values(k)) for k in range(F.dimension + 1)])
                if F.dimension >= 0
                else np.zeros(1)
            )
            P = F.persistence()
            deaths = np.concatenate([np.asarray(a)[:, 1] for a in P.values() if len(a)] or [np.zeros(0)])
            births = vals.min() if len(vals) else 0.0
            stop = deaths[np.isfinite(deaths)].max() if np.isfinite(deaths).any() else vals.max()
            stop = max(stop, births + 1e-9)
            margin = 0.08 * (stop - births)
            t = np.unique(np.concatenate([vals[(vals >= births) & (vals <= stop)], [births - margin, stop + margin]]))
        else:
            t = np.sort(np.asarray(taus, dtype=np.float64).reshape(-1))
        curve = np.asarray(F.betti_curve(t))
    else:
        raise TypeError(
            f"F_or_curve must be a Filtration, Balls or a (taus, curve) pair, got {type(F_or_curve).__name__}"
        )
    if not np.all(np.isfinite(t)):
        raise ValueError("taus must be finite")
    if tau is not None:
        tau = _check_tau(tau)
    fig, ax = axes(ax)
    with style():
        for k in range(curve.shape[1]):
            if k == d and not curve[:, k].any():
                continue  # β_d of a complex in R^d is always 0
            ax.step(
                t,
                curve[:, k],
                where="post",
                color=_dim_color(k),
                ls=_LINESTYLES[k % len(_LINESTYLES)],
                lw=1.8,
                label=f"β{_SUB[k] if k < 4 else k} ({_dim_label(k, d).split(' ', 1)[1]})",
            )
        if tau is not None:
            ax.axvline(tau, color=COLORS["accent"], ls="--", lw=1.2)
        if log is None:
            log = bool(curve.size) and int(curve.max()) > 20
        if log:
            ax.set_yscale("symlog", linthresh=1.0, linscale=0.6)
            ax.set_ylim(bottom=-0.2)
        else:
            ax.yaxis.set_major_locator(MaxNLocator(integer=True))
        ax.set_xlabel("growth time τ")
        ax.set_ylabel("Betti number" + (" (symlog scale)" if log else ""))
        ax.set_title(title)
        ax.legend(loc="upper right")
        peaks = [
            f"β{_SUB[k] if k < 4 else k} peaks at {int(curve[:, k].max())} (τ = {t[int(np.argmax(curve[:, k]))]:.3g}) "
            f"and ends at {int(curve[-1, k])}"
            for k in range(curve.shape[1])
            if not (k == d and not curve[:, k].any()) and len(t)
        ]
        describe(
            ax,
            f"{title}: step curves of the Betti numbers against the growth time τ from {t[0]:.3g} to "
            f"{t[-1]:.3g}, one line style per dimension. " + "; ".join(peaks),
        )
    return fig


# ------------------------------------------------------------------ drawing
def _draw_disks(ax, balls, tau, *, highlight=None, alpha=1.0, zorder=2):
    r, ok = grown_radii(balls, tau), balls.weights + tau > 0
    c = balls.centers
    patches = [Circle(c[i], r[i]) for i in np.flatnonzero(ok)]
    face = np.tile(np.array(_rgba(COLORS["ball"], alpha)), (len(patches), 1))
    if highlight is not None and len(patches):
        hl = np.zeros(len(balls), bool)
        hl[np.asarray(highlight, dtype=np.int64)] = True
        face[hl[ok]] = _rgba("#a6d7f2", alpha)
    ax.add_collection(
        PatchCollection(patches, facecolors=face, edgecolors=COLORS["ball_edge"], linewidths=0.6, zorder=zorder)
    )
    ax.scatter(c[:, 0], c[:, 1], s=3, color=COLORS["ball_edge"], zorder=zorder + 0.1)
    lo = (c - r[:, None]).min(0)
    hi = (c + r[:, None]).max(0)
    pad = 0.05 * (hi - lo).max()
    ax.set_xlim(lo[0] - pad, hi[0] + pad)
    ax.set_ylim(lo[1] - pad, hi[1] + pad)
    ax.set_aspect("equal")
    ax.set_xlabel("x")
    ax.set_ylabel("y")


def _rgba(color, alpha=1.0):
    from matplotlib.colors import to_rgba

    return to_rgba(color, alpha)


def _draw_complex_2d(ax, F, tau):
    K = F.complex_at(tau)
    c = F.balls.centers
    E = np.asarray(K.simplices(1))
    T = np.asarray(K.simplices(2))
    if len(T):
        ax.add_collection(PolyCollection(c[T], facecolors=_rgba(COLORS["triangle"], 0.25), edgecolors="none", zorder=3))
    if len(E):
        ax.add_collection(LineCollection(c[E], colors=COLORS["complex"], linewidths=0.7, zorder=3))


def _cells_of(feature):
    return np.asarray(_field(feature, "cells"), dtype=np.int64)


def _lining_of(feature):
    return np.asarray(_field(feature, "lining", "lining_balls", "balls_lining"), dtype=np.int64).reshape(-1)


def _measure_word(d):
    return "area" if d == 2 else "volume"


def _label_point(balls, cells):
    """A point to label a feature: the centroid of its largest cell."""
    pts = balls.centers[cells]
    if balls.dim == 2:
        e1, e2 = pts[:, 1] - pts[:, 0], pts[:, 2] - pts[:, 0]
        size = np.abs(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0])
    else:
        size = np.abs(np.linalg.det(pts[:, 1:] - pts[:, :1]))
    return pts[int(np.argmax(size))].mean(0)


def _setup_3d(ax, balls, elev, azim, around=None):
    """Equal 3D axes around all balls, or around the balls ``around`` (indices) only."""
    c = balls.centers if around is None else balls.centers[around]
    lo, hi = c.min(0), c.max(0)
    mid = 0.5 * (lo + hi)
    half = 0.5 * (hi - lo).max() + balls.radii.max()
    set_3d_view(ax, mid - half, mid + half, elev, azim, cube=True)
    return half


def _draw_balls_3d(ax, balls, tau, *, highlight=None, half=1.0, box=None):
    """Balls as depth-shaded discs; lining balls darker and smaller so that the
    features drawn after them (on top: the axes do not sort by depth) stay visible.
    With ``box`` (lo, hi), only the balls whose centres lie in it (the axes of a
    zoomed view do not clip what lies beyond them)."""
    r, ok = grown_radii(balls, tau), balls.weights + tau > 0
    c = balls.centers
    if box is not None:
        ok = ok & np.all((c >= box[0]) & (c <= box[1]), axis=1)
    fig = ax.get_figure()
    # marker area in points^2 so that a marker's diameter is about the ball's
    width_pt = 72.0 * fig.get_size_inches()[0] * 0.55
    s = (2 * r / (2 * half) * width_pt * 0.75) ** 2
    base = ok.copy()
    if highlight is not None:
        base[np.asarray(highlight, dtype=np.int64)] = False
    ax.scatter(
        *c[base].T,
        s=s[base],
        color=COLORS["ball"],
        alpha=0.3 if highlight is None else 0.12,
        edgecolors="none",
        depthshade=True,
        zorder=1,
    )
    if highlight is None:  # the centres: the structure shows through the blur (tunnel figures)
        ax.scatter(
            *c[base].T, s=5, color=COLORS["ball_edge"], alpha=0.8, edgecolors="none", depthshade=False, zorder=1.5
        )
    if highlight is not None and len(highlight):
        h = np.asarray(highlight, dtype=np.int64)
        h = h[ok[h]]
        ax.scatter(
            *c[h].T,
            s=s[h] * 0.2,
            color=COLORS["ball_edge"],
            alpha=0.55,
            edgecolors="white",
            linewidths=0.3,
            depthshade=True,
            zorder=2,
        )


def _features_or_compute(F, features, tau, fn_name, **kw):
    """The features given, or those computed from ``F`` at ``tau`` (the filtration keeps
    its merge tree and cycles, so this costs little once it has been asked)."""
    if features is None:
        from .. import cavities

        return list(getattr(cavities, fn_name)(F, tau, **kw))
    return list(features)


def voids(
    F: Filtration | Balls,
    tau: float = 0.0,
    *,
    voids: Sequence[Void] | None = None,
    ax: Axes | None = None,
    show_complex: bool = False,
    elev: float = 20,
    azim: float = 35,
    title: str | None = None,
    show_volumes: bool | None = None,
    legend: bool = True,
) -> Figure:
    """Draw the voids of the union of balls grown to τ (holes in 2D, Notes §23.1).

    A void is a bounded component of :math:`\\mathbb{R}^d \\setminus \\bigcup B_i`; it is
    drawn as the top simplices of DT it consists of (2D: filled triangles under the
    opaque disks, so the free space shows; 3D: its boundary triangles, inside
    see-through balls), with its lining balls highlighted.

    Parameters
    ----------
    F : Filtration
        ``alpha_filtration(balls)`` (a :class:`~shapelab.Balls` is accepted too, as
        by :func:`shapelab.voids`); the balls drawn are ``F.balls``.
    tau : float
        Growth time at which to draw the balls (radii :math:`\\sqrt{r^2+\\tau}`).
    voids : sequence of Void, optional
        ``shapelab.voids(F, tau)``, if already computed; computed from ``F`` if not.
    ax : Axes, optional (a 3D Axes for 3D balls)
    show_complex : bool
        2D only: also draw the dual complex :math:`K_\\tau` (edges and triangles).
    elev, azim : float
        3D view.
    title : str, optional
    show_volumes : bool, optional
        Write each feature's area/volume in the legend (default: in 2D only, since
        an exact pocket volume in 3D can take seconds).
    legend : bool
        Draw a legend (outside on the right of a new figure, inside a given ``ax``).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.voids
        The voids drawn.

    Notes
    -----
    In 3D the free space is shown as a cloud of points: uniform samples of the
    void's cells kept where no grown ball covers them.  The cells themselves would
    draw the void of :math:`K_\\tau`, which is much larger than the void of the union.

    Examples
    --------
    >>> import shapelab as sl
    >>> fig = voids(sl.alpha_filtration(sl.datasets.ring(12)), tau=0.0)
    >>> type(fig).__name__
    'Figure'
    >>> print(sl.plot.alt_text(fig))
    1 hole at τ = 0: the 12 disks grown to τ = 0; hole V1 (10 cells, area 13.60), each hole named in the legend and on the figure, lining balls highlighted.
    """
    F = as_filtration(F, "plot.voids")
    balls = F.balls
    tau = _check_tau(tau)
    V = _features_or_compute(F, voids, tau, "voids")
    word = "hole" if balls.dim == 2 else "void"
    title = title or f"{len(V)} {word}{'s' if len(V) != 1 else ''} at τ = {tau:g}"
    return _draw_features(
        F,
        tau,
        V,
        [],
        [],
        ax=ax,
        show_complex=show_complex,
        elev=elev,
        azim=azim,
        title=title,
        show_volumes=show_volumes,
        legend=legend,
    )


def pockets(
    F: Filtration | Balls,
    tau: float = 0.0,
    *,
    pockets: Sequence[Pocket] | None = None,
    voids: Sequence[Void] | None = None,
    show_voids: bool = True,
    ax: Axes | None = None,
    show_complex: bool = False,
    min_persistence: float = 1e-9,
    elev: float = 20,
    azim: float = 35,
    title: str | None = None,
    show_volumes: bool | None = None,
    legend: bool = True,
    focus: bool = False,
    numbers: bool | None = None,
) -> Figure:
    """Draw the pockets of the growth model at τ with their mouths (Notes §23.1, Fig. 23.2).

    A pocket is a region of the complement still connected to the outside at τ that
    becomes a void later, when its mouth closes.  Each pocket's cells are filled in a
    colour of its own, its mouth — the (d−1)-simplices joining it to the outside —
    drawn as thick pink edges (2D) or triangles (3D), and its lining balls highlighted.

    Parameters
    ----------
    F : Filtration
        ``alpha_filtration(balls)`` (or the :class:`~shapelab.Balls`), as for :func:`voids`.
    tau : float
    pockets : sequence of Pocket, optional
        ``shapelab.pockets(F, tau, ...)``, if already computed; computed from ``F``
        (with ``min_persistence``) if not.
    voids : sequence of Void, optional
        Voids to draw too (computed at τ if ``show_voids`` and not given).
    show_voids : bool
    ax, show_complex, elev, azim, title, show_volumes, legend
        As for :func:`voids`.
    min_persistence : float, default 1e-9
        Passed to :func:`shapelab.pockets` when computing (the default leaves out
        pockets that close and fill at the same τ up to round-off).
    focus : bool, default False
        3D: zoom on the features drawn (the box of their lining balls) and draw only
        the balls in it, for a close-up of one pocket; otherwise each pocket is
        named (P1, P2, ...) beside its free space.
    numbers : sequence of int, optional
        The pockets' numbers, which also pick their colours (default 1, 2, ...): a
        close-up of one pocket passes its number in the overview, so that both
        name and colour it alike.

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.pockets
        The pockets drawn.
    pocket_gallery
        In 3D.

    Examples
    --------
    >>> import shapelab as sl
    >>> fig = pockets(sl.alpha_filtration(sl.datasets.figure_23_2()[0]), tau=0.0)
    >>> type(fig).__name__
    'Figure'
    >>> print(sl.plot.alt_text(fig))
    1 pocket, 0 holes at τ = 0: the 112 disks grown to τ = 0; pocket P1 (9 cells, area 10.75, a mouth of 1 edge), each pocket named in the legend and on the figure, lining balls highlighted.
    """
    F = as_filtration(F, "plot.pockets")
    balls = F.balls
    tau = _check_tau(tau)
    Pk = _features_or_compute(F, pockets, tau, "pockets", min_persistence=min_persistence)
    V = _features_or_compute(F, voids, tau, "voids") if show_voids else []
    word = "hole" if balls.dim == 2 else "void"
    if title is None:
        title = f"{len(Pk)} pocket{'s' if len(Pk) != 1 else ''}"
        if show_voids:
            title += f", {len(V)} {word}{'s' if len(V) != 1 else ''}"
        title += f" at τ = {tau:g}"
    return _draw_features(
        F,
        tau,
        V,
        Pk,
        [],
        ax=ax,
        show_complex=show_complex,
        elev=elev,
        azim=azim,
        title=title,
        show_volumes=show_volumes,
        legend=legend,
        focus=focus,
        numbers=numbers,
    )


def pocket_gallery(
    F: Filtration | Balls,
    tau: float = 0.0,
    *,
    pockets: Sequence[Pocket] | None = None,
    voids: Sequence[Void] | None = None,
    min_persistence: float = 1e-9,
    elev: float = 20,
    azim: float = 35,
    title: str | None = None,
) -> Figure:
    """The pockets of a 3D molecule: an overview beside a close-up of each (Notes §23.1).

    Pockets of a protein often sit side by side in one groove, and in one 3D view
    they hide each other.  The overview (left) draws all of them with the voids,
    each named P1, P2, ... beside its free space; on the right one panel per pocket
    zooms on it alone (:func:`pockets` with ``focus=True``), in the same colour and
    under the same name, with its cell and mouth counts.

    Parameters
    ----------
    F : Filtration
        ``alpha_filtration(balls)`` of 3D balls (or the :class:`~shapelab.Balls`).
    tau : float
    pockets, voids : sequence, optional
        As for :func:`pockets` (computed at τ if not given).
    min_persistence : float
        Passed to :func:`shapelab.pockets` when computing.
    elev, azim : float
        The view of every panel.
    title : str, optional
        The overview's title (default: the counts).

    Returns
    -------
    matplotlib.figure.Figure
        Slide-sized; up to six close-ups (two columns).

    See Also
    --------
    pockets
        In 2D.
    shapelab.plot.view3d
        An interactive view.
    """
    import matplotlib.pyplot as plt

    draw = globals()["pockets"]  # the function; the argument of that name holds features
    F = as_filtration(F, "plot.pocket_gallery")
    tau = _check_tau(tau)
    if F.balls.dim != 3:
        raise ValueError(f"pocket_gallery draws 3D molecules, got dim={F.balls.dim}; use pockets() in 2D")
    Pk = _features_or_compute(F, pockets, tau, "pockets", min_persistence=min_persistence)
    V = _features_or_compute(F, voids, tau, "voids")
    if not Pk:
        raise ValueError("pocket_gallery: there is no pocket at this tau to draw")
    shown = Pk[:6]
    rows = 2 if len(shown) > 1 else 1
    cols = (len(shown) + rows - 1) // rows
    if title is None:
        title = f"{len(Pk)} pocket{'s' if len(Pk) != 1 else ''} and {len(V)} void{'s' if len(V) != 1 else ''} at τ = {tau:g}"
    with style():
        fig = plt.figure(figsize=SLIDE, layout="constrained")
        grid = fig.add_gridspec(rows, 2 + cols, width_ratios=[1.3, 1.3] + [1] * cols)
        overview = fig.add_subplot(grid[:, :2], projection="3d")
        draw(F, tau, pockets=Pk, voids=V, ax=overview, legend=False, title=title, elev=elev, azim=azim)
        for k, p in enumerate(shown):
            ax = fig.add_subplot(grid[k // cols, 2 + k % cols], projection="3d")
            draw(
                F,
                tau,
                pockets=[p],
                numbers=[k + 1],
                show_voids=False,
                focus=True,
                legend=False,
                ax=ax,
                elev=elev,
                azim=azim,
                title=f"P{k + 1}: {len(_cells_of(p))} cells\nmouth of {len(_field(p, 'mouth'))} triangles",
            )
            ax.title.set_fontsize(11)
            ax.set_axis_off()
    return fig


def tunnels(
    F: Filtration | Balls,
    tau: float = 0.0,
    *,
    tunnels: Sequence[Tunnel] | None = None,
    ax: Axes | None = None,
    show_complex: bool = False,
    elev: float = 20,
    azim: float = 35,
    title: str | None = None,
    legend: bool = True,
) -> Figure:
    """Draw the tunnels alive at τ: a representative cycle of each H₁ class (Notes §23.1).

    Parameters
    ----------
    F : Filtration
        ``alpha_filtration(balls)`` of 3D balls (or the :class:`~shapelab.Balls`), as
        for :func:`voids`.
    tau : float
    tunnels : sequence of Tunnel, optional
        ``shapelab.tunnels(F, tau)``, if already computed; computed from ``F`` if not.
        Each cycle is a closed chain of edges between ball centres, drawn as a thick line.
    ax, show_complex, elev, azim, title, legend
        As for :func:`voids`.

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.tunnels
        The tunnels drawn.

    Examples
    --------
    >>> import shapelab as sl
    >>> fig = tunnels(sl.alpha_filtration(sl.datasets.ring(12, dim=3)), tau=0.0)
    >>> type(fig).__name__
    'Figure'
    >>> print(sl.plot.alt_text(fig))
    3D view of 1 tunnel at τ = 0: the 12 balls grown to τ = 0; tunnel 1: a cycle of 12 edges.
    """
    F = as_filtration(F, "plot.tunnels")
    tau = _check_tau(tau)
    T = _features_or_compute(F, tunnels, tau, "tunnels")
    title = title or f"{len(T)} tunnel{'s' if len(T) != 1 else ''} at τ = {tau:g}"
    return _draw_features(
        F, tau, [], [], T, ax=ax, show_complex=show_complex, elev=elev, azim=azim, title=title, legend=legend
    )


def _cycle_edges(t):
    e = np.asarray(_field(t, "cycle", "edges", "cycle_edges"), dtype=np.int64)
    return e.reshape(-1, 2)


def _feature_label(kind, i, f, d, show_volumes):
    if not show_volumes:
        return f"{kind}{i}"
    try:
        vol = float(_field(f, "volume"))
    except AttributeError:
        return f"{kind}{i}"
    return f"{kind}{i}: {_measure_word(d)} {vol:.2f}"


#: orange, bluish green, indigo, black, yellow: none is the balls' blue, the voids'
#: vermillion or the mouths' reddish purple
_POCKET_COLORS = (PALETTE[1], PALETTE[2], "#332288", PALETTE[7], PALETTE[6])


def _pocket_color(i: int) -> str:
    return _POCKET_COLORS[(i - 1) % len(_POCKET_COLORS)]


def _draw_features(
    F, tau, V, Pk, T, *, ax, show_complex, elev, azim, title, show_volumes=None, legend=True, focus=False, numbers=None
):
    from ..cavities.freespace import free_points

    balls = F.balls
    d = balls.dim
    own_figure = ax is None
    want_legend = legend
    show_volumes = (d == 2) if show_volumes is None else bool(show_volumes)
    legend = []
    c = balls.centers
    void_word = "hole" if d == 2 else "void"
    nums = list(range(1, len(Pk) + 1)) if numbers is None else [int(k) for k in numbers]
    if len(nums) != len(Pk):
        raise ValueError(f"numbers must give one number per pocket: {len(nums)} for {len(Pk)} pockets")
    lining = [_lining_of(f) for f in list(V) + list(Pk)]
    hl = np.unique(np.concatenate(lining)) if lining else None
    if d == 2:
        fig, ax = axes(ax, size=(6.8, 5.0))
        with style():
            _draw_disks(ax, balls, tau, highlight=hl, zorder=2)
            for i, v in enumerate(V, 1):
                cells = _cells_of(v)
                ax.add_collection(
                    PolyCollection(c[cells].reshape(-1, 3, 2), facecolors=COLORS["void"], edgecolors="none", zorder=1)
                )
                legend.append(
                    Patch(color=COLORS["void"], label=f"{void_word} " + _feature_label("V", i, v, d, show_volumes))
                )
                _tag(ax, balls, cells, f"V{i}")
            # larger pockets first, so that nested ones show on top of them
            order = sorted(range(len(Pk)), key=lambda j: -len(_cells_of(Pk[j])))
            for k, (i, p) in enumerate(zip(nums, Pk)):
                cells = _cells_of(p)
                ax.add_collection(
                    PolyCollection(
                        c[cells].reshape(-1, 3, 2),
                        facecolors=_pocket_color(i),
                        edgecolors="none",
                        zorder=1 + 0.01 * order.index(k),
                    )
                )
                mouth = np.asarray(_field(p, "mouth"), dtype=np.int64).reshape(-1, 2)
                if len(mouth):
                    ax.add_collection(
                        LineCollection(c[mouth], colors=COLORS["mouth"], linewidths=3.0, zorder=4, capstyle="round")
                    )
                legend.append(
                    Patch(color=_pocket_color(i), label="pocket " + _feature_label("P", i, p, d, show_volumes))
                )
                _tag(ax, balls, cells, f"P{i}")
            if show_complex:
                _draw_complex_2d(ax, F, tau)
            for t in T:
                e = _cycle_edges(t)
                ax.add_collection(LineCollection(c[e], colors=COLORS["void"], linewidths=2.5, zorder=5))
            ax.set_title(title)
    else:
        from mpl_toolkits.mplot3d.art3d import Line3DCollection, Poly3DCollection

        fig, ax = axes(ax, size=(6.8, 5.6), projection="3d")
        ax.computed_zorder = False  # draw in the order given: features on top of the balls
        rng = np.random.default_rng(0)
        with style():
            around = hl if focus and hl is not None and len(hl) else None
            half = _setup_3d(ax, balls, elev, azim, around=around)
            box = None
            if around is not None:
                mid = 0.5 * (c[around].min(0) + c[around].max(0))
                box = (mid - half, mid + half)
            _draw_balls_3d(ax, balls, tau, highlight=hl, half=half, box=box)
            for i, v in enumerate(V, 1):
                pts = free_points(balls, tau, _cells_of(v), 3000, rng)
                ax.scatter(*pts.T, s=3, color=COLORS["void"], alpha=0.9, depthshade=False, zorder=3)
                if Pk and not focus and len(pts):  # beside pockets, name the voids too
                    _tag3d(ax, pts, f"V{i}", COLORS["void"])
                legend.append(
                    Patch(color=COLORS["void"], label=f"{void_word} " + _feature_label("V", i, v, d, show_volumes))
                )
            for i, p in zip(nums, Pk):
                pts = free_points(balls, tau, _cells_of(p), 3000, rng)
                ax.scatter(*pts.T, s=3, color=_pocket_color(i), alpha=0.9, depthshade=False, zorder=3)
                if not focus and len(pts):
                    _tag3d(ax, pts, f"P{i}", _pocket_color(i))
                mouth = np.asarray(_field(p, "mouth"), dtype=np.int64).reshape(-1, 3)
                if len(mouth):
                    ax.add_collection3d(
                        Poly3DCollection(
                            c[mouth],
                            facecolors=_rgba(COLORS["mouth"], 0.2),
                            edgecolors=_rgba(COLORS["mouth"], 0.8),
                            linewidths=0.4,
                            zorder=4,
                        )
                    )
                legend.append(
                    Patch(color=_pocket_color(i), label="pocket " + _feature_label("P", i, p, d, show_volumes))
                )
            for t in T:
                e = _cycle_edges(t)
                ax.add_collection3d(Line3DCollection(c[e], colors=COLORS["void"], linewidths=3.0, zorder=5))
            ax.set_title(title)
    if Pk:
        legend.append(Line2D([], [], color=COLORS["mouth"], lw=3, label="mouth"))
    if T:
        legend.append(Line2D([], [], color=COLORS["void"], lw=2.5, label="tunnel cycle"))
    if show_complex and d == 2:
        legend.append(Line2D([], [], color=COLORS["complex"], lw=0.8, label="K(τ)"))
    if hl is not None and len(hl):
        legend.append(
            Patch(
                facecolor="#a6d7f2" if d == 2 else COLORS["ball_edge"],
                edgecolor=COLORS["ball_edge"],
                label="lining balls",
            )
        )
    describe(ax, _features_text(balls, tau, V, Pk, T, nums, title, show_volumes, focus, bool(legend and want_legend)))
    if legend and want_legend:
        with style():
            if own_figure:  # outside, to the right; constrained layout makes room
                fig.legend(handles=legend, loc="outside right upper", fontsize=9)
            else:  # drawing into a panel of a bigger figure
                ax.legend(handles=legend, loc="lower left", fontsize=8, framealpha=0.85, frameon=True)
    return fig


def _features_text(balls, tau, V, Pk, T, nums, title, show_volumes, focus, legend=True) -> str:
    """What :func:`_draw_features` drew, in words."""
    d = balls.dim
    void_word = "hole" if d == 2 else "void"
    kind = "disks" if d == 2 else "balls"
    view = "" if d == 2 else "3D view of "
    text = f"{view}{title}: the {len(balls)} {kind} grown to τ = {tau:g}"
    parts = []

    def size(f):
        n = len(_cells_of(f))
        out = f"{n} cell{'s' if n != 1 else ''}"
        if show_volumes:
            try:
                out += f", {_measure_word(d)} {float(_field(f, 'volume')):.2f}"
            except AttributeError:
                pass
        return out

    for i, v in enumerate(V, 1):
        parts.append(f"{void_word} V{i} ({size(v)})")
    for i, p in zip(nums, Pk):
        m = len(np.asarray(_field(p, "mouth")).reshape(-1, d))
        side = "edge" if d == 2 else "triangle"
        parts.append(f"pocket P{i} ({size(p)}, a mouth of {m} {side}{'s' if m != 1 else ''})")
    for i, t in enumerate(T, 1):
        m = len(_cycle_edges(t))
        parts.append(f"tunnel {i}: a cycle of {m} edge{'s' if m != 1 else ''}")
    if parts:
        text += "; " + ", ".join(parts)
        # what _draw_features tags by name on the figure: in 2D the voids and pockets; in 3D
        # the pockets, and the voids only beside pockets; a close-up and the tunnels, none
        if V or Pk:
            tagged = d == 2 or (not focus and (Pk or not V))
            where = [w for w, yes in (("in the legend", legend), ("on the figure", tagged)) if yes]
            if where:
                text += f", each {void_word if not Pk else 'pocket' if not V else 'feature'} named " + " and ".join(
                    where
                )
            text += ", lining balls highlighted"
    else:
        text += "; none of the features is present"
    if focus:
        text += "; a close-up"
    return text


def _tag3d(ax, pts, text, color):
    """Name a 3D feature beside its points, offset outwards so it hides none of them."""
    centre = ax.get_w_lims()
    mid = np.array([(centre[0] + centre[1]) / 2, (centre[2] + centre[3]) / 2, (centre[4] + centre[5]) / 2])
    x = pts.mean(0)
    out = x - mid
    n = np.linalg.norm(out)
    x = x + (out / n if n > 0 else np.array([0.0, 0.0, 1.0])) * (0.5 * np.ptp(pts, axis=0).max() + 1.5)
    ax.text(
        *x,
        text,
        color="white",
        fontsize=11,
        fontweight="bold",
        ha="center",
        va="center",
        zorder=7,
        bbox=dict(boxstyle="round,pad=0.2", facecolor=color, edgecolor="none", alpha=0.95),
    )


def _tag(ax, balls, cells, text):
    if not len(cells):
        return
    x = _label_point(balls, cells)
    ax.annotate(text, x, ha="center", va="center", fontsize=8, zorder=6, color="white", fontweight="bold")


def channel_profile(
    profile: ChannelProfile, *, reference: dict | None = None, ax: Axes | None = None, title: str | None = None
) -> Figure:
    """The free radius along a channel (:func:`shapelab.channel_profile`), bottleneck marked.

    Parameters
    ----------
    profile : ChannelProfile
    reference : dict of str → float, optional
        Radii to draw as horizontal lines (e.g. the bottleneck the tunnel's death gives).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.channel_profile
        The profile drawn.

    Examples
    --------
    >>> import numpy as np
    >>> import shapelab as sl
    >>> balls = sl.datasets.ring(8, radius=3.0, disk_radius=1.0, dim=3)
    >>> profile = sl.channel_profile(balls, [0.0, 0.0, 0.0], [0.0, 0.0, 1.0], np.linspace(-2.0, 2.0, 5))
    >>> fig = channel_profile(profile)
    >>> type(fig).__name__
    'Figure'
    >>> print(sl.plot.alt_text(fig))
    Free radius along the channel: the free radius against the position along the axis, from -2.0 to 2.0 Å; the bottleneck, 2.00 Å at 0.0 Å, marked with a dot.
    """
    if not all(hasattr(profile, a) for a in ("offsets", "radius", "bottleneck")):
        raise TypeError(f"profile must be a ChannelProfile, got {type(profile).__name__}")
    if ax is None:
        fig, ax = new_figure()
    else:
        fig = ax.get_figure()
    with style():
        ax.plot(profile.offsets, profile.radius, color=PALETTE[0], lw=2, label="free radius")
        k = int(np.argmin(profile.radius))
        ax.plot(
            profile.offsets[k],
            profile.radius[k],
            "o",
            color=PALETTE[3],
            ms=9,
            label=f"bottleneck {profile.radius[k]:.2f} Å",
        )
        for j, (label, value) in enumerate((reference or {}).items()):
            ax.axhline(float(value), color=PALETTE[(j + 1) % len(PALETTE)], ls="--", lw=1.5, label=label)
        ax.set_xlabel("position along the axis (Å)")
        ax.set_ylabel("radius (Å)")
        ax.set_ylim(bottom=0)
        ax.legend(loc="upper center", frameon=False)
        ax.set_title(title or "Free radius along the channel")
        refs = "; ".join(f"{label}: {float(v):.2f} Å (dashed)" for label, v in (reference or {}).items())
        describe(
            ax,
            f"{title or 'Free radius along the channel'}: the free radius against the position along the axis, "
            f"from {profile.offsets[0]:.1f} to {profile.offsets[-1]:.1f} Å; the bottleneck, "
            f"{profile.radius[k]:.2f} Å at {profile.offsets[k]:.1f} Å, marked with a dot"
            + (f"; reference radii {refs}" if refs else ""),
        )
    return fig


# ==================================================== boundary matrix, voxel slices
def reduced_matrix(
    D: ArrayLike, R: ArrayLike, names: Sequence[str], low: ArrayLike | None = None, *, title: str | None = None
) -> Figure:
    """The boundary matrix :math:`D` and its reduction :math:`R` side by side, with the
    lowest ones of :math:`R` in red and crossed (Notes §23.1; the persistence algorithm
    of Edelsbrunner, Letscher and Zomorodian 2002).

    Parameters
    ----------
    D, R : array_like or scipy sparse matrix, shape (n, n)
        The boundary matrix over :math:`\\mathbb{Z}/2` (``F.boundary_matrix().matrix``)
        and its reduction (:func:`shapelab.persistence.reduce_boundary`).
    names : sequence of str
        The simplices in filtration order, for the rows and the columns.
    low : array_like of int, optional
        The row of each column's lowest one, ``-1`` for a zero column (the second
        result of :func:`~shapelab.persistence.reduce_boundary`); computed from ``R`` if
        not given.
    title : str, optional
        The figure's title.

    Returns
    -------
    matplotlib.figure.Figure
        Two panels, described for their text alternative.

    Raises
    ------
    ValueError
        If the matrices are not square of the size of ``names``.

    See Also
    --------
    shapelab.persistence.reduce_boundary : the reduction drawn.
    persistence_diagram : the pairs read off the lowest ones.

    References
    ----------
    .. [1] H. Edelsbrunner, D. Letscher and A. Zomorodian, "Topological persistence and
       simplification", Discrete Comput. Geom. 28 (2002) 511-533.

    Examples
    --------
    >>> import numpy as np, shapelab as sl
    >>> from shapelab.persistence import reduce_boundary
    >>> F = sl.alpha_filtration(sl.Balls([[0, 0], [2, 0], [1, 1.6]], 0.5))
    >>> B = F.boundary_matrix()
    >>> R, low = reduce_boundary(B.matrix)
    >>> names = ["".join(map(str, F.simplices(k)[r])) for k, r in zip(B.dims, B.rows)]
    >>> fig = sl.plot.reduced_matrix(B.matrix, R, names, low)
    >>> len(fig.axes)
    2
    """
    from matplotlib.colors import ListedColormap

    dense = [np.asarray(M.toarray() if hasattr(M, "toarray") else M) % 2 for M in (D, R)]
    n = len(names)
    if any(M.shape != (n, n) for M in dense):
        raise ValueError(f"reduced_matrix: D and R must be {n} x {n} (one row and column per name)")
    Rl = dense[1].astype(np.int64)
    if low is None:
        low = np.array([int(np.flatnonzero(c)[-1]) if c.any() else -1 for c in dense[1].T], dtype=np.int64)
    low = np.asarray(low, dtype=np.int64)
    j = np.flatnonzero(low >= 0)
    Rl[low[j], j] = 2
    fig, axes_ = new_figure(1, 2, size=SLIDE)
    cmap = ListedColormap(["white", COLORS["ball_edge"], COLORS["red"]])
    for ax, M, sub in (
        (axes_[0], dense[0], "D, the boundary matrix"),
        (axes_[1], Rl, "R, reduced: lowest ones in red, crossed"),
    ):
        ax.imshow(M, cmap=cmap, vmin=0, vmax=2)
        ax.set_xticks(range(n), names, rotation=90)
        ax.set_yticks(range(n), names)
        ax.set_xticks(np.arange(n + 1) - 0.5, minor=True)
        ax.set_yticks(np.arange(n + 1) - 0.5, minor=True)
        ax.grid(which="minor", color=COLORS["muted"], lw=0.5)
        ax.tick_params(which="minor", length=0)
        ax.set_title(sub)
    axes_[1].scatter(j, low[j], marker="x", color="white", s=30, zorder=3)  # not by colour alone
    if title:
        fig.suptitle(title)
    describe(
        fig,
        f"Two {n} × {n} matrices, rows and columns labelled by the simplices in filtration order: left, the "
        f"boundary matrix D; right, its reduction R, whose {len(j)} lowest ones are red and crossed, each pairing "
        "the simplex of its row with the simplex of its column",
    )
    return fig


def voxel_slice(
    labels: np.ndarray,
    grid: tuple[np.ndarray, np.ndarray, np.ndarray],
    *,
    title: str | None = None,
    ax: Axes | None = None,
) -> Figure:
    """A slice of a voxelized complement (:func:`shapelab.oracles.voxel_complement`):
    the union grey, the unbounded component white, each bounded component (a void) in
    a colour of the palette, in the :math:`z`-slice that cuts most void voxels
    (Notes §23.1, voids as bounded components of the complement).

    Parameters
    ----------
    labels : ndarray of int, shape (nx, ny, nz)
        0 for voxels in the union, 1 for the unbounded component, 2, 3, ... for the
        bounded ones (the first result of ``voxel_complement``).
    grid : tuple of three 1D arrays
        The voxel centres along x, y and z (its second result).
    title : str, optional
        The panel's title (default: the number of bounded components).
    ax : matplotlib Axes, optional
        Draw into this 2D axes.

    Returns
    -------
    matplotlib.figure.Figure
        Its axes described for the text alternative.

    Raises
    ------
    ValueError
        If ``labels`` is not a 3D array matching ``grid``.

    See Also
    --------
    shapelab.oracles.voxel_complement : the labels drawn.
    voids : the voids computed from the α-complex.

    Examples
    --------
    >>> import shapelab as sl
    >>> labels, grid = sl.oracles.voxel_complement(sl.datasets.fullerene_c60(), tau=0.0, spacing=0.4)
    >>> fig = sl.plot.voxel_slice(labels, grid)
    >>> "1 bounded component" in sl.plot.alt_text(fig)
    True
    """
    from matplotlib.colors import ListedColormap

    labels = np.asarray(labels)
    xs, ys, zs = (np.asarray(g, dtype=np.float64) for g in grid)
    if labels.ndim != 3 or labels.shape != (xs.size, ys.size, zs.size):
        raise ValueError("voxel_slice: labels must be a 3D array of the shape of the grid (x, y, z)")
    fig, ax = axes(ax)
    k = int(np.argmax((labels >= 2).sum(axis=(0, 1))))
    n = max(int(labels.max()) - 1, 0)
    word = f"{n} bounded component{'s' if n != 1 else ''}"
    colors = ["#D9D9D9", "white", *[PALETTE[(2 + i) % len(PALETTE)] for i in range(n)]]
    ax.imshow(
        labels[:, :, k].T,
        origin="lower",
        extent=(xs[0], xs[-1], ys[0], ys[-1]),
        cmap=ListedColormap(colors),
        vmin=-0.5,
        vmax=n + 1.5,
        interpolation="nearest",
    )
    ax.set_title(title if title is not None else word)
    ax.set_xlabel("x (Å)")
    ax.set_ylabel("y (Å)")
    describe(
        ax,
        f"A slice at z = {zs[k]:.1f} Å through the voxels: the union grey, the outside white, "
        f"{word} of the complement in colour",
    )
    return fig
