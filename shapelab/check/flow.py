"""Self-checks on the discrete flow (lesson 09; Notes §23.1, "Voids and pockets")."""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ._runner import CheckResult, run_check

if TYPE_CHECKING:
    from collections.abc import Callable, Sequence

    from ..balls import Balls

__all__ = ["flow_order"]


class _Arrows:
    """The flow's arrows between the empty top simplices ``cells`` (ball indices, in
    the shuffled order given to the student), shown in a failing message as what an
    order must respect (never as an order: that would be the answer)."""

    def __init__(self, balls, cells, F, tau):
        from ..flow import discrete_flow

        flow = discrete_flow(F, tau)
        i, j = np.nonzero(flow.flows)
        k = flow.neighbour[i, j]
        inside = k >= 0  # arrows to infinity constrain nothing
        rows = {tuple(r): n for n, r in enumerate(np.sort(np.asarray(F.simplices(balls.dim)), axis=1).tolist())}
        index = np.full(len(F.values(balls.dim)), -1, dtype=np.int64)
        index[[rows[tuple(c)] for c in np.sort(cells, axis=1).tolist()]] = np.arange(len(cells))
        self.m = len(cells)
        self.src, self.dst = index[i[inside]], index[k[inside]]
        self.d = balls.dim

    def __repr__(self) -> str:
        kind = "triangles" if self.d == 2 else "tetrahedra"
        return (
            f"an order of the {self.m} {kind} in which each of the {len(self.src)} arrows between them points forward"
        )


def flow_order(student: Callable[[Balls, np.ndarray], Sequence[int]]) -> CheckResult:
    """Lesson 09: ``student(balls, cells)`` returns an order of the empty top
    simplices ``cells`` (an ``(m, d+1)`` array of ball indices, in random order: the
    top simplices of the regular triangulation not in :math:`K_\\tau`) in which every
    simplex comes before each simplex it flows into: a list of the indices
    ``0, ..., m-1`` into ``cells``, each once (a topological order of the flow, which
    exists because the flow has no cycle).

    The cases are balls in general position (no four disks, no five 3D balls with a
    common orthogonal circle or sphere), so that the orthosphere's power increases
    strictly along every arrow: unequal disks first (a triangle there can flow across
    two edges, and the circumradius of the centres, which ignores the weights, does
    not order the flow), then disks of one radius, then 3D balls, at several τ.

    See Also
    --------
    shapelab.discrete_flow
        The flow whose arrows the order must respect.

    Examples
    --------
    >>> # the order of the rows as given is no order of the flow
    >>> result = flow_order(lambda balls, cells: list(range(len(cells))))  # doctest: +ELLIPSIS
    ✗ an order of the discrete flow: not quite. First failing input (case 1):...
    >>> result.passed
    False
    """
    from ..balls import Balls
    from ..filtration import alpha_filtration

    rng = np.random.default_rng(11)
    cases = []
    specs = [(2, 40, 0.0, True), (2, 60, 0.5, True), (2, 40, 0.0, False), (3, 50, 0.0, True), (3, 70, -0.3, True)]
    for d, n, tau, unequal in specs:
        radii = rng.uniform(0.3, 1.6, n) if unequal else 0.7
        balls = Balls(rng.uniform(-5, 5, (n, d)), radii)
        F = alpha_filtration(balls)
        rows = np.flatnonzero(np.asarray(F.values(d)) > tau)
        cells = np.asarray(F.simplices(d))[rng.permutation(rows)]
        cases.append((balls, cells, F, tau))

    def respects(expected: _Arrows, received) -> bool:
        try:
            got = [int(i) for i in received]
        except (TypeError, ValueError):
            return False
        if sorted(got) != list(range(expected.m)):
            return False
        pos = np.empty(expected.m, dtype=np.int64)
        pos[np.asarray(got, dtype=np.int64)] = np.arange(expected.m)
        return bool(np.all(pos[expected.src] < pos[expected.dst]))

    def call(balls, cells, F, tau):  # the student sees the balls and the cells only
        return student(balls, cells)

    return run_check(
        "an order of the discrete flow",
        call if callable(student) else student,
        cases,
        _Arrows,
        respects,
        describe=lambda case: (
            f"{len(case[0])} {'disks' if case[0].dim == 2 else 'balls'} of "
            f"{'unequal radii' if np.ptp(case[0].radii) > 0 else 'one radius'}, the {len(case[1])} empty "
            f"{'triangles' if case[0].dim == 2 else 'tetrahedra'} at tau = {case[3]:g}"
        ),
    )
