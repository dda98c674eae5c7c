"""Figures for §23.2 of the notes: red and green point sets, ICP steps and
convergence, and a rotation about an axis (Figure 23.4) in 3D.

Every function returns a :class:`matplotlib.figure.Figure` (or draws into ``ax`` and
returns its figure).  Geometry comes from :mod:`shapelab.registration` and
:mod:`shapelab.quaternion`; nothing is recomputed here.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from .._toolkit.validate import as_finite_scalar, as_point, as_points, as_positive_int
from ..quaternion import Quaternion, qfrom_axis_angle, qrotate
from ..registration import ICPResult, RigidMotion
from ._common import axes
from ._describe import describe
from ._style import COLORS, PALETTE, new_figure, style

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure
    from numpy.typing import ArrayLike

_SHADES = tuple(PALETTE[k] for k in (1, 4, 5))

__all__ = ["point_sets", "icp_step", "icp_convergence", "rotation_axis", "two_stage", "displacement"]


def _cube_limits(ax, pts: np.ndarray, pad: float = 0.08) -> None:
    """Equal aspect in 3D: a cube around the points."""
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    c = 0.5 * (lo + hi)
    r = 0.5 * float((hi - lo).max()) * (1 + pad) or 1.0
    ax.set_xlim(c[0] - r, c[0] + r)
    ax.set_ylim(c[1] - r, c[1] + r)
    ax.set_zlim(c[2] - r, c[2] + r)
    ax.set_box_aspect((1, 1, 1))
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    ax.set_zlabel("z")


def _stride(n: int, most: int) -> np.ndarray:
    """At most ``most`` evenly spaced indices of range(n) (deterministic)."""
    if n <= most:
        return np.arange(n)
    return np.unique(np.linspace(0, n - 1, most).round().astype(int))


def _marker_size(n: int) -> float:
    return float(np.clip(1200.0 / max(n, 1) ** 0.75, 1.0, 36.0))


def point_sets(
    R: ArrayLike,
    G: ArrayLike,
    *,
    pairs: bool = False,
    labels: tuple[str, str] = ("R", "G"),
    ax: Axes | None = None,
    title: str | None = None,
    max_pairs: int = 400,
    elev: float = 20.0,
    azim: float = 35.0,
) -> Figure:
    """The red set R and the green set G of the notes (§23.2), in 2D or 3D.

    Parameters
    ----------
    R, G : array_like, shape (n, d) and (m, d), d in {2, 3}
    pairs : bool
        Draw the segments :math:`r_j g_j` of paired sets (needs n = m); at most
        ``max_pairs`` of them, evenly spaced.
    labels : (str, str)
        Legend entries.
    ax : Axes, optional
        Draw into this axes (3D axes for 3D points).
    title : str, optional
    elev, azim : float
        3D view angles.

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    icp_step
        One ICP iteration.

    Examples
    --------
    >>> import numpy as np
    >>> import shapelab as sl
    >>> R = np.random.default_rng(0).normal(size=(20, 3))
    >>> G = sl.Quaternion.from_axis_angle([0, 0, 1], np.pi / 4).rotate(R)
    >>> fig = point_sets(R, G, pairs=True)
    >>> type(fig).__name__
    'Figure'
    >>> print(sl.plot.alt_text(fig))
    3D view of two point sets, R (20 dots) and G (20 squares), each r_j joined to its g_j by a grey segment (RMS distance 1.04).
    """
    R = as_points(R, "R", dim=(2, 3))
    G = as_points(G, "G", dim=(2, 3))
    if R.shape[1] != G.shape[1]:
        raise ValueError(f"R and G must have the same dimension, got {R.shape[1]} and {G.shape[1]}")
    if pairs and R.shape != G.shape:
        raise ValueError(f"pairs=True needs R and G of the same shape, got {R.shape} and {G.shape}")
    max_pairs = as_positive_int(max_pairs, "max_pairs")
    three = R.shape[1] == 3
    fig, ax = axes(ax, projection="3d" if three else None, planar=True)
    with style():
        if pairs:
            idx = _stride(len(R), max_pairs)
            seg = np.stack([R[idx], G[idx]], axis=1)
            if three:
                from mpl_toolkits.mplot3d.art3d import Line3DCollection

                ax.add_collection3d(Line3DCollection(seg, colors=COLORS["muted"], linewidths=0.6, alpha=0.7))
            else:
                from matplotlib.collections import LineCollection

                ax.add_collection(LineCollection(seg, colors=COLORS["muted"], linewidths=0.8, alpha=0.7))
        for P, color, label, marker in ((R, COLORS["red"], labels[0], "o"), (G, COLORS["green"], labels[1], "s")):
            s = _marker_size(len(P))
            if three:
                ax.scatter(
                    P[:, 0],
                    P[:, 1],
                    P[:, 2],
                    s=s,
                    color=color,
                    label=label,
                    marker=marker,
                    depthshade=False,
                    alpha=0.85,
                    linewidths=0,
                )
            else:
                ax.scatter(
                    P[:, 0],
                    P[:, 1],
                    s=s * 1.5,
                    color=color,
                    label=label,
                    marker=marker,
                    alpha=0.9,
                    linewidths=0,
                    zorder=3,
                )
        if three:
            _cube_limits(ax, np.vstack([R, G]))
            ax.view_init(elev=elev, azim=azim)
        else:
            ax.set_aspect("equal", adjustable="datalim")
            ax.set_xlabel("x")
            ax.set_ylabel("y")
        ax.legend(loc="upper left", markerscale=2.0)
        if title:
            ax.set_title(title)
        rms = float(np.sqrt(((R - G) ** 2).sum(axis=1).mean())) if R.shape == G.shape else None
        describe(
            ax,
            (f"{title}: " if title else "")
            + f"{'3D view of ' if three else ''}two point sets, {labels[0]} ({len(R)} dots) and {labels[1]} "
            f"({len(G)} squares)"
            + (f", each r_j joined to its g_j by a grey segment (RMS distance {rms:.3g})" if pairs else "")
            + (f"; RMS distance between paired points {rms:.3g}" if rms is not None and not pairs else ""),
        )
    return fig


def _correspondence_at(result: ICPResult, k: int) -> np.ndarray:
    if result.correspondences is not None:
        return result.correspondences[k]
    if k == result.n_iter:
        return result.correspondence
    raise ValueError(
        f"the correspondence of iteration {k} was not kept; run icp(..., keep_history=True) to draw intermediate steps"
    )


def icp_step(
    source: ArrayLike,
    target: ArrayLike,
    result: ICPResult,
    k: int = 0,
    *,
    ax: Axes | None = None,
    max_lines: int = 300,
    show_next: bool = True,
    title: str | None = None,
    elev: float = 20.0,
    azim: float = 35.0,
) -> Figure:
    """One ICP iteration (Notes §23.2, steps 1–3) in 3D.

    Draws the target (green), the source at motion ``result.motions[k]`` (red), the
    closest-point correspondence :math:`\\pi` of step 1 as grey segments, and (with
    ``show_next``) where steps 2–3 move the source, as hollow red markers.

    Parameters
    ----------
    source, target : array_like, shape (n, 3), (m, 3)
        The inputs given to :func:`shapelab.icp`.
    result : ICPResult
        Its output; intermediate ``k`` need ``keep_history=True``.
    k : int
        Iteration, 0 ≤ k ≤ ``result.n_iter``.
    max_lines : int
        At most this many correspondence segments (evenly spaced source points).

    See Also
    --------
    shapelab.icp
        The iterations drawn.
    icp_convergence
        The error per iteration.

    Examples
    --------
    >>> import numpy as np
    >>> import shapelab as sl
    >>> target = np.random.default_rng(0).normal(size=(30, 3))
    >>> source = sl.Quaternion.from_axis_angle([0, 0, 1], 0.3).rotate(target) + 0.1
    >>> result = sl.icp(source, target, keep_history=True)
    >>> fig = icp_step(source, target, result, k=0)
    >>> type(fig).__name__
    'Figure'
    >>> print(sl.plot.alt_text(fig))
    3D view of ICP iteration 0 of 3: the source (30 dots) at iteration 0 over the fixed target (30 squares), 30 closest-point pairs drawn as lines; mean squared error 0.192; open circles show the source after the next step.
    """
    if not isinstance(result, ICPResult):
        raise TypeError(f"result must be an ICPResult, got {type(result).__name__}")
    src = as_points(source, "source", dim=3)
    tgt = as_points(target, "target", dim=3)
    k = as_positive_int(k, "k", minimum=0)
    if k > result.n_iter:
        raise ValueError(f"k must be at most result.n_iter = {result.n_iter}, got {k}")
    corr = _correspondence_at(result, k)
    if corr.shape[0] != src.shape[0]:
        raise ValueError(f"source has {src.shape[0]} points but the result pairs {corr.shape[0]}")
    max_lines = as_positive_int(max_lines, "max_lines")
    moved = result.motions[k].apply(src)
    fig, ax = axes(ax, projection="3d", planar=True)
    from mpl_toolkits.mplot3d.art3d import Line3DCollection

    with style():
        s = _marker_size(max(len(src), len(tgt)))
        ax.scatter(
            *tgt.T,
            s=s,
            color=COLORS["green"],
            marker="s",
            depthshade=False,
            alpha=0.55,
            linewidths=0,
            label="target (fixed)",
        )
        ax.scatter(
            *moved.T,
            s=s,
            color=COLORS["red"],
            depthshade=False,
            alpha=0.9,
            linewidths=0,
            label=f"source at iteration {k}",
        )
        idx = _stride(len(src), max_lines)
        idx = idx[corr[idx] >= 0]
        seg = np.stack([moved[idx], tgt[corr[idx]]], axis=1)
        ax.add_collection3d(Line3DCollection(seg, colors=COLORS["complex"], linewidths=0.6, alpha=0.55))
        ax.plot([], [], color=COLORS["complex"], lw=0.8, label="closest-point pairs π (step 1)")
        pts = [tgt, moved]
        if show_next and k < result.n_iter:
            nxt = result.motions[k + 1].apply(src)
            ax.scatter(
                *nxt[idx].T,
                s=2.2 * s,
                facecolors="none",
                edgecolors=COLORS["red"],
                linewidths=0.7,
                depthshade=False,
                alpha=0.8,
                label="after steps 2–3",
            )
            pts.append(nxt)
        _cube_limits(ax, np.vstack(pts))
        ax.view_init(elev=elev, azim=azim)
        ax.legend(loc="upper left", fontsize=9, markerscale=1.5)
        ax.set_title(title or f"ICP iteration {k} of {result.n_iter}: MSE = {result.mse[k]:.3g}")
        describe(
            ax,
            f"3D view of ICP iteration {k} of {result.n_iter}: the source ({len(src)} dots) at iteration {k} over the "
            f"fixed target ({len(tgt)} squares), {len(idx)} closest-point pairs drawn as lines; "
            f"mean squared error {result.mse[k]:.3g}"
            + ("; open circles show the source after the next step" if show_next and k < result.n_iter else ""),
        )
    return fig


def icp_convergence(
    result: ICPResult | dict[str, ICPResult],
    *,
    truth: RigidMotion | None = None,
    ax: Axes | None = None,
    mark: int | None = None,
    title: str | None = None,
) -> Figure:
    """Mean squared error against iteration, on a log scale (Notes §23.2, step 4).

    Parameters
    ----------
    result : ICPResult or dict of str → ICPResult
        One run, or several labelled runs to compare (e.g. plain and accelerated).
    truth : RigidMotion, optional
        The true motion, when known: the rotation error (degrees) of each iterate
        is drawn too, dashed, on a second log axis.
    mark : int, optional
        An iteration to highlight (e.g. the widget's current one).

    See Also
    --------
    shapelab.icp
        The errors drawn.

    Examples
    --------
    >>> import numpy as np
    >>> import shapelab as sl
    >>> rng = np.random.default_rng(0)
    >>> target = rng.normal(size=(30, 3))
    >>> source = sl.Quaternion.from_axis_angle([0, 0, 1], 0.3).rotate(target) + 0.1 + rng.normal(0, 0.05, (30, 3))
    >>> fig = icp_convergence(sl.icp(source, target))
    >>> type(fig).__name__
    'Figure'
    >>> print(sl.plot.alt_text(fig))
    ICP convergence: the mean squared error against the iteration on a log scale, one line and marker shape per run. ICP: 2 iterations, MSE from 0.186 to 0.00656, converged.
    """
    runs = result if isinstance(result, dict) else {"ICP": result}
    if not runs:
        raise ValueError("result must hold at least one ICPResult")
    for name, r in runs.items():
        if not isinstance(r, ICPResult):
            raise TypeError(f"result[{name!r}] must be an ICPResult, got {type(r).__name__}")
    if truth is not None and not isinstance(truth, RigidMotion):
        raise TypeError(f"truth must be a RigidMotion, got {type(truth).__name__}")
    fig, ax = axes(ax, planar=True)
    with style():
        colors = [COLORS["ball_edge"], COLORS["accent"], COLORS["mouth"], COLORS["green"]]
        handles = []
        ax2 = ax.twinx() if truth is not None else None
        markers = "os^D"  # each run its own marker, not only its own colour
        for j, ((name, r), color) in enumerate(zip(runs.items(), colors * 4)):
            it = np.arange(r.n_iter + 1)
            mse = np.where(r.mse > 0, r.mse, np.nan)
            (h,) = ax.plot(
                it,
                mse,
                markers[j % 4] + "-",
                color=color,
                ms=3.5,
                lw=1.6,
                label=f"{name}: MSE" + (" (converged)" if r.converged else ""),
            )
            handles.append(h)
            if ax2 is not None:
                err = np.degrees([m.rotation.angle_to(truth.rotation) for m in r.motions])
                err = np.where(err > 0, err, np.nan)
                (h2,) = ax2.plot(it, err, "--", color=color, lw=1.2, alpha=0.8, label=f"{name}: rotation error")
                handles.append(h2)
        ax.set_yscale("log")
        ax.set_xlabel("iteration k")
        ax.set_ylabel("mean squared error μ/n")
        if ax2 is not None:
            ax2.set_yscale("log")
            ax2.set_ylabel("rotation error (degrees)")
            ax2.spines["right"].set_visible(True)
        if mark is not None:
            mark = as_positive_int(mark, "mark", minimum=0)
            ax.axvline(mark, color=COLORS["muted"], lw=1.0, ls=":")
        ax.legend(handles=handles, loc="upper right", fontsize=9)
        ax.set_title(title or "ICP convergence")
        ax.grid(True, which="major", alpha=0.25)
        runs_text = "; ".join(
            f"{name}: {r.n_iter} iterations, MSE from {r.mse[0]:.3g} to {r.mse[-1]:.3g}"
            + (", converged" if r.converged else ", not converged")
            for name, r in runs.items()
        )
        describe(
            ax,
            f"{title or 'ICP convergence'}: the mean squared error against the iteration on a log scale, "
            f"one line and marker shape per run"
            + (", the rotation error in degrees dashed on a second axis" if truth is not None else "")
            + f". {runs_text}"
            + (f"; iteration {mark} marked" if mark is not None else ""),
        )
    return fig


def rotation_axis(
    rotation: Quaternion | ArrayLike,
    angle: float | None = None,
    *,
    points: ArrayLike | None = None,
    ax: Axes | None = None,
    title: str | None = None,
    elev: float = 22.0,
    azim: float = -55.0,
) -> Figure:
    """A rotation about an axis through the origin, Figure 23.4 of the notes in 3D.

    Draws the unit axis :math:`u` as an arrow, each point before (red) and after
    (green) the rotation, its circle about the axis (dotted), the arc swept through
    the angle :math:`\\theta` (with an arrowhead, right-hand rule), and the radii from
    the axis to both positions.

    Parameters
    ----------
    rotation : Quaternion or array_like (3,)
        A quaternion (its axis and angle in [0, π] are used), or an axis vector.
    angle : float, optional
        The angle in radians, required with an axis vector, not allowed with a
        quaternion.
    points : array_like, shape (3,) or (k, 3), optional
        Points to rotate; default one point off the axis.

    See Also
    --------
    shapelab.Quaternion
        The rotation's quaternion.

    Examples
    --------
    >>> import numpy as np
    >>> import shapelab as sl
    >>> fig = rotation_axis(sl.Quaternion.from_axis_angle([1, 1, 0], np.pi / 3))
    >>> type(fig).__name__
    'Figure'
    >>> print(sl.plot.alt_text(fig))
    3D view of a rotation by θ = 60.0° about the axis u = (0.71, 0.71, 0.00), an arrow through the origin: 1 point r (dots) carried along an arc of its dotted circle about the axis to q r q* (squares).
    """
    if isinstance(rotation, Quaternion):
        if angle is not None:
            raise ValueError("angle must be None when rotation is a Quaternion (it carries its own angle)")
        u, theta = rotation.to_axis_angle()
    else:
        u = as_point(rotation, "rotation", dim=3)
        if angle is None:
            raise ValueError("angle is required when rotation is an axis vector")
        theta = as_finite_scalar(angle, "angle")
        if not np.linalg.norm(u) > 0:
            raise ValueError("rotation must be a non-zero axis vector")
        u = u / np.linalg.norm(u)
    if points is None:
        helper = np.array([1.0, 0.0, 0.0]) if abs(u[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
        perp = np.cross(u, helper)
        P = (perp / np.linalg.norm(perp) + 0.45 * u)[None, :]
    else:
        P = np.atleast_2d(np.asarray(points, dtype=float))
        P = as_points(P, "points", dim=3)
    fig, ax = axes(ax, projection="3d", planar=True)
    t = np.linspace(0.0, theta, 64)
    full = np.linspace(0.0, 2 * np.pi, 129)
    with style():
        L = 1.25 * max(1.0, float(np.abs(P).max()))
        ax.plot(*np.stack([-L * u, L * u]).T, color=COLORS["complex"], lw=1.2, alpha=0.5)
        ax.quiver(0, 0, 0, *(L * u), color=COLORS["complex"], lw=2.0, arrow_length_ratio=0.12)
        ax.text(*(1.08 * L * u), "u", fontsize=13, fontweight="bold")
        ax.scatter([0], [0], [0], color=COLORS["complex"], s=14, depthshade=False)
        everything = [np.stack([-L * u, L * u])]
        for j, p in enumerate(P):
            c = float(p @ u) * u  # the foot of p on the axis
            circle = qrotate(qfrom_axis_angle(u, full), np.broadcast_to(p, (full.size, 3)))
            arc = qrotate(qfrom_axis_angle(u, t), np.broadcast_to(p, (t.size, 3)))
            q = arc[-1]
            ax.plot(*circle.T, color=COLORS["muted"], lw=0.9, ls=":")
            ax.plot(*arc.T, color=COLORS["accent"], lw=2.6, label="rotation by θ" if j == 0 else None)
            if abs(theta) > 1e-9:
                d = arc[-1] - arc[-4]
                ax.quiver(
                    *arc[-4], *d, color=COLORS["accent"], lw=2.6, arrow_length_ratio=0.9, length=1.0, normalize=False
                )
            for end in (p, q):
                ax.plot(*np.stack([c, end]).T, color=COLORS["muted"], lw=1.0, ls="--")
            ax.scatter(*p, s=60, color=COLORS["red"], depthshade=False, label="r" if j == 0 else None, zorder=5)
            ax.scatter(
                *q,
                s=60,
                color=COLORS["green"],
                marker="s",
                depthshade=False,
                label="q r q*" if j == 0 else None,
                zorder=5,
            )
            mid = arc[len(arc) // 2]
            ax.text(*(c + 1.18 * (mid - c)), "θ", color=COLORS["accent"], fontsize=13)
            everything += [circle, p[None], q[None]]
        _cube_limits(ax, np.vstack(everything), pad=0.02)
        ax.view_init(elev=elev, azim=azim)
        ax.legend(loc="upper left")
        ax.set_title(
            title or (f"Rotation by θ = {np.degrees(theta):.1f}° about u = ({u[0]:.2f}, {u[1]:.2f}, {u[2]:.2f})")
        )
        describe(
            ax,
            f"3D view of a rotation by θ = {np.degrees(theta):.1f}° about the axis u = ({u[0]:.2f}, {u[1]:.2f}, "
            f"{u[2]:.2f}), an arrow through the origin: {len(P)} point{'s' if len(P) != 1 else ''} r (dots) carried "
            "along an arc of its dotted circle about the axis to q r q* (squares)",
        )
    return fig


def two_stage(
    source: ArrayLike,
    target: ArrayLike,
    stages: dict,
    *,
    size: tuple[float, float] = (12.0, 4.5),
    elev: float = 20.0,
    azim: float = 35.0,
) -> Figure:
    """Two-stage matching (Notes §23.2): one 3D panel per stage, the moved source on the target.

    Parameters
    ----------
    source, target : array_like, shape (n, 3), (m, 3)
        The red set R and the green set G.
    stages : dict of str → RigidMotion or ICPResult
        Panel title → the motion to draw (an :class:`~shapelab.ICPResult` draws its
        final motion), in panel order; for example the plain ICP result, the best
        :func:`shapelab.coarse_align` candidate, and ICP started from it.
    size : (float, float)
        Figure size in inches.

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.coarse_align
        Stage one.
    shapelab.icp
        Stage two.

    Examples
    --------
    >>> import numpy as np
    >>> import shapelab as sl
    >>> rng = np.random.default_rng(0)
    >>> target = rng.normal(size=(30, 3))
    >>> source = sl.Quaternion.from_axis_angle([0, 0, 1], 0.3).rotate(target) + rng.normal(0, 0.05, (30, 3))
    >>> fig = two_stage(source, target, {"coarse": sl.coarse_align(source, target)[0].motion, "ICP": sl.icp(source, target)})
    >>> type(fig).__name__
    'Figure'
    >>> print(sl.plot.alt_text(fig))
    2 panels. Left: 3D view, coarse: the source R moved (30 dots) on the target G (squares), RMS 0.12. Right: 3D view, ICP: the source R moved (30 dots) on the target G (squares), RMS 0.081.
    """
    source = as_points(source, "source", dim=3)
    target = as_points(target, "target", dim=3)
    if not isinstance(stages, dict) or not stages:
        raise TypeError("stages must be a non-empty dict of title -> RigidMotion or ICPResult")
    motions = {}
    for title, m in stages.items():
        if isinstance(m, ICPResult):
            m = m.motion
        if not isinstance(m, RigidMotion):
            raise TypeError(f"stages[{title!r}] must be a RigidMotion or an ICPResult, got {type(m).__name__}")
        motions[str(title)] = m
    fig, axes = new_figure(1, len(motions), size=size, projection="3d")
    axes = np.atleast_1d(axes)
    for ax, (title, m) in zip(axes, motions.items(), strict=True):
        point_sets(m.apply(source), target, ax=ax, title=title, labels=("R moved", "G"), elev=elev, azim=azim)
    for ax in axes[1:]:
        legend = ax.get_legend()
        if legend is not None:
            legend.remove()
    for ax, (title, m) in zip(axes, motions.items(), strict=True):
        moved = m.apply(source)
        if moved.shape == target.shape:
            rms = float(np.sqrt(((moved - target) ** 2).sum(axis=1).mean()))
            describe(
                ax,
                f"3D view, {title}: the source R moved ({len(source)} dots) on the target G (squares), RMS {rms:.3g}",
            )
        else:
            describe(
                ax, f"3D view, {title}: the source R moved ({len(source)} dots) on the target G ({len(target)} squares)"
            )
    return fig


def displacement(
    residues: ArrayLike,
    displacements: dict,
    *,
    domains: dict | None = None,
    ax: Axes | None = None,
    title: str | None = None,
    unit: str = "Å",
) -> Figure:
    """Per-residue displacement after a superposition, one curve per fit.

    Parameters
    ----------
    residues : array_like, shape (n,)
        Residue numbers (the horizontal axis).
    displacements : dict of str → array_like, shape (n,)
        Label → the distance of each residue's atom to its partner after that fit.
    domains : dict of str → (first, last), optional
        Residue ranges to shade and name (e.g. a protein's mobile domains).

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.register
        The superposition.

    Examples
    --------
    >>> import numpy as np
    >>> import shapelab as sl
    >>> residues = np.arange(1, 11)
    >>> fig = displacement(residues, {"after ICP": np.linspace(0.5, 2.0, 10)})
    >>> type(fig).__name__
    'Figure'
    >>> print(sl.plot.alt_text(fig))
    the displacement of each of 10 residues after superposition, one line style per fit. after ICP: largest 2.00 Å at residue 10, median 1.25 Å.
    """
    x = np.asarray(residues, float).ravel()
    if not isinstance(displacements, dict) or not displacements:
        raise TypeError("displacements must be a non-empty dict of label -> per-residue distances")
    fig, ax = axes(ax, planar=True)
    with style():
        for k, (name, (a, b)) in enumerate((domains or {}).items()):
            ax.axvspan(a - 0.5, b + 0.5, color=_SHADES[k % len(_SHADES)], alpha=0.35, lw=0)
            ax.text((a + b) / 2, 1.0, name, transform=ax.get_xaxis_transform(), ha="center", va="bottom", fontsize=10)
        for k, (label, d) in enumerate(displacements.items()):
            d = np.asarray(d, float).ravel()
            if d.shape != x.shape:
                raise ValueError(f"displacements[{label!r}] must have one value per residue")
            ax.plot(
                x,
                d,
                color=(COLORS["red"], COLORS["green"], COLORS["muted"])[k % 3],
                ls=("-", "--", ":")[k % 3],
                lw=1.6,
                label=label,
            )
        ax.set_xlabel("residue")
        ax.set_ylabel(f"displacement ({unit})")
        ax.set_ylim(bottom=0)
        ax.legend(loc="upper center", frameon=False)
        if title:
            ax.set_title(title, pad=18)
        curves = "; ".join(
            f"{label}: largest {np.max(d):.2f} {unit} at residue {x[int(np.argmax(d))]:g}, median {np.median(d):.2f} {unit}"
            for label, d in ((k, np.asarray(v, float).ravel()) for k, v in displacements.items())
        )
        describe(
            ax,
            (f"{title}: " if title else "")
            + f"the displacement of each of {len(x)} residues after superposition, one line style per fit. {curves}"
            + (f"; shaded domains: {', '.join(domains)}" if domains else ""),
        )
    return fig
