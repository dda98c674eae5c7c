"""The discrete flow in 2D: arrows between empty triangles, sinks, pocket regions."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from matplotlib.collections import LineCollection, PatchCollection, PolyCollection
from matplotlib.patches import Circle

from ._describe import describe
from ._style import COLORS, PAGE, PALETTE, new_figure, style

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from ..balls import Balls
    from ..filtration import Filtration

__all__ = ["discrete_flow"]


def _n(k: int, word: str) -> str:
    return f"{k} {word}" + ("" if k == 1 else "s")


def discrete_flow(
    F: Filtration | Balls,
    tau: float = 0.0,
    *,
    ax: Axes | None = None,
    title: str | None = None,
    legend: bool = True,
    arrows: bool = True,
) -> Figure:
    """Draw Edelsbrunner's discrete flow of 2D disks at ``tau`` (Notes §23.1).

    The triangles of :math:`K_\\tau` are grey; each empty triangle is coloured by its
    pocket region (a void in vermillion), white if its flow reaches the outside; an
    arrow goes from each empty triangle across every edge it flows over (to the
    neighbour's centroid, or out of the hull); sinks carry a black dot, and each
    region's mouth is drawn as thick pink edges.

    Parameters
    ----------
    F : Filtration
        ``alpha_filtration(balls)`` of 2D disks (or the :class:`~shapelab.Balls`).
    tau : float, default 0.0
    ax : matplotlib Axes, optional
    title : str, optional
    legend : bool, default True
    arrows : bool, default True

    Returns
    -------
    matplotlib.figure.Figure

    See Also
    --------
    shapelab.discrete_flow : what is drawn.
    shapelab.plot.pockets : the growth model's pockets.

    References
    ----------
    .. [1] H. Edelsbrunner, M. Facello and J. Liang, "On the definition and the
       construction of pockets in macromolecules", Discrete Appl. Math. 88 (1998) 83-102.

    Examples
    --------
    >>> import shapelab as sl
    >>> fig = discrete_flow(sl.alpha_filtration(sl.datasets.figure_23_2()[0]), tau=0.0)
    >>> type(fig).__name__
    'Figure'
    >>> print(sl.plot.alt_text(fig))
    discrete flow at τ = 0: 1 pocket(s), 0 void(s): the discrete flow of 112 disks at τ = 0 over 203 triangles, 174 of them in K (grey); 1 pocket (orange, hatched //), 0 voids (vermillion, hatched xx), the other empty triangles flowing to the outside (white); 2 sinks (black dots), 1 mouth edge (thick reddish purple), arrows across the edges the flow crosses.
    """
    from ..cavities.flow import discrete_flow as compute_flow
    from ..filtration import as_filtration

    F = as_filtration(F, "plot.discrete_flow")
    balls = F.balls
    if balls.dim != 2:
        raise ValueError(f"plot.discrete_flow: draws 2D disks, got balls of dimension {balls.dim}")
    flow = compute_flow(F, tau)
    if ax is None:
        fig, ax = new_figure(size=PAGE)
    fig = ax.figure
    z, r = balls.centers, balls.radii
    S = np.asarray(F.simplices(2), dtype=np.int64)
    with style():
        rr = np.sqrt(np.maximum(r * r + flow.tau, 0.0)) if np.isfinite(flow.tau) else r
        ax.add_collection(
            PatchCollection(
                [Circle(c, q) for c, q in zip(z, rr)],
                facecolor=COLORS["ball"],
                edgecolor=COLORS["ball_edge"],
                alpha=0.25,
                linewidth=0.5,
            )
        )
        tri = z[S]
        face = []
        for i in range(len(S)):
            if not flow.empty[i]:
                face.append("#bbbbbb")
            elif flow.region[i] < 0:
                face.append("#ffffff")
            else:
                p = flow.pockets[int(flow.region[i])]
                face.append(COLORS["void"] if p.is_void else PALETTE[1])
        ax.add_collection(PolyCollection(tri, facecolors=face, edgecolors="#555555", linewidths=0.4, alpha=0.8))
        # hatched, so that pockets and voids differ by more than their colour
        for hatch, keep in (("//", False), ("xx", True)):
            sel = [
                i
                for i in range(len(S))
                if flow.empty[i] and flow.region[i] >= 0 and flow.pockets[int(flow.region[i])].is_void == keep
            ]
            if sel:
                ax.add_collection(
                    PolyCollection(tri[sel], facecolors="none", edgecolors="#333333", linewidths=0, hatch=hatch)
                )
        E = np.asarray(F.simplices(1), dtype=np.int64)
        mouth = [z[E[m]] for p in flow.pockets for m in p.mouth_ids]
        if mouth:
            ax.add_collection(LineCollection(mouth, colors=COLORS["mouth"], linewidths=4, zorder=4))
        cen = tri.mean(axis=1)
        if arrows:
            B = np.asarray(F.boundary(2), dtype=np.int64)
            for i, j in zip(*np.nonzero(flow.flows)):
                nb = flow.neighbour[i, j]
                if nb >= 0:
                    end = cen[nb]
                else:  # out of the hull: just beyond the edge's midpoint
                    mid = z[E[B[i, j]]].mean(axis=0)
                    end = mid + 0.6 * (mid - cen[i])
                ax.annotate(
                    "",
                    xy=end,
                    xytext=cen[i],
                    arrowprops=dict(arrowstyle="-|>", color="#000000", lw=0.8, shrinkA=0, shrinkB=2),
                    zorder=5,
                )
        sk = np.flatnonzero(flow.sink)
        ax.plot(cen[sk, 0], cen[sk, 1], "o", color="#000000", ms=5, zorder=6, label="sink")
        if legend:
            from matplotlib.patches import Patch

            handles = [
                Patch(facecolor="#bbbbbb", label="in $K_\\tau$"),
                Patch(facecolor=PALETTE[1], hatch="//", label="pocket (flow stays in)"),
                Patch(facecolor="#ffffff", edgecolor="#555555", label="flows to the outside"),
                Patch(facecolor=COLORS["void"], hatch="xx", label="void"),
                ax.lines[-1],
                LineCollection([], colors=COLORS["mouth"], linewidths=4, label="mouth"),
            ]
            ax.legend(handles=handles, loc="upper left", bbox_to_anchor=(1.01, 1.0), fontsize=9, frameon=False)
        lo, hi = (z - rr[:, None]).min(axis=0), (z + rr[:, None]).max(axis=0)
        pad = 0.05 * (hi - lo).max()
        ax.set_xlim(lo[0] - pad, hi[0] + pad)
        ax.set_ylim(lo[1] - pad, hi[1] + pad)
        ax.set_aspect("equal")
        ax.set_xticks([])
        ax.set_yticks([])
        for spine in ax.spines.values():
            spine.set_visible(False)
        if title is None:
            n_void = sum(p.is_void for p in flow.pockets)
            title = f"discrete flow at τ = {flow.tau:g}: {len(flow.pockets) - n_void} pocket(s), {n_void} void(s)"
        ax.set_title(title)
        n_void = sum(p.is_void for p in flow.pockets)
        describe(
            ax,
            f"{title}: the discrete flow of {len(balls)} disks at τ = {flow.tau:g} over {len(S)} triangles, "
            f"{int((~np.asarray(flow.empty)).sum())} of them in K (grey); {_n(len(flow.pockets) - n_void, 'pocket')} "
            f"(orange, hatched //), {_n(n_void, 'void')} (vermillion, hatched xx), the other empty triangles "
            f"flowing to the outside (white); {_n(len(sk), 'sink')} (black dots), {_n(len(mouth), 'mouth edge')} "
            "(thick reddish purple)" + (", arrows across the edges the flow crosses" if arrows else ""),
        )
    return fig
