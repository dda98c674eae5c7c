"""Self-checks for exercises whose answer is a value computed from the lesson's data.

The reference computation lives here, not in the lesson: the exercise cell shows neither
the answer nor the code that finds it, and a wrong answer is described ("too large",
"3 of 10 entries differ") but never given.  Each check takes the student's answer first,
then the lesson's objects the reference needs.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from ._runner import CheckResult, value

if TYPE_CHECKING:
    from ..balls import Balls
    from ..cavities import Pocket
    from ..filtration import Filtration
    from ..io import PDBStructure

__all__ = [
    "connected_time",
    "distinct_complexes",
    "standard_error_factor",
    "neck_closing",
    "mouth_closing",
    "flow_sinks",
    "torus_viewpoints",
    "radical_center",
    "void_count",
    "ring_tunnel",
    "curve_pairs",
    "euler_poincare",
    "most_exposed_residue",
    "pocket_residues",
    "void_radii",
    "void_components",
    "buried_area",
    "most_spread_class",
    "rips_not_nerve",
    "first_site_rank",
]


def connected_time(tau_connected: float, F: Filtration, *, atol: float = 2e-3) -> CheckResult:
    """Lesson 03: the growth time from which the union of disks is connected.

    The reference is the last merge of two components: the largest finite death of
    the persistence pairs in dimension 0 (lesson 11).

    See Also
    --------
    shapelab.persistence.betti
        β₀ at a growth time.

    Examples
    --------
    >>> import shapelab as sl
    >>> F = sl.alpha_filtration(sl.Balls([[0.0, 0.0], [4.0, 0.0]], [1.0, 1.0]))
    >>> # two unit disks 4 apart touch when (4/2)^2 - 1 = 3
    >>> ok = connected_time(3.0, F)
    ✓ τ at which the union becomes connected (to 0.002): correct.
    >>> bad = connected_time(2.0, F)
    ✗ τ at which the union becomes connected (to 0.002): not quite: yours is too small.
    """
    h0 = np.asarray(F.persistence()[0], dtype=float)
    finite = h0[np.isfinite(h0[:, 1]), 1]
    expected = float(finite.max()) if finite.size else float(F.values(0).max())
    return value("τ at which the union becomes connected (to 0.002)", tau_connected, expected, atol=atol, rtol=0.0)


def distinct_complexes(n_complexes: int, F: Filtration, lo: float = 0.0, hi: float = 1.0) -> CheckResult:
    """Lesson 04: how many distinct complexes :math:`K_\\tau` there are for τ in [lo, hi].

    The complexes grow by inclusion, so distinct complexes have distinct sizes: the
    reference counts the sizes of the complexes at every entry time in the range.

    See Also
    --------
    shapelab.alpha_filtration
        The filtration whose complexes are counted.

    Examples
    --------
    >>> import shapelab as sl
    >>> F = sl.alpha_filtration(sl.Balls([[0.0, 0.0], [4.0, 0.0]], [1.0, 1.0]))
    >>> # for tau in [0, 5]: the two disks, then the edge from tau = 3
    >>> ok = distinct_complexes(2, F, 0.0, 5.0)
    ✓ number of distinct complexes: correct.
    >>> bad = distinct_complexes(3, F, 0.0, 5.0)
    ✗ number of distinct complexes: not quite: yours is too large.
    """
    values = np.unique(np.r_[lo, np.concatenate([F.values(k) for k in range(F.dimension + 1)])])
    sizes = {len(F.complex_at(t)) for t in values[(values >= lo) & (values <= hi)]}
    return value("number of distinct complexes", n_complexes, len(sizes))


def standard_error_factor(shrink: float, balls: Balls, *, seed: int = 0) -> CheckResult:
    """Lesson 05: by what factor Monte Carlo's standard error falls with 100 times more
    samples (measured on ``balls`` with 10⁴ and 10⁶ samples, to 5 %).

    See Also
    --------
    shapelab.oracles.monte_carlo_union_measure
        The estimate whose error shrinks.

    Examples
    --------
    >>> import shapelab as sl
    >>> bad = standard_error_factor(100.0, sl.Balls([[0.0, 0.0], [1.0, 0.0]], [1.0, 1.0]))
    ✗ the standard error's factor per 100 times more samples: not quite: yours is too large.
    """
    from ..oracles import monte_carlo_union_measure

    ratio = (
        monte_carlo_union_measure(balls, 10**4, seed=seed)[1] / monte_carlo_union_measure(balls, 10**6, seed=seed)[1]
    )
    return value("the standard error's factor per 100 times more samples", shrink, ratio, rtol=0.05)


def neck_closing(neck_closes: float, F: Filtration) -> CheckResult:
    """Lesson 08: when the neck between the two chambers of ``datasets.nested_pockets``
    closes: the second pocket's ``closes_at``.

    See Also
    --------
    shapelab.pockets
        The pocket whose neck closes.

    Examples
    --------
    >>> import shapelab as sl
    >>> F = sl.alpha_filtration(sl.datasets.nested_pockets())
    >>> bad = neck_closing(-1.0, F)
    ✗ when the neck closes: not quite: yours is too small.
    """
    from ..cavities import pockets

    found = pockets(F, min_persistence=1e-9)
    expected = found[1].closes_at if len(found) > 1 else np.nan
    return value("when the neck closes", neck_closes, expected)


def _torus_kind(S, R: float, r: float) -> str | None:
    S = np.asarray(S, dtype=float)
    rho = float(np.hypot(S[0], S[1]))
    if np.linalg.norm(S) > R + r + 0.6:
        return "far outside"
    if np.linalg.norm(S) < 0.75 * (R - r):
        return "in the hole"
    if np.hypot(rho - R, S[2]) < 0.5 * r:
        return "inside the tube"
    return None


def torus_viewpoints(
    viewpoints: ArrayLike, counts: ArrayLike, *, n_major: int = 24, n_minor: int = 12, R: float = 1.0, r: float = 0.4
) -> CheckResult:
    """Lesson 13: three viewpoints on ``torus(24, 12)`` (far outside, in the hole,
    inside the tube) and the student's ``(#min, #saddles, #max)`` from each.

    Passes when the three viewpoints are one of each kind and every count equals the
    library's (:func:`shapelab.critical_points`).  Nothing about the counts is printed.

    See Also
    --------
    shapelab.critical_points
        The critical points seen from a viewpoint.

    Examples
    --------
    >>> import numpy as np
    >>> bad = torus_viewpoints([[5.0, 0.0, 0.0], [0.0, 0.0, 0.0], [0.0, 5.0, 0.0]], np.zeros((3, 3), dtype=int))
    ✗ critical points of the torus from three viewpoints: the viewpoints must be one far outside (more than 2 from the centre), one in the hole (within 0.45 of the centre) and one inside the tube (within 0.2 of its core circle); yours are: far outside, in the hole, far outside.
    """
    from ..critical import critical_points
    from ..datasets import torus

    name = "critical points of the torus from three viewpoints"
    try:
        P = np.asarray(viewpoints, dtype=float)
        C = np.asarray(counts, dtype=float)
    except (TypeError, ValueError):
        return value(name, None, np.zeros((3, 3)), quiet=False)
    if P.shape != (3, 3) or C.shape != (3, 3) or not np.all(np.isfinite(P)):
        return value(name, C if C.shape != (3, 3) else None, np.zeros((3, 3)))
    kinds = [_torus_kind(S, R, r) for S in P]
    if sorted(k or "" for k in kinds) != ["far outside", "in the hole", "inside the tube"]:
        msg = (
            f"✗ {name}: the viewpoints must be one far outside (more than {R + r + 0.6:g} from the "
            f"centre), one in the hole (within {0.75 * (R - r):g} of the centre) and one inside the "
            f"tube (within {0.5 * r:g} of its core circle); yours are: "
            + ", ".join(k or "none of these" for k in kinds)
            + "."
        )
        print(msg)
        return CheckResult(name, False, 1, msg)
    V, F = torus(n_major, n_minor, R=R, r=r)
    expected = []
    for S in P:
        cp = critical_points(V, S, faces=F)
        expected.append([cp.n_min, cp.n_saddle, cp.n_max])
    return value(name, C, np.array(expected, dtype=float), rtol=0.0, atol=0.0)


def mouth_closing(student: Callable[[Pocket, Balls], float]) -> CheckResult:
    """Lesson 08: ``student(pocket, balls)`` returns the time at which the pocket's mouth
    closes, from its mouth edges; checked against the entry time in the filtration of
    its last mouth edge (``pocket.closes_at`` for a pocket that is not nested; the
    two-chamber flask's inner pocket becomes a hole of its own later) on the pockets of
    Figure 23.2's flask and of the two-chamber flask, then of Figure 23.2's flask with
    radii from 0.9 to 1.1 times its own (seeded): the data sets' disks all have one
    radius, on which :math:`(d/2)^2 - r^2` is right, and the lesson's formula is for two
    radii (Notes §23.1, the edge's entry time on the radical axis); last, a ring with a
    small disk in its gap, whose two mouth edges close at different times (every
    other case has one mouth edge, on which the first, the smallest or the mean of the
    edges' times is right too).

    See Also
    --------
    shapelab.pockets
        The pocket whose mouth closes.

    Examples
    --------
    >>> result = mouth_closing(lambda pocket, balls: pocket.closes_at)  # doctest: +ELLIPSIS
    ✗ when a pocket's mouth closes: not quite. First failing input (case 3):...
    >>> result.passed
    False
    """
    from ..balls import Balls
    from ..cavities import pockets
    from ..datasets import figure_23_2, nested_pockets
    from ..filtration import alpha_filtration
    from ._runner import run_check

    flask = figure_23_2()[0]
    uneven = Balls(flask.centers, flask.radii * np.random.default_rng(0).uniform(0.9, 1.1, len(flask)))
    cases, closes = [], {}
    # a ring of twelve places, one left empty, and a small disk in the gap off its middle
    t = np.deg2rad(np.r_[np.arange(30.0, 331.0, 30.0), 6.0])
    gapped = Balls(3 * np.c_[np.cos(t), np.sin(t)], np.r_[np.full(11, 0.9), 0.3])
    for balls in (flask, nested_pockets(), figure_23_2(disk_radius=0.6)[0], uneven, gapped):
        F = alpha_filtration(balls)
        for p in pockets(F, 0.0, min_persistence=1e-9):
            cases.append((p, balls))
            closes[id(p)] = float(np.max(np.asarray(F.values(1))[p.mouth_ids]))
    return run_check(
        "when a pocket's mouth closes",
        student,
        cases,
        lambda p, b: closes[id(p)],
        describe=lambda case: f"a pocket with {len(case[0].mouth)} mouth edges among {len(case[1])} disks",
    )


def flow_sinks(student: Callable[[Filtration, float], Sequence[int]]) -> CheckResult:
    """Lesson 08: ``student(F, tau)`` returns the rows of ``F.simplices(2)`` that are the
    sinks of the discrete flow at ``tau`` (disks of one radius), as a list; compared as
    sets with :func:`shapelab.discrete_flow` on a ring of disks with a gap and on seeded
    random disks at three growth times (every case has sinks; the random ones also
    have centred triangles already in :math:`K_\\tau`, which are no sinks), after
    two edge cases: a lattice with right triangles (sinks: the circumcentre is on the
    hypotenuse) and a τ equal to a centred triangle's entry time (then in
    :math:`K_\\tau`, no sink) (Notes §23.1).

    See Also
    --------
    shapelab.discrete_flow
        The flow whose sinks are checked.

    Examples
    --------
    >>> import numpy as np
    >>> import shapelab as sl
    >>> ok = flow_sinks(lambda F, tau: np.flatnonzero(sl.discrete_flow(F, tau).sink).tolist())
    ✓ the sinks of the discrete flow: correct on all 6 cases.
    >>> # every empty triangle is not a sink
    >>> bad = flow_sinks(lambda F, tau: list(range(len(F.simplices(2)))))  # doctest: +ELLIPSIS
    ✗ the sinks of the discrete flow: not quite. First failing input (case 1):...
    """
    from ..balls import Balls
    from ..cavities.flow import discrete_flow
    from ..filtration import alpha_filtration
    from ._runner import run_check

    rng = np.random.default_rng(7)
    t = np.linspace(0, 2 * np.pi, 14, endpoint=False)[1:]
    ring = Balls(3 * np.c_[np.cos(t), np.sin(t)] + rng.normal(0, 0.05, (13, 2)), 0.8)
    cases = [(alpha_filtration(ring), 0.0)]
    for n, tau in ((30, 0.0), (30, 0.6), (40, 0.2)):
        cases.append((alpha_filtration(Balls(rng.uniform(-4, 4, (n, 2)), 0.7)), tau))
    # edge cases: right triangles (circumcentre on the hypotenuse, in the closed
    # triangle: sinks) on a lattice of even integers, three points moved by dyadic
    # amounts (all exact); tau equal to a centred triangle's entry time (it is in K_tau)
    g = np.array([(2.0 * i, 2.0 * j) for i in range(5) for j in range(4)])
    g[[6, 9, 13]] += [[0.5, 0.25], [-0.25, 0.5], [0.25, -0.5]]
    F_right = alpha_filtration(Balls(g, 0.7))
    F_tie = alpha_filtration(Balls(rng.uniform(-4, 4, (30, 2)), 0.7))
    centred = np.flatnonzero(discrete_flow(F_tie, -np.inf).sink)
    tie = float(np.sort(F_tie.values(2)[centred])[len(centred) // 2])
    cases = [(F_right, 0.0), (F_tie, tie), *cases]  # edge cases first
    notes = {id(F_right): " (a lattice: right triangles)", id(F_tie): " (a triangle enters at this tau)"}

    def same_set(expected, received):
        try:
            got = sorted(int(i) for i in received)
        except (TypeError, ValueError):
            return False
        return got == sorted(int(i) for i in expected) and len(got) == len(set(got))

    return run_check(
        "the sinks of the discrete flow",
        student,
        cases,
        lambda F, tau: np.flatnonzero(discrete_flow(F, tau).sink).tolist(),
        same_set,
        describe=lambda case: f"{len(case[0].balls)} disks at tau = {case[1]:g}{notes.get(id(case[0]), '')}",
    )


def radical_center(student: Callable[[Balls], ArrayLike]) -> CheckResult:
    """Lesson 01: ``student(balls)`` returns the point with equal power distance from three
    disks (their radical centre), checked against the vertex of their power diagram.

    See Also
    --------
    shapelab.power_diagram
        The diagram whose vertex it is.

    Examples
    --------
    >>> import numpy as np
    >>> import shapelab as sl
    >>> ok = radical_center(lambda balls: sl.power_diagram(balls).vertices[0])
    ✓ radical centre of three disks: correct on all 6 cases.
    >>> # the centroid of the centres is no radical centre
    >>> bad = radical_center(lambda balls: balls.centers.mean(axis=0))  # doctest: +ELLIPSIS
    ✗ radical centre of three disks: not quite. First failing input (case 1):...
    """
    from ..balls import Balls
    from ..power import power_diagram
    from ._runner import run_check

    rng = np.random.default_rng(23)
    cases = [
        (Balls([[0.0, 0.0], [4.0, 0.0], [0.0, 3.0]], [1.0, 1.0, 1.0]),),
        (Balls([[0.0, 0.0], [3.0, 0.5], [1.0, 2.5]], [1.0, 1.2, 0.8]),),
    ]
    while len(cases) < 6:
        b = Balls(rng.uniform(-3, 3, size=(3, 2)), rng.uniform(0.3, 1.5, size=3))
        d = power_diagram(b)
        (ux, uy), (vx, vy) = b.centers[1] - b.centers[0], b.centers[2] - b.centers[0]
        area2 = ux * vy - uy * vx  # twice the signed area (np.cross of 2-vectors is deprecated)
        if abs(area2) > 1.0 and len(d.vertices) == 1 and not np.any(d.hidden):
            cases.append((b,))
    return run_check(
        "radical centre of three disks",
        student,
        cases,
        lambda b: power_diagram(b).vertices[0],
        describe=lambda c: f"centres {np.round(c[0].centers, 3).tolist()}, radii {np.round(c[0].radii, 3).tolist()}",
    )


def void_count(student: Callable[[Filtration, float], int]) -> CheckResult:
    """Lesson 07: ``student(F, tau)`` returns the number of voids from the Betti numbers
    alone (:math:`\\beta_{d-1}` of :math:`K_\\tau`), checked against :func:`shapelab.voids`.

    See Also
    --------
    shapelab.voids
        The voids counted.

    Examples
    --------
    >>> import shapelab as sl
    >>> ok = void_count(lambda F, tau: len(sl.voids(F, tau)))
    ✓ voids from the Betti numbers: correct on all 7 cases.
    >>> bad = void_count(lambda F, tau: 1)  # doctest: +ELLIPSIS
    ✗ voids from the Betti numbers: not quite. First failing input (case 2):...
    """
    from ..cavities import voids
    from ..datasets import fullerene_c60, ring, swiss_cheese
    from ..filtration import alpha_filtration
    from ._runner import run_check

    F60, Fch, Fring = alpha_filtration(fullerene_c60()), alpha_filtration(swiss_cheese()), alpha_filtration(ring(12))
    cases = [(F60, 0.0), (F60, 20.0), (Fch, 0.0), (Fch, 0.45), (Fch, 5.0), (Fring, 0.0), (Fring, 8.5)]
    names = {id(F60): "C60", id(Fch): "the 2D swiss cheese", id(Fring): "a 2D ring of 12 disks"}
    return run_check(
        "voids from the Betti numbers",
        student,
        cases,
        lambda F, t: len(voids(F, t)),
        compare=lambda e, r: isinstance(r, (int, np.integer)) and not isinstance(r, bool) and int(r) == e,
        describe=lambda c: f"{names[id(c[0])]} at τ = {c[1]:g}",
    )


def ring_tunnel(student: Callable[[int, float, float], ArrayLike]) -> CheckResult:
    """Lesson 10: ``student(n, R, r)`` returns ``(birth, death)`` of the tunnel of
    ``datasets.ring(n, radius=R, disk_radius=r, dim=3)``, checked against the most
    persistent pair of :math:`H_1` of its α-filtration.

    See Also
    --------
    shapelab.tunnels
        The tunnel of the ring.

    Examples
    --------
    >>> import numpy as np
    >>> import shapelab as sl
    >>> def tunnel(n, R, r):
    ...     F = sl.alpha_filtration(sl.datasets.ring(n, radius=R, disk_radius=r, dim=3))
    ...     P = np.asarray(F.persistence()[1])
    ...     return P[np.argmax(P[:, 1] - P[:, 0])]
    >>> ok = ring_tunnel(tunnel)
    ✓ birth and death of a ring's tunnel: correct on all 5 cases.
    >>> bad = ring_tunnel(lambda n, R, r: tunnel(n, R, r)[::-1])  # doctest: +ELLIPSIS
    ✗ birth and death of a ring's tunnel: not quite. First failing input (case 1):...
    """
    from ..datasets import ring
    from ..filtration import alpha_filtration
    from ._runner import run_check

    def reference(n, R, r):
        P = np.asarray(alpha_filtration(ring(n, radius=R, disk_radius=r, dim=3)).persistence()[1], dtype=float)
        k = int(np.argmax(P[:, 1] - P[:, 0]))
        return P[k]

    cases = [(12, 3.0, 1.0), (8, 2.0, 0.9), (10, 4.0, 0.5), (6, 1.5, 0.2), (20, 5.0, 0.3)]
    return run_check(
        "birth and death of a ring's tunnel",
        student,
        cases,
        reference,
        describe=lambda c: f"n = {c[0]}, R = {c[1]}, r = {c[2]}",
    )


def curve_pairs(student: Callable[[np.ndarray], ArrayLike]) -> CheckResult:
    """Lesson 11: ``student(f)`` returns the ``(birth, death)`` pairs (persistence > 0) of
    the sublevel sets of ``f`` along a path, checked against
    :func:`shapelab.curve_persistence` (any order of the rows).

    See Also
    --------
    shapelab.curve_persistence
        The pairs of a curve.

    Examples
    --------
    >>> import numpy as np
    >>> import shapelab as sl
    >>> def pairs(f):
    ...     D = sl.curve_persistence(f, closed=False).diagram()
    ...     return D[D[:, 1] > D[:, 0]]
    >>> ok = curve_pairs(pairs)
    ✓ persistence pairs along a path: correct on all 7 cases.
    >>> # the pairs of the closed curve are refused
    >>> bad = curve_pairs(lambda f: sl.curve_persistence(f, closed=True).diagram())  # doctest: +ELLIPSIS
    ✗ persistence pairs along a path: not quite. First failing input (case 4):...
    """
    from ..simplification import curve_persistence
    from ._runner import run_check

    def reference(f):
        D = curve_persistence(f, closed=False).diagram()
        D = D[D[:, 1] > D[:, 0]]
        return D[np.lexsort((D[:, 1], D[:, 0]))]

    def compare(expected, received):
        try:
            R = np.asarray(received, dtype=float).reshape(-1, 2)
        except (TypeError, ValueError):
            return False
        R = R[np.lexsort((R[:, 1], R[:, 0]))]
        return R.shape == expected.shape and bool(np.allclose(R, expected))

    rng = np.random.default_rng(9)
    cases = [
        (np.array([0.0, 3.0, 1.0, 2.0, -1.0, 4.0]),),
        (np.array([1.0, 2.0, 3.0]),),
        (np.array([2.0, 0.0, 2.0, 0.0, 2.0]),),
    ]
    cases += [(rng.integers(-5, 6, size=n).astype(float),) for n in (8, 15, 30)]
    cases += [(np.round(rng.normal(size=50), 3),)]
    return run_check("persistence pairs along a path", student, cases, reference, compare=compare)


def euler_poincare(chis: Sequence[int], betti_sums: Sequence[int], F: Filtration, taus: Sequence[float]) -> CheckResult:
    """Lesson 06: the Euler characteristic of :math:`K_\\tau` at each τ of ``taus``,
    from its simplex counts, and the alternating sum of its Betti numbers.

    Both are compared entry by entry with the library's: :math:`\\chi` from
    ``Complex.euler_characteristic`` (the alternating sum of the counts, tetrahedra
    included) and :math:`\\sum_k (-1)^k \\beta_k` from ``Filtration.betti``.  The two
    lists agree by the Euler–Poincaré formula; a wrong answer is told how many entries
    differ, never what they should be.

    Parameters
    ----------
    chis : sequence of int
        The student's :math:`\\chi(K_\\tau)`, one per τ.
    betti_sums : sequence of int
        The student's :math:`\\beta_0 - \\beta_1 + \\beta_2`, one per τ.
    F : Filtration
        The α-filtration the lesson built.
    taus : sequence of float
        The growth times.

    Returns
    -------
    CheckResult
        Passed when both lists agree with the references.

    See Also
    --------
    shapelab.check.euler_characteristic : the function exercise on χ.

    References
    ----------
    .. [1] Lecture notes, §23.1 (the dual complex and the growth model).
    .. [2] H. Edelsbrunner and J. Harer, *Computational Topology*, AMS, 2010, §IV.1
           (the Euler–Poincaré formula).

    Examples
    --------
    >>> import shapelab as sl
    >>> F = sl.alpha_filtration(sl.Balls([[0.0, 0.0], [4.0, 0.0]], [1.0, 1.0]))
    >>> ok = euler_poincare([2, 1], [2, 1], F, [0.0, 5.0])
    ✓ χ of K_τ from its counts, at each τ: correct.
    ✓ β0 − β1 + β2 at each τ: correct.
    >>> bad = euler_poincare([2, 2], [2, 1], F, [0.0, 5.0])
    ✗ χ of K_τ from its counts, at each τ: not quite: 1 of 2 entries differ, the first at index 1.
    ✓ β0 − β1 + β2 at each τ: correct.
    """
    taus = [float(t) for t in taus]
    chi = [int(F.complex_at(t).euler_characteristic()) for t in taus]
    sums = [int(sum((-1) ** k * b for k, b in enumerate(F.betti(t)))) for t in taus]
    first = value("χ of K_τ from its counts, at each τ", chis, chi)
    second = value("β0 − β1 + β2 at each τ", betti_sums, sums)
    passed = bool(first.passed and second.passed)
    return CheckResult("the Euler–Poincaré formula", passed, 2, first.message + "\n" + second.message)


def most_exposed_residue(answer: str, structure: PDBStructure, probe: float = 1.4) -> CheckResult:
    """Lesson 12: the residue (``"NAME NUMBER"``) with the largest solvent-accessible
    area, the sum of its atoms' shares of the union's boundary with radii grown by ``probe``.

    See Also
    --------
    shapelab.union_measure
        The per-ball areas summed by residue.

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> import numpy as np
    >>> import shapelab as sl
    >>> mol = SimpleNamespace(balls=sl.Balls([[0.0, 0.0, 0.0], [10.0, 0.0, 0.0]], [1.5, 1.0]),
    ...                       residue_names=np.array(["LEU", "GLY"]), residue_numbers=np.array([1, 2]))
    >>> ok = most_exposed_residue("leu 1", mol)
    ✓ the most exposed residue: correct.
    >>> bad = most_exposed_residue("GLY 2", mol)
    ✗ the most exposed residue: not quite: that residue's solvent-accessible area is 31.5 % below the largest (radii grown by the 1.4 Å probe, atoms' shares of the boundary summed per residue).
    """
    from ..balls import Balls
    from ..measure import union_measure

    b = structure.balls
    m = union_measure(Balls(b.centers, b.radii + probe))
    keys = [f"{n} {k}" for n, k in zip(structure.residue_names, structure.residue_numbers)]
    totals: dict = {}
    for key, a in zip(keys, m.ball_boundary):
        totals[key] = totals.get(key, 0.0) + float(a)
    expected = max(totals, key=lambda k: (totals[k], k))
    received = _label(answer) if isinstance(answer, str) else answer
    if isinstance(received, str) and received != expected:
        # "TYR83" or "83" is a spelling, not a residue; a real residue is told how far it falls short
        if received not in totals:
            return _fail(
                "the most exposed residue", f'{answer!r} is no residue of this structure (a label reads "NAME NUMBER")'
            )
        short = 100.0 * (1.0 - totals[received] / totals[expected])
        return _fail(
            "the most exposed residue",
            f"that residue's solvent-accessible area is {short:.1f} % below the largest "
            f"(radii grown by the {probe} Å probe, atoms' shares of the boundary summed per residue)",
        )
    return value("the most exposed residue", received, expected)


def _fail(name: str, hint: str) -> CheckResult:
    """Print and return a failed check whose ``hint`` says how the answer is off."""
    msg = f"✗ {name}: not quite: {hint}."
    print(msg)
    return CheckResult(name, False, 1, msg)


def _label(text) -> str:
    """A residue label ``"NAME NUMBER"`` in one spelling: upper case, single spaces."""
    return " ".join(str(text).split()).upper()


def pocket_residues(answer: Sequence[str], structure: PDBStructure, pocket: Pocket) -> CheckResult:
    """Lesson 12: the residues lining ``pocket``, as labels ``"NAME NUMBER"``.

    Compared as sets with the residues of the atoms in ``pocket.lining`` (Notes §23.3,
    a pocket's lining: the atoms whose balls bound it), in any order, case and spacing.
    A wrong answer is told how many of its labels do not line the pocket (and how many
    are no residue of the structure at all), how many lining residues it misses and
    whether it repeats one; never which.

    Parameters
    ----------
    answer : list of str
        The student's labels, e.g. ``["LEU 12", ...]``.
    structure : PDBStructure
        The protein (``residue_names``, ``residue_numbers`` per atom).
    pocket : Pocket
        The pocket whose ``lining`` holds atom indices into ``structure``.

    Returns
    -------
    CheckResult
        Passed when the two sets of labels are equal and no label repeats.

    See Also
    --------
    shapelab.pockets : finds the pockets and their lining atoms.

    References
    ----------
    .. [1] Lecture notes, §23.3 (pockets and their mouths).

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> import numpy as np
    >>> mol = SimpleNamespace(residue_names=np.array(["ALA", "ALA", "GLY"]),
    ...                       residue_numbers=np.array([1, 1, 2]))
    >>> ok = pocket_residues(["gly 2", "ALA 1"], mol, SimpleNamespace(lining=np.array([0, 2])))
    ✓ residues lining the pocket: correct.
    >>> bad = pocket_residues(["ALA 1", "GLY 3"], mol, SimpleNamespace(lining=np.array([0, 2])))
    ✗ residues lining the pocket: not quite: 1 of your 2 labels does not line the pocket (1 is no residue of the structure); 1 lining residue is missing.
    """
    name = "residues lining the pocket"
    names = np.asarray(structure.residue_names)
    numbers = np.asarray(structure.residue_numbers)
    lining = np.asarray(pocket.lining, dtype=np.int64).reshape(-1)
    expected = {_label(f"{names[i]} {numbers[i]}") for i in lining}
    known = {_label(f"{n} {k}") for n, k in zip(names, numbers)}
    if isinstance(answer, (str, bytes)) or not isinstance(answer, (list, tuple, set, frozenset, np.ndarray)):
        hint = f"expected a list of labels 'NAME NUMBER', got a {type(answer).__name__}"
        return _fail(name, hint)
    items = list(answer)
    if not all(isinstance(a, (str, np.str_)) for a in items):
        bad = next(a for a in items if not isinstance(a, (str, np.str_)))
        hint = f"expected labels 'NAME NUMBER' (strings), got a {type(bad).__name__} among them"
        return _fail(name, hint)
    labels = [_label(a) for a in items]
    received = set(labels)
    wrong = received - expected
    unknown = wrong - known
    missing = expected - received
    repeated = len(labels) - len(received)
    if not wrong and not missing and not repeated:
        msg = f"✓ {name}: correct."
        print(msg)
        return CheckResult(name, True, 1, msg)
    parts = []
    if wrong:
        verb = "does" if len(wrong) == 1 else "do"
        part = f"{len(wrong)} of your {len(received)} labels {verb} not line the pocket"
        if unknown:
            part += f" ({len(unknown)} {'is' if len(unknown) == 1 else 'are'} no residue of the structure)"
        parts.append(part)
    if missing:
        parts.append(f"{len(missing)} lining residue{'s are' if len(missing) != 1 else ' is'} missing")
    if repeated:
        parts.append(f"{repeated} label{'s are' if repeated != 1 else ' is'} repeated")
    return _fail(name, "; ".join(parts))


def void_radii(r_low: float, r_high: float, *, bond_length: float = 1.4, rtol: float = 1e-8) -> CheckResult:
    """Lesson 07: the carbon radii r with a void inside C60 at τ = 0, as ``[r_low, r_high)``.

    The reference comes from the α-filtration of ``datasets.fullerene_c60(atom_radius=0)``:
    with equal radii r every value shifts by :math:`-r^2` (Notes §23.1: the power distance
    is :math:`\\lVert x - z\\rVert^2 - r^2`), so the void of the bare cage, born at b₀ and
    dead at d₀, exists at τ = 0 exactly for :math:`\\sqrt{b_0} \\le r < \\sqrt{d_0}`.
    Both ends are lengths of about 1 Å computed in a few floating-point operations, so
    they compare to ``rtol`` (1e-8) relative: a closed form passes, a value read off a
    grid of radii does not.

    Parameters
    ----------
    r_low, r_high : float
        The student's ends of the interval.
    bond_length : float
        The cage's bond length (Å).
    rtol : float
        Relative tolerance on each end.

    Returns
    -------
    CheckResult
        Passed when both ends agree; otherwise says which end is too large or too small.

    See Also
    --------
    shapelab.voids : the voids of a union of balls at a growth time.

    References
    ----------
    .. [1] Lecture notes, §23.1 (the growth model) and §23.3 (voids).

    Examples
    --------
    >>> bad = void_radii(0.5, 1.0)
    ✗ the radii with a void at τ = 0 (r_low, r_high): not quite: 2 of 2 entries differ, the first at index 0.
    """
    from ..datasets import fullerene_c60
    from ..filtration import alpha_filtration

    pairs = np.asarray(
        alpha_filtration(fullerene_c60(bond_length=bond_length, atom_radius=0.0)).persistence()[2], dtype=float
    )
    birth, death = pairs[int(np.argmax(pairs[:, 1] - pairs[:, 0]))]
    return value(
        "the radii with a void at τ = 0 (r_low, r_high)",
        [r_low, r_high],
        np.sqrt([birth, death]),
        rtol=rtol,
        atol=0.0,
    )


def void_components(counts: Sequence[int], balls: Balls, taus: Sequence[float]) -> CheckResult:
    """Lesson 07: the number of bounded components of the complement of the union of
    ``balls`` grown to each τ of ``taus``, counted by the student on voxels.

    The reference is :math:`\\beta_2` of the α-complex at each τ (Alexander duality:
    the bounded components of :math:`\\mathbb{R}^3 \\setminus U_\\tau` are counted by
    :math:`\\beta_2(U_\\tau) = \\beta_2(K_\\tau)`), compared entry by entry.

    Parameters
    ----------
    counts : sequence of int
        The student's counts, one per τ.
    balls : Balls
        The union's balls (3D).
    taus : sequence of float
        The growth times.

    Returns
    -------
    CheckResult
        Passed when every count agrees; otherwise says how many differ, at which τ and in
        which direction (too many or too few), never the count itself.

    See Also
    --------
    shapelab.oracles.voxel_complement : the same count, on voxels.

    References
    ----------
    .. [1] Lecture notes, §23.1 ("Voids and pockets").
    .. [2] A. Hatcher, *Algebraic Topology*, 2002, Theorem 3.44.

    Examples
    --------
    >>> import shapelab as sl
    >>> one = sl.Balls([[0.0, 0.0, 0.0]], [1.0])
    >>> ok = void_components([0, 0], one, [0.0, 1.0])
    ✓ the bounded components of the complement at each τ: correct.
    >>> bad = void_components([1, 0], one, [0.0, 1.0])
    ✗ the bounded components of the complement at each τ: not quite: 1 of 2 counts differ, at τ = 0 (too many). Check that a voxel is in the union when its centre lies in a ball grown to τ (radius √(r² + τ)), that the unbounded component (the one touching the grid's border) is left out, and that voxels meeting only at an edge or a corner are neighbours (26-connectivity).
    """
    from ..filtration import alpha_filtration

    F = alpha_filtration(balls)
    expected = np.array([F.betti(float(t))[2] for t in taus], dtype=int)
    name = "the bounded components of the complement at each τ"
    try:
        given = np.asarray(counts)
    except (TypeError, ValueError):
        given = None
    if given is not None and given.dtype == bool:
        return _fail(name, "these are truth values (is there a void?), not counts of components")
    result = value(name, counts, expected, rtol=0.0, atol=0.0, quiet=True)
    numeric = given is not None and given.shape == expected.shape and np.issubdtype(given.dtype, np.number)
    if result.passed or not numeric or not np.all(np.isfinite(given)):
        print(result.message)
        return result
    # say where and in which direction, never the count itself
    where = [
        f"τ = {float(t):g} ({'too many' if g > e else 'too few'})" for t, g, e in zip(taus, given, expected) if g != e
    ]
    hint = f"{len(where)} of {len(expected)} counts differ, at " + ", ".join(where) + ". Check that a voxel is in "
    hint += "the union when its centre lies in a ball grown to τ (radius √(r² + τ))"
    if any(g > e for g, e in zip(given, expected)):
        hint += (
            ", that the unbounded component (the one touching the grid's border) is left out, and that voxels "
            "meeting only at an edge or a corner are neighbours (26-connectivity)"
        )
    return _fail(name, hint)


def buried_area(answer: float, receptor: Balls, ligand: Balls, probe: float = 0.0) -> CheckResult:
    """Lesson 18: the area buried when ``ligand`` binds ``receptor`` as given,
    :math:`|\\partial A| + |\\partial B| - |\\partial(A\\cup B)|` with radii grown by ``probe``
    (to 1e-6 relative).

    See Also
    --------
    shapelab.docking_score
        The buried area of a pose.

    Examples
    --------
    >>> import numpy as np
    >>> import shapelab as sl
    >>> A, B = sl.Balls([[0.0, 0.0, 0.0]], [1.0]), sl.Balls([[1.0, 0.0, 0.0]], [1.0])
    >>> # each unit sphere loses a cap of height 1/2, of area 2 pi r h = pi
    >>> ok = buried_area(2 * np.pi, A, B)
    ✓ the buried area (Å²): correct.
    >>> bad = buried_area(np.pi, A, B)
    ✗ the buried area (Å²): not quite: yours is too small.
    """
    from ..balls import Balls
    from ..measure import union_measure

    grow = probe

    def area(centers, radii):
        return union_measure(Balls(centers, radii + grow)).surface_area

    expected = (
        area(receptor.centers, receptor.radii)
        + area(ligand.centers, ligand.radii)
        - area(np.vstack([receptor.centers, ligand.centers]), np.concatenate([receptor.radii, ligand.radii]))
    )
    return value("the buried area (Å²)", answer, expected, rtol=1e-6)


def most_spread_class(
    answer: str, distances: ArrayLike, labels: Sequence[str], *, spread: dict[str, float]
) -> CheckResult:
    """Lesson 19: the class with the largest distance between two of its members, and
    that largest distance for every class.

    Both are checked: the label alone has four possible values, and a wrong reading of
    "spread" (the mean distance, one dimension's distance, the bottleneck matrix) can
    land on the right class by chance; the per-class values cannot.

    Parameters
    ----------
    answer : str
        The student's class (case and surrounding spaces ignored).
    distances : array_like, shape (n, n)
        The lesson's distance matrix between the shapes.
    labels : sequence of str
        The class of each shape.
    spread : dict
        The student's largest within-class distance, class -> number (to 1e-9
        relative), compared class by class.

    Returns
    -------
    CheckResult
        Passed when every class's value and the label are right; a wrong value is
        named by its class, never given.

    See Also
    --------
    shapelab.diagrams.distance_matrix : the matrices of the lesson.

    References
    ----------
    .. [1] Lecture notes, §23.2 (protein shape classification).

    Examples
    --------
    >>> import numpy as np
    >>> D = np.array([[0, 1, 5, 5], [1, 0, 5, 5], [5, 5, 0, 3], [5, 5, 3, 0]], dtype=float)
    >>> labels = ["alpha", "alpha", "beta", "beta"]
    >>> ok = most_spread_class("beta", D, labels, spread={"alpha": 1.0, "beta": 3.0})
    ✓ the most spread-out class: correct.
    >>> bad = most_spread_class("beta", D, labels, spread={"alpha": 1.0, "beta": 5.0})
    ✗ the largest distance within each class: not quite: yours differs for 'beta'.
    """
    D = np.asarray(distances, dtype=float)
    labels = [str(s) for s in labels]
    want = {}
    for i, a in enumerate(labels):
        for j, b in enumerate(labels):
            if a == b and i != j:
                want[a] = max(want.get(a, 0.0), float(D[i, j]))
    expected = max(want, key=lambda k: (want[k], k))
    per_class = "the largest distance within each class"
    if not isinstance(spread, dict):
        msg = f"✗ {per_class}: expected a dict class -> distance, got a {type(spread).__name__}."
    elif {str(k).strip().lower() for k in spread} != set(want):
        msg = f"✗ {per_class}: its keys should be the classes {sorted(want)}."
    else:
        got = {str(k).strip().lower(): v for k, v in spread.items()}
        wrong = [k for k in want if not value(per_class, got[k], want[k], rtol=1e-9, atol=0.0, quiet=True).passed]
        msg = f"✗ {per_class}: not quite: yours differs for {', '.join(map(repr, wrong))}." if wrong else ""
    if msg:
        print(msg)
        return CheckResult("the most spread-out class", False, 1, msg)
    received = answer.strip().lower() if isinstance(answer, str) else answer
    return value("the most spread-out class", received, expected)


def rips_not_nerve(count: int, points: ArrayLike, rho: float) -> CheckResult:
    """Lesson 19: how many triangles of the Vietoris–Rips complex of ``points`` at radius
    ``rho`` are not in the Čech complex, the nerve of the balls of radius ``rho``.

    A triangle is in the Rips complex when its three sides are at most :math:`2\\rho`;
    it is in the nerve when the three balls share a point, that is when the smallest
    ball enclosing its vertices has radius at most :math:`\\rho`.  The check finds that
    ball its own way, not by the triangle's angles: the circumcentre solved as a
    linear system in the triangle's plane, kept when its barycentric coordinates are
    all non-negative, else (and for a triangle with collinear or repeated vertices,
    which has none) the midpoint of the longest side.

    Parameters
    ----------
    count : int
        The student's number of triangles.
    points : array_like, shape (n, d)
        The centres, in any dimension d (the lesson's are in 3).
    rho : float
        The radius, > 0.

    Returns
    -------
    CheckResult

    Raises
    ------
    ValueError
        If a side or an enclosing radius lies within 1e-9 of its threshold: round-off
        would then decide the count.

    See Also
    --------
    shapelab.filtration.alpha_filtration : the α-filtration, the nerve of the clipped balls.

    References
    ----------
    .. [1] Lecture notes, §23.1 (the dual complex as a nerve).
    .. [2] H. Edelsbrunner and J. Harer, *Computational Topology*, AMS, 2010, §III.2
       (Čech and Vietoris–Rips complexes).

    Examples
    --------
    >>> import numpy as np
    >>> triangle = [[0.0, 0.0], [2.0, 0.0], [1.0, np.sqrt(3.0)]]
    >>> # sides 2 <= 2 rho, but the enclosing radius 2/sqrt(3) > rho = 1.1
    >>> ok = rips_not_nerve(1, triangle, 1.1)
    ✓ the Rips triangles outside the nerve: correct.
    >>> bad = rips_not_nerve(0, triangle, 1.1)
    ✗ the Rips triangles outside the nerve: not quite: yours is too small.
    """
    from .._toolkit.validate import as_finite_scalar, as_points

    X = as_points(points, "points")
    rho = as_finite_scalar(rho, "rho", positive=True)
    D = np.linalg.norm(X[:, None, :] - X[None, :, :], axis=-1)
    off = ~np.eye(len(X), dtype=bool)
    if np.any(np.abs(D[off] - 2 * rho) < 1e-9):
        raise ValueError(f"a distance between two points lies within 1e-9 of 2*rho = {2 * rho!r}")
    i, j = np.nonzero(np.triu(D <= 2 * rho, 1))
    adj = D <= 2 * rho
    tri = [
        (a, b, c)
        for a, b in zip(i.tolist(), j.tolist())
        for c in (np.flatnonzero(adj[a, b + 1 :] & adj[b, b + 1 :]) + b + 1).tolist()
    ]
    outside = 0
    for a, b, c in tri:
        P, Q, S = X[a], X[b], X[c]
        u, v = Q - P, S - P
        G = np.array([[u @ u, u @ v], [u @ v, v @ v]])
        try:
            s, t = np.linalg.solve(G, 0.5 * np.array([u @ u, v @ v]))  # circumcentre P + s u + t v
        except np.linalg.LinAlgError:  # collinear or repeated vertices: no circumcentre
            s = t = -1.0
        if min(s, t, 1.0 - s - t) >= 0.0:
            radius = np.linalg.norm(s * u + t * v)
        else:
            radius = max(D[a, b], D[a, c], D[b, c]) / 2.0
        if abs(radius - rho) < 1e-9:
            raise ValueError(f"a triangle's smallest enclosing ball has radius within 1e-9 of rho = {rho!r}")
        outside += radius > rho
    if isinstance(count, (bool, np.bool_)) or not isinstance(count, (int, np.integer)):
        msg = f"✗ the Rips triangles outside the nerve: expected a whole number, got a {type(count).__name__}."
        print(msg)
        return CheckResult("the Rips triangles outside the nerve", False, 1, msg)
    return value("the Rips triangles outside the nerve", int(count), outside)


def first_site_rank(
    answer: int,
    structure: PDBStructure | Balls,
    ligand: ArrayLike,
    *,
    method: str = "growth",
    probe: float = 1.4,
    dca: float = 4.0,
) -> CheckResult:
    """Lesson 20: the rank of the first cavity of the default ranked report whose centre
    lies within ``dca`` Å of a ligand atom (the DCA criterion), or 0 when none does.

    The reference is ``shapelab.report(structure, probe, method=method)`` in its default
    order (``rank="score"``); a cavity's centre is the centroid of its lining atoms, and
    ranks count from 1 (the row's ``id``).

    Parameters
    ----------
    answer : int
        The student's rank.
    structure : shapelab.io.PDBStructure or Balls
        The protein, read without its ligand.
    ligand : array_like, shape (m, 3)
        The ligand's heavy-atom centres.
    method : {"growth", "flow"}, default "growth"
        The pocket definition of the report.
    probe : float, default 1.4
        The report's probe radius (Å).
    dca : float, default 4.0
        The distance (Å) from the centre to the nearest ligand atom that counts as a hit.

    Returns
    -------
    CheckResult
        Passed when the rank is right; a wrong rank is called too large or too small,
        never given.

    See Also
    --------
    shapelab.report : the ranked table of cavities.
    shapelab.ranking.rank_score : the default order.

    References
    ----------
    .. [1] Lecture notes, §23.1 (a pocket "often defines a docking site").
    .. [2] R. Krivák and D. Hoksza, "P2Rank: machine learning based tool for rapid and
       accurate prediction of ligand binding sites from protein structure",
       *J. Cheminform.* 10:39, 2018 (the DCA criterion).

    Examples
    --------
    >>> import shapelab as sl
    >>> bad = first_site_rank(1.5, sl.datasets.fullerene_c60(), [[0.0, 0.0, 0.0]])
    ✗ the rank of the first cavity at the ligand: not quite: expected a whole number (a rank), got a float.
    """
    from ..report import report

    rows = report(structure, probe, method=method).rows
    atoms = structure.balls.centers if hasattr(structure, "balls") else structure.centers
    L = np.asarray(ligand, dtype=float).reshape(-1, 3)
    expected = 0
    for k, row in enumerate(rows, start=1):
        centre = atoms[np.asarray(row.lining_atoms, dtype=int)].mean(axis=0)
        if np.min(np.linalg.norm(L - centre, axis=1)) <= dca:
            expected = k
            break
    if isinstance(answer, (bool, np.bool_)) or not isinstance(answer, (int, np.integer)):
        return _fail(
            "the rank of the first cavity at the ligand",
            f"expected a whole number (a rank), got a {type(answer).__name__}",
        )
    return value("the rank of the first cavity at the ligand (ranks count from 1)", int(answer), expected)
