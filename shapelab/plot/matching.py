"""Figures of shape matching (notes §23.2): critical points and the Hausdorff distance.

* :func:`critical_points` — Figure 23.3: a closed curve, the viewpoint S, the rays
  from S to the extrema of F(x) = |x − S|, and F plotted along the curve.
* :func:`critical_surface` — the 3D remark: a closed surface shaded by F with its
  minima, saddles and maxima.
* :func:`hausdorff` — two point sets with the witness segments of both directed
  distances and the empty disks that certify them.
* :func:`translation` — matching under translation: centroid against optimum.
* :func:`timings` — a bar chart of measured running times.

Every function returns a :class:`matplotlib.figure.Figure` (or draws into ``ax=``
and returns its figure) and computes no geometry beyond calling the library.
"""

from __future__ import annotations

import numpy as np
from matplotlib.patches import Circle
from matplotlib.ticker import MaxNLocator

from ._common import axes
from ._describe import describe
from ._style import COLORS, PAGE, PALETTE, SLIDE, new_figure, style

__all__ = [
    "critical_points",
    "critical_surface",
    "hausdorff",
    "translation",
    "timings",
    "docking_landscape",
    "docking_pose",
    "point_clouds",
    "distance_matrix",
    "embedding",
    "stability",
]

_KIND_STYLE = {
    "min": dict(color=PALETTE[0], marker="v", label="minimum"),
    "max": dict(color=PALETTE[3], marker="^", label="maximum"),
    "saddle": dict(color=PALETTE[1], marker="X", label="saddle"),
}


def _check_result(result, sources):
    from ..critical import CriticalPoints

    if not isinstance(result, CriticalPoints):
        raise TypeError(f"result must be a CriticalPoints from shapelab.critical_points, got {type(result).__name__}")
    if result.source not in sources:
        raise ValueError(f"result comes from a {result.source}; this figure needs one of {sources}")


def critical_points(
    curve,
    result,
    *,
    ax=None,
    profile_ax=None,
    profile: bool = True,
    rays: bool = True,
    title: str | None = None,
    size=SLIDE,
    n: int = 600,
):
    """Figure 23.3: a closed curve seen from S, with its critical points.

    Parameters
    ----------
    curve : array_like or callable
        The closed polyline or parametric curve given to
        :func:`shapelab.critical_points`.
    result : CriticalPoints
        Its critical points (the viewpoint is ``result.viewpoint``).
    ax : Axes, optional
        Draw the curve panel here (then the profile goes to ``profile_ax`` if
        given, and is omitted otherwise).
    profile_ax : Axes, optional
        Where to draw F along the curve when ``ax`` is given.
    profile : bool
        Add the second panel, F along the curve, when creating the figure.
    rays : bool
        Draw the segments from S to each extremum.
    title : str, optional
    size : (float, float)
        Figure size when creating the figure.
    n : int
        Samples used to draw a parametric curve and the profile.

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.critical_points
        The points drawn.
    critical_surface
        On a surface.
    """
    from ..critical import distance_along, polyline

    _check_result(result, ("polyline", "parametric"))
    if ax is None:
        if profile:
            fig, (ax, profile_ax) = new_figure(1, 2, size=size)
        else:
            fig, ax = new_figure(size=size)
    else:
        fig = ax.get_figure()
    if callable(curve):
        P = polyline(curve, n)
        param_label = "parameter t"
    else:
        P = np.asarray(curve, dtype=float)
        if not np.array_equal(P[0], P[-1]):
            P = np.vstack([P, P[:1]])
        param_label = "arc length (fraction of the perimeter)"
    S = result.viewpoint
    with style():
        ax.plot(P[:, 0], P[:, 1], color=COLORS["complex"], lw=1.6, zorder=2, label="curve C")
        if not callable(curve):
            ax.plot(P[:-1, 0], P[:-1, 1], ".", color=COLORS["complex"], ms=3, zorder=2)
        for kind in ("min", "max"):
            sel = result.kinds == kind
            X = result.positions[sel]
            st = _KIND_STYLE[kind]
            if rays:
                for x in X:
                    ax.plot([S[0], x[0]], [S[1], x[1]], color=st["color"], lw=0.9, ls="--", alpha=0.8, zorder=1)
            ax.scatter(
                X[:, 0],
                X[:, 1],
                s=70,
                color=st["color"],
                marker=st["marker"],
                zorder=4,
                edgecolor="white",
                linewidth=0.6,
                label=f"{st['label']} ({int(sel.sum())})",
            )
        ax.scatter(
            [S[0]],
            [S[1]],
            s=90,
            color=COLORS["accent"],
            marker="*",
            zorder=5,
            edgecolor="black",
            linewidth=0.5,
            label="viewpoint S",
        )
        ax.annotate("S", S[:2], xytext=(6, 6), textcoords="offset points", fontsize=11)
        ax.set_aspect("equal")
        ax.set_xlabel("x")
        ax.set_ylabel("y")
        deg = " — F constant: every point is critical" if result.degenerate else ""
        ax.set_title(title or f"Critical points of F(x) = |x − S|{deg}")
        ax.legend(
            loc="upper left",
            bbox_to_anchor=(1.0, 1.0) if profile_ax is None else (0.0, -0.2),
            ncol=1 if profile_ax is None else 2,
            fontsize=9,
        )
        if profile_ax is not None:
            s, F = distance_along(curve, S, n=n)
            pax = profile_ax
            pax.plot(s, F, color=COLORS["complex"], lw=1.4)
            for kind in ("min", "max"):
                sel = result.kinds == kind
                st = _KIND_STYLE[kind]
                pax.scatter(
                    result.parameters[sel],
                    result.values[sel],
                    s=55,
                    color=st["color"],
                    marker=st["marker"],
                    zorder=4,
                    edgecolor="white",
                    linewidth=0.6,
                )
                for p in result.parameters[sel]:
                    pax.axvline(p, color=st["color"], lw=0.6, ls=":", zorder=0)
            pax.set_xlabel(param_label)
            pax.set_ylabel("F = |x − S|")
            pax.set_title("F along the curve")
            describe(
                pax,
                f"F = |x − S| along the curve against the {param_label}, from {float(np.min(F)):.3g} to "
                f"{float(np.max(F)):.3g}, its minima and maxima marked with down and up triangles",
            )
        n_min, n_max = int((result.kinds == "min").sum()), int((result.kinds == "max").sum())
        describe(
            ax,
            f"A closed planar curve and the viewpoint S = ({S[0]:.3g}, {S[1]:.3g}), a star: the critical points of "
            f"the distance from S, {n_min} minima (down triangles) and {n_max} maxima (up triangles)"
            + (", joined to S by dashed rays" if rays else "")
            + ("; F is constant, every point is critical" if result.degenerate else ""),
        )
    return fig


def critical_surface(
    vertices,
    faces,
    result,
    *,
    ax=None,
    size=PAGE,
    elev: float = 20.0,
    azim: float = -60.0,
    title: str | None = None,
    colorbar: bool = True,
):
    """A closed surface shaded by F = |x − S| with its minima, saddles and maxima.

    Parameters
    ----------
    vertices, faces : array_like
        The mesh given to :func:`shapelab.critical_points`.
    result : CriticalPoints
        From a surface (``faces=`` given).
    ax : Axes3D, optional
    elev, azim : float
        The camera.
    title : str, optional
    colorbar : bool

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    critical_points
        On a curve.
    """
    from matplotlib import colormaps
    from matplotlib.cm import ScalarMappable
    from matplotlib.colors import Normalize
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    _check_result(result, ("surface",))
    V = np.asarray(vertices, dtype=float)
    F = np.asarray(faces, dtype=np.intp)
    fig, ax = axes(ax, size=size, projection="3d")
    S = result.viewpoint
    h = np.sqrt(np.sum((V - S) ** 2, axis=1))
    with style():
        norm = Normalize(h.min(), h.max())
        cmap = colormaps["viridis"]
        coll = Poly3DCollection(
            V[F], facecolors=cmap(norm(h[F].mean(axis=1))), edgecolor=(0, 0, 0, 0.12), linewidth=0.2, alpha=0.55
        )
        ax.add_collection3d(coll)
        for kind in ("min", "saddle", "max"):
            sel = result.kinds == kind
            st = _KIND_STYLE[kind]
            X = result.positions[sel]
            count = int(result.multiplicities[sel].sum())
            ax.scatter(
                X[:, 0],
                X[:, 1],
                X[:, 2],
                s=60,
                color=st["color"],
                marker=st["marker"],
                edgecolor="black",
                linewidth=0.4,
                depthshade=False,
                label=f"{st['label']} ({count})",
            )
        ax.scatter(
            [S[0]],
            [S[1]],
            [S[2]],
            s=90,
            color=COLORS["accent"],
            marker="*",
            edgecolor="black",
            linewidth=0.5,
            depthshade=False,
            label="viewpoint S",
        )
        lo, hi = V.min(axis=0), V.max(axis=0)
        c, r = 0.5 * (lo + hi), 0.5 * float((hi - lo).max())
        ax.set_xlim(c[0] - r, c[0] + r)
        ax.set_ylim(c[1] - r, c[1] + r)
        ax.set_zlim(c[2] - r, c[2] + r)
        ax.set_box_aspect((1, 1, 1))
        for axis in (ax.xaxis, ax.yaxis, ax.zaxis):
            axis.set_major_locator(MaxNLocator(4))
            axis.set_tick_params(labelsize=8)
        ax.view_init(elev=elev, azim=azim)
        ax.set_xlabel("x")
        ax.set_ylabel("y")
        ax.set_zlabel("z")
        chi = result.euler_characteristic
        ax.set_title(title or f"#min − #saddle + #max = {result.n_min} − {result.n_saddle} + {result.n_max} = {chi}")
        ax.legend(loc="upper left", fontsize=9)
        if colorbar:
            sm = ScalarMappable(norm=norm, cmap=cmap)
            fig.colorbar(sm, ax=ax, shrink=0.6, label="F = |x − S|")
        describe(
            ax,
            f"3D view of a surface shaded by the distance F from a viewpoint S (a star), with its critical points: "
            f"{result.n_min} minima, {result.n_saddle} saddles and {result.n_max} maxima, each kind with its own "
            f"marker; #min − #saddle + #max = {chi}, the Euler characteristic",
        )
    return fig


def hausdorff(A, B, *, ax=None, size=PAGE, labels=("A", "B"), disks: bool = True, title: str | None = None):
    """Two planar point sets with the witnesses of both directed Hausdorff distances.

    The segment from ``A[i]`` to its nearest point ``B[j]`` realises h(A, B);
    the disk of that radius around ``A[i]`` holds no point of B in its interior,
    which certifies the value.  Likewise for h(B, A).  The longer segment is
    H(A, B) (notes §23.2).

    Parameters
    ----------
    A, B : array_like, shape (n, 2) and (m, 2)
    ax : Axes, optional
    labels : (str, str)
        Names of the sets (e.g. ``("R", "G")`` as in the notes).
    disks : bool
        Draw the certifying empty disks.
    title : str, optional

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.directed_hausdorff
        The witnesses drawn.
    """
    from .._toolkit.validate import as_points
    from ..distance import hausdorff_pair

    A = as_points(A, "A", dim=2)
    B = as_points(B, "B", dim=2)
    ab, ba = hausdorff_pair(A, B)
    fig, ax = axes(ax, size=size)
    la, lb = labels
    ca, cb = COLORS["red"], COLORS["green"]
    with style():
        ax.scatter(A[:, 0], A[:, 1], s=22, color=ca, label=la, zorder=3)
        ax.scatter(B[:, 0], B[:, 1], s=22, color=cb, marker="s", label=lb, zorder=3)
        # the two witnesses differ by line style as well as by colour
        for (h, i, j), P, Q, col, name, ls in (
            (ab, A, B, ca, f"h({la}, {lb})", "-"),
            (ba, B, A, cb, f"h({lb}, {la})", (0, (4, 2))),
        ):
            p, q = P[i], Q[j]
            ax.annotate("", xy=q, xytext=p, arrowprops=dict(arrowstyle="-|>", color=col, lw=2.0, ls=ls), zorder=4)
            ax.plot([], [], color=col, lw=2.0, ls=ls, label=f"{name} = {h:.3f}")
            if disks and h > 0:
                ax.add_patch(Circle(p, h, facecolor=col, alpha=0.08, edgecolor=col, lw=0.8, ls="--", zorder=1))
            ax.scatter([p[0]], [p[1]], s=80, facecolor="none", edgecolor=col, linewidth=1.5, zorder=5)
        H = max(ab.distance, ba.distance)
        ax.set_aspect("equal")
        ax.autoscale_view()
        ax.set_xlabel("x")
        ax.set_ylabel("y")
        ax.set_title(title or f"H({la}, {lb}) = max{{h({la},{lb}), h({lb},{la})}} = {H:.3f}")
        ax.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0), fontsize=9)
        describe(
            ax,
            (f"{title}: " if title else "")
            + f"Two planar point sets, {la} ({len(A)} dots) and {lb} ({len(B)} squares), with the witnesses of the "
            f"directed Hausdorff distances: h({la}, {lb}) = {ab.distance:.3f} (solid arrow) and "
            f"h({lb}, {la}) = {ba.distance:.3f} (dashed arrow)"
            + (", each with its empty disk" if disks else "")
            + f"; H({la}, {lb}) = {H:.3f}",
        )
    return fig


def translation(A, B, match, *, size=SLIDE, labels=("A", "B"), title: str | None = None):
    """Matching under translation: B moved by the centroid translation and by the
    optimal one, each panel with its Hausdorff witnesses.

    Parameters
    ----------
    A, B : array_like, shape (n, 2) and (m, 2)
    match : TranslationMatch
        From :func:`shapelab.hausdorff_under_translation` on the same sets.

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.hausdorff_under_translation
        The match drawn.
    """
    from .._toolkit.validate import as_points
    from ..matching import TranslationMatch

    if not isinstance(match, TranslationMatch):
        raise TypeError(f"match must be a TranslationMatch, got {type(match).__name__}")
    A = as_points(A, "A", dim=2)
    B = as_points(B, "B", dim=2)
    fig, axes = new_figure(1, 2, size=size)
    la, lb = labels
    hausdorff(
        A,
        B + match.centroid_translation,
        ax=axes[0],
        labels=(la, f"{lb}+t"),
        title=f"centroids aligned: H = {match.centroid_distance:.3f}",
    )
    hausdorff(
        A,
        B + match.optimal_translation,
        ax=axes[1],
        labels=(la, f"{lb}+t"),
        title=f"optimal translation: H = {match.optimal_distance:.3f}",
    )
    with style():
        lims = np.array([a.get_xlim() + a.get_ylim() for a in axes])
        for a in axes:
            a.set_xlim(lims[:, 0].min(), lims[:, 1].max())
            a.set_ylim(lims[:, 2].min(), lims[:, 3].max())
            a.legend(loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=2, fontsize=8)
        fig.suptitle(title or f"centroid / optimum = {match.ratio:.3f}")
    return fig


_ALGORITHM_COLORS = {
    "brute force": PALETTE[7],
    "k-d tree (scipy)": PALETTE[0],
    "early break (scipy)": PALETTE[1],
    "shapelab": PALETTE[3],
}


def timings(seconds: dict, *, ax=None, size=PAGE, title: str | None = None, log: bool = True):
    """A horizontal bar chart of measured running times.

    Parameters
    ----------
    seconds : dict
        ``{label: seconds}`` (e.g. ``Timings.seconds`` from
        :func:`shapelab.distance.timings`).  The algorithms of that function keep
        the same colour in every chart.
    log : bool
        Logarithmic time axis (bars start at a third of the fastest time).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.distance.timings
        Measures the times.
    """
    from matplotlib.ticker import LogLocator, NullFormatter

    if not isinstance(seconds, dict) or not seconds:
        raise TypeError("seconds must be a non-empty dict {label: seconds}")
    names = list(seconds)
    vals = np.array([float(seconds[k]) for k in names])
    if not np.all(np.isfinite(vals)) or np.any(vals <= 0):
        raise ValueError("seconds must hold positive finite times")
    fig, ax = axes(ax, size=size)
    spare = iter(c for c in PALETTE if c not in _ALGORITHM_COLORS.values())
    colors = [_ALGORITHM_COLORS.get(k) or next(spare, COLORS["muted"]) for k in names]
    with style():
        y = np.arange(len(names))
        left = vals.min() / 3 if log else 0.0
        ax.barh(y, vals - left, left=left, color=colors)
        ax.set_yticks(y, names)
        ax.invert_yaxis()
        if log:
            ax.set_xscale("log")
            ax.xaxis.set_major_locator(LogLocator(base=10))
            ax.xaxis.set_minor_formatter(NullFormatter())
            ax.set_xlim(left, vals.max() * 12)
        else:
            ax.set_xlim(0, vals.max() * 1.3)
        for k, v in enumerate(vals):
            text = f"{v * 1e3:.1f} ms" if v < 1 else f"{v:.2f} s"
            ax.text(v, k, "  " + text, va="center", fontsize=9)
        ax.set_xlabel("time (s)")
        ax.set_title(title or "Running time")
        describe(
            ax,
            f"{title or 'Running time'}: a bar chart of {len(names)} running times, each bar labelled: "
            + ", ".join(f"{k} {v * 1e3:.1f} ms" if v < 1 else f"{k} {v:.2f} s" for k, v in zip(names, vals)),
        )
    return fig


def docking_landscape(angles, shifts, scores, *, marks=None, ax=None, size=PAGE, title: str | None = None):
    """The docking score on a grid of poses (:meth:`shapelab.Docking.landscape`), as a heat map.

    Parameters
    ----------
    angles : array_like, shape (a,)
        Turns in radians (drawn in degrees, horizontally).
    shifts : array_like, shape (s,)
        Shifts in Å (vertically).
    scores : array_like, shape (a, s)
        ``scores[i, j]`` at ``angles[i]``, ``shifts[j]``.
    marks : dict of str → (angle, shift), optional
        Poses to mark (angle in radians), e.g. the crystal pose and the one found.

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.Docking
        The scores.
    """
    A = np.degrees(np.asarray(angles, float).ravel())
    S = np.asarray(shifts, float).ravel()
    Z = np.asarray(scores, float)
    if Z.shape != (len(A), len(S)):
        raise ValueError(f"scores must have shape (len(angles), len(shifts)) = {(len(A), len(S))}, got {Z.shape}")
    if not (np.all(np.isfinite(Z)) and np.all(np.isfinite(A)) and np.all(np.isfinite(S))):
        raise ValueError("angles, shifts and scores must be finite")
    fig, ax = axes(ax, size=size)
    with style():
        lo = np.percentile(Z, 5)  # clashes make some scores hugely negative: clip the colour scale
        mesh = ax.pcolormesh(A, S, Z.T, shading="nearest", cmap="viridis", vmin=lo, vmax=Z.max())
        fig.colorbar(mesh, ax=ax, label="score: buried area − penalty × clash (Å²)")
        styles = iter([("*", "white", 18), ("o", COLORS["red"], 10), ("s", COLORS["green"], 9), ("D", "black", 8)])
        for label, (a, s) in (marks or {}).items():
            m, c, z = next(styles, ("x", "black", 9))
            ax.plot(np.degrees(a), s, marker=m, color=c, markersize=z, markeredgecolor="black", ls="", label=label)
        if marks:
            ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.14), ncols=len(marks), frameon=False)
        ax.set_xlabel("turn about the ligand's axis (°)")
        ax.set_ylabel("shift (Å)")
        ax.set_title(title or "Docking score landscape")
        i, j = np.unravel_index(int(np.argmax(Z)), Z.shape)
        describe(
            ax,
            f"{title or 'Docking score landscape'}: a heat map of the docking score over turns from {A.min():.0f}° "
            f"to {A.max():.0f}° and shifts from {S.min():.3g} to {S.max():.3g} Å; the best score, {Z.max():.3g} Å², "
            f"at a turn of {A[i]:.0f}° and a shift of {S[j]:.3g} Å"
            + (f"; marked: {', '.join(marks)}" if marks else ""),
        )
    return fig


def docking_pose(
    receptor, crystal, docked, *, radius: float = 8.0, ax=None, size=PAGE, title=None, elev=20.0, azim=35.0
):
    """A docked ligand against the crystal pose, among the receptor atoms near it.

    Parameters
    ----------
    receptor : array_like, shape (n, 3)
        Receptor atom centres; those within ``radius`` of a crystal ligand atom are drawn.
    crystal, docked : array_like, shape (m, 3)
        The ligand's atom centres in the crystal and as docked.

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.Docking
        The poses.
    """
    from scipy.spatial import cKDTree

    from .._toolkit.validate import as_points

    receptor = as_points(receptor, "receptor", dim=3)
    crystal = as_points(crystal, "crystal", dim=3)
    docked = as_points(docked, "docked", dim=3)
    near = cKDTree(crystal).query(receptor, distance_upper_bound=radius)[0] < np.inf
    fig, ax = axes(ax, size=size, projection="3d")
    with style():
        R = receptor[near]
        ax.scatter(*R.T, s=14, color=COLORS["muted"], alpha=0.25, linewidths=0, depthshade=False, label="receptor")
        ax.scatter(*crystal.T, s=70, color=COLORS["green"], alpha=0.9, linewidths=0, label="crystal pose")
        ax.scatter(*docked.T, s=30, color=COLORS["red"], alpha=0.95, marker="D", linewidths=0, label="docked")
        c = crystal.mean(axis=0)
        h = radius * 0.9
        ax.set_xlim(c[0] - h, c[0] + h)
        ax.set_ylim(c[1] - h, c[1] + h)
        ax.set_zlim(c[2] - h, c[2] + h)
        ax.set_box_aspect((1, 1, 1))
        ax.view_init(elev=elev, azim=azim)
        ax.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0), frameon=False, markerscale=1.2)
        if title:
            ax.set_title(title)
        rmsd = float(np.sqrt(((docked - crystal) ** 2).sum(axis=1).mean())) if docked.shape == crystal.shape else None
        describe(
            ax,
            (f"{title}: " if title else "")
            + f"3D view of a docked ligand ({len(docked)} atoms, small diamonds) over its crystal pose (large dots), "
            f"among the {int(near.sum())} receptor atoms within {radius:g} Å"
            + (f"; RMSD {rmsd:.2f} Å" if rmsd is not None else ""),
        )
    return fig


# ====================================================== shape classification
def _class_colors(labels):
    names = list(dict.fromkeys(labels))
    return names, {c: PALETTE[k % len(PALETTE)] for k, c in enumerate(names)}


def point_clouds(clouds: dict, *, size=SLIDE, elev: float = 20.0, azim: float = 35.0):
    """Small multiples of 3D point sets, one panel each (a family of shapes).

    Parameters
    ----------
    clouds : dict of str → array_like, shape (n, 3)
        Panel title → points.

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.datasets.shape_family
        A family of shapes to draw.
    """
    from .._toolkit.validate import as_points

    if not isinstance(clouds, dict) or not clouds:
        raise TypeError("clouds must be a non-empty dict of title -> (n, 3) points")
    pts = {str(k): as_points(v, f"clouds[{k!r}]", dim=3) for k, v in clouds.items()}
    fig, axes = new_figure(1, len(pts), size=size, projection="3d")
    with style():
        for k, (ax, (title, X)) in enumerate(zip(np.atleast_1d(axes), pts.items(), strict=True)):
            ax.scatter(*X.T, s=6, color=PALETTE[k % len(PALETTE)], depthshade=True, linewidths=0)
            h = np.abs(X - X.mean(axis=0)).max()
            c = X.mean(axis=0)
            ax.set_xlim(c[0] - h, c[0] + h)
            ax.set_ylim(c[1] - h, c[1] + h)
            ax.set_zlim(c[2] - h, c[2] + h)
            ax.set_box_aspect((1, 1, 1))
            ax.view_init(elev=elev, azim=azim)
            ax.set_title(title)
            ax.set_xticklabels([])
            ax.set_yticklabels([])
            ax.set_zticklabels([])
            describe(ax, f"3D view of {title}, {len(X)} points")
    return fig


def distance_matrix(D, labels, *, ax=None, size=PAGE, title: str | None = None, unit: str = ""):
    """A distance matrix between the shapes of a family, as a heat map grouped by class.

    Parameters
    ----------
    D : array_like, shape (k, k)
    labels : sequence of str, length k
        The class of each shape; rows of one class should be contiguous.

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.diagrams.distance_matrix
        The distances drawn.
    embedding
        The same distances in the plane.
    """
    D = np.asarray(D, float)
    labels = [str(s) for s in labels]
    if D.ndim != 2 or D.shape != (len(labels), len(labels)):
        raise ValueError(f"D must be a square matrix with one row per label, got {D.shape} and {len(labels)} labels")
    fig, ax = axes(ax, size=size)
    names, _ = _class_colors(labels)
    with style():
        im = ax.imshow(D, cmap="magma_r", interpolation="nearest")
        fig.colorbar(im, ax=ax, label=f"distance{f' ({unit})' if unit else ''}")
        starts = [labels.index(c) for c in names]
        ends = [len(labels) - labels[::-1].index(c) for c in names]
        mids = [(a + b - 1) / 2 for a, b in zip(starts, ends, strict=True)]
        for b in ends[:-1]:
            ax.axhline(b - 0.5, color="white", lw=1.5)
            ax.axvline(b - 0.5, color="white", lw=1.5)
        ax.set_xticks(mids, names, rotation=30, ha="right")
        ax.set_yticks(mids, names)
        ax.set_title(title or "Distances between the shapes")
        within = [D[a:b, a:b][~np.eye(b - a, dtype=bool)] for a, b in zip(starts, ends, strict=True)]
        inner = np.concatenate([w for w in within if w.size]) if any(w.size for w in within) else np.zeros(0)
        mask = np.zeros(D.shape, bool)
        for a, b in zip(starts, ends, strict=True):
            mask[a:b, a:b] = True
        outer = D[~mask]
        u = f" {unit}" if unit else ""
        describe(
            ax,
            f"{title or 'Distances between the shapes'}: a heat map of the {len(labels)} × {len(labels)} distances "
            f"between the shapes, grouped into {len(names)} classes ({', '.join(names)})"
            + (f"; within a class at most {inner.max():.3g}{u}" if inner.size else "")
            + (f", between classes at least {outer.min():.3g}{u}" if outer.size else ""),
        )
    return fig


def embedding(points, labels, *, ax=None, size=PAGE, title: str | None = None):
    """Shapes as points in the plane (:func:`shapelab.classical_mds`), coloured by class.

    Parameters
    ----------
    points : array_like, shape (k, 2)
    labels : sequence of str, length k

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.classical_mds
        The embedding drawn.
    distance_matrix
        The distances embedded.
    """
    from .._toolkit.validate import as_points

    X = as_points(points, "points", dim=2)
    labels = [str(s) for s in labels]
    if len(labels) != len(X):
        raise ValueError(f"labels must have one entry per point, got {len(labels)} for {len(X)} points")
    fig, ax = axes(ax, size=size)
    names, colors = _class_colors(labels)
    markers = "osD^vP*X"
    with style():
        for k, c in enumerate(names):
            P = X[[i for i, s in enumerate(labels) if s == c]]
            ax.scatter(*P.T, s=70, color=colors[c], marker=markers[k % len(markers)], label=c, edgecolors="white")
        ax.set_aspect("equal", adjustable="datalim")
        ax.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0), frameon=False)
        ax.set_xlabel("first coordinate")
        ax.set_ylabel("second coordinate")
        ax.set_title(title or "The family in the plane (classical MDS)")
        describe(
            ax,
            f"{title or 'The family in the plane (classical MDS)'}: {len(X)} shapes as points in the plane, one "
            f"marker shape per class: " + ", ".join(f"{c} ({labels.count(c)})" for c in names),
        )
    return fig


def stability(perturbation, distances: dict, *, ax=None, size=PAGE, title: str | None = None, unit: str = ""):
    """The stability theorem at work: diagram distance against the perturbation's size.

    Parameters
    ----------
    perturbation : array_like, shape (k,)
        Sizes δ > 0 of the perturbations (drawn on log axes).
    distances : dict of str → array_like, shape (k,)
        Label → the bottleneck distance measured at each δ.  Zero distances are drawn
        at the bottom of the axes.

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.bottleneck_distance
        The distances drawn.

    References
    ----------
    .. [1] D. Cohen-Steiner, H. Edelsbrunner and J. Harer, "Stability of persistence
           diagrams", *Discrete Comput. Geom.* 37:103-120, 2007.
           doi:10.1007/s00454-006-1276-5
    """
    x = np.asarray(perturbation, float).ravel()
    if x.size == 0 or not np.all(np.isfinite(x)) or np.any(x <= 0):
        raise ValueError("perturbation must hold positive finite sizes")
    if not isinstance(distances, dict) or not distances:
        raise TypeError("distances must be a non-empty dict of label -> distances")
    fig, ax = axes(ax, size=size)
    with style():
        ax.plot(x, x, color="black", lw=1.5, ls="--", label="bound: distance = δ")
        floor = x.min() / 30
        for k, (label, y) in enumerate(distances.items()):
            y = np.asarray(y, float).ravel()
            if y.shape != x.shape:
                raise ValueError(f"distances[{label!r}] must have one value per perturbation")
            ax.plot(x, np.maximum(y, floor), marker="os^D"[k % 4], color=PALETTE[k % len(PALETTE)], label=label)
        ax.set_xscale("log")
        ax.set_yscale("log")
        u = f" ({unit})" if unit else ""
        ax.set_xlabel(f"perturbation δ{u}")
        ax.set_ylabel(f"bottleneck distance{u}")
        ax.legend(loc="upper left", frameon=False)
        ax.set_title(title or "Stability: the diagrams move no more than the points")
        below = all(np.all(np.asarray(y, float).ravel() <= x * (1 + 1e-9)) for y in distances.values())
        describe(
            ax,
            f"{title or 'Stability: the diagrams move no more than the points'}: on log axes, the bottleneck distance "
            f"against the perturbation δ from {x.min():.3g} to {x.max():.3g}, one line and marker shape for each of "
            f"{', '.join(map(str, distances))}, under the dashed bound distance = δ; "
            + ("every distance is at most δ" if below else "some distance exceeds δ"),
        )
    return fig
