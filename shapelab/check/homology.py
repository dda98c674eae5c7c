"""Self-checks for lesson 02 (homology over Z/2): ranks mod 2, Betti numbers of a
given complex, and which chains are cycles and which are boundaries.

The references are :mod:`shapelab.homology`'s functions, computed here so that the
lesson shows neither the answer nor the code that finds it.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from typing import Any

import numpy as np

from ._runner import CheckResult, run_check, value

__all__ = ["rank_mod2", "complex_betti", "cycles_and_boundaries"]


def _rank_cases():
    """0/1 matrices: edge cases first (no rows, no columns, zero, one entry, rank
    deficient over Z/2 but not over the rationals), then boundary matrices of small
    complexes and seeded random matrices."""
    from itertools import combinations

    from .. import homology

    yield (np.zeros((0, 0), dtype=np.uint8),)
    yield (np.zeros((0, 3), dtype=np.uint8),)
    yield (np.zeros((4, 0), dtype=np.uint8),)
    yield (np.zeros((3, 3), dtype=np.uint8),)
    yield (np.array([[0, 0], [0, 1]], dtype=np.uint8),)
    yield (np.array([[1, 1, 0], [1, 0, 1], [0, 1, 1]], dtype=np.uint8),)  # rank 2 mod 2, 3 over Q
    yield (np.array([[1, 1], [1, 1], [1, 1]], dtype=np.uint8),)
    yield (np.eye(5, dtype=np.uint8),)
    yield (np.array([[0, 1, 1], [0, 1, 1], [0, 0, 1]], dtype=np.uint8),)  # the pivot is not on the diagonal
    sphere = [s for k in (1, 2, 3) for s in combinations(range(4), k)]
    torus = homology.closure(
        [tri for i in range(7) for tri in ((i, (i + 1) % 7, (i + 3) % 7), (i, (i + 2) % 7, (i + 3) % 7))]
    )
    for K in (sphere, torus):
        for k in (1, 2):
            yield (homology.boundary_matrix(K, k),)
    rng = np.random.default_rng(2026)
    for _ in range(40):
        m, n = (int(x) for x in rng.integers(1, 13, size=2))
        p = float(rng.choice([0.15, 0.5, 0.85]))
        yield ((rng.random((m, n)) < p).astype(np.uint8),)
    # products of two thin matrices: low rank, many dependent rows
    for _ in range(10):
        r = int(rng.integers(1, 5))
        A = rng.integers(0, 2, size=(int(rng.integers(r, 12)), r))
        B = rng.integers(0, 2, size=(r, int(rng.integers(r, 12))))
        yield (((A @ B) % 2).astype(np.uint8),)


def rank_mod2(student_fn: Callable[..., Any], *, quiet: bool = False) -> CheckResult:
    """Check ``student_fn(M) -> int``, the rank of a 0/1 matrix over Z/2.

    Cases: empty and zero matrices, a matrix whose rank differs over Z/2 and over the
    rationals, boundary matrices of a sphere and a torus, then seeded random
    matrices (of full and of low rank), against :func:`shapelab.homology.rank_mod2`.

    See Also
    --------
    shapelab.homology.rank_mod2 : the reference.

    Examples
    --------
    >>> import shapelab as sl
    >>> rank_mod2(sl.rank_mod2).passed
    ✓ rank over Z/2: correct on all 63 cases.
    True
    >>> # the rank over the rationals is refused
    >>> import numpy as np
    >>> rank_mod2(lambda M: int(np.linalg.matrix_rank(np.asarray(M, dtype=float))) if np.size(M) else 0, quiet=True).passed
    False
    """
    from .. import homology

    def compare(expected, received):
        if isinstance(received, (bool, np.bool_)) or not isinstance(received, (int, np.integer, float, np.floating)):
            return False
        return float(received) == float(expected)

    return run_check(
        "rank over Z/2",
        student_fn,
        list(_rank_cases()),
        homology.rank_mod2,
        compare=compare,
        describe=lambda case: "M =\n  " + np.array2string(np.asarray(case[0]), separator=" ").replace("\n", "\n  "),
        quiet=quiet,
    )


def complex_betti(betti: Sequence[int], simplices: Iterable[Sequence[int]]) -> CheckResult:
    """Lesson 02: the Betti numbers :math:`(\\beta_0, \\dots, \\beta_d)` over Z/2 of the
    complex ``simplices``, compared entry by entry without showing them.

    See Also
    --------
    shapelab.homology.betti_numbers : the reference.

    Examples
    --------
    >>> circle = [[0], [1], [2], [0, 1], [1, 2], [0, 2]]
    >>> ok = complex_betti([1, 1], circle)
    ✓ Betti numbers (β0, β1): correct.
    >>> bad = complex_betti([1, 0], circle)
    ✗ Betti numbers (β0, β1): not quite: 1 of 2 entries differ, the first at index 1.
    """
    from .. import homology

    expected = homology.betti_numbers(simplices)
    name = "Betti numbers (" + ", ".join(f"β{k}" for k in range(len(expected))) + ")"
    if betti is None or isinstance(betti, (str, bytes)) or not hasattr(betti, "__len__"):
        return value(name, betti, expected)
    if (isinstance(betti, np.ndarray) and betti.dtype == np.bool_) or any(
        isinstance(x, (bool, np.bool_)) for x in betti
    ):
        msg = f"✗ {name}: not quite: expected numbers (the dimensions of the homology groups), got truth values."
        print(msg)
        return CheckResult(name, False, 1, msg)
    return value(name, list(betti), list(expected))


def cycles_and_boundaries(
    cycle: Sequence[bool],
    boundary: Sequence[bool],
    chains: Sequence[Iterable[Sequence[int]]],
    simplices: Iterable[Sequence[int]],
) -> CheckResult:
    """Lesson 02: for each chain of ``chains``, is it a cycle (``cycle[i]``) and is it
    a boundary in ``simplices`` (``boundary[i]``; the lesson's list ``bounds``)?  Both
    lists are compared entry by entry. A message says how many entries of each list are
    wrong, not which (with two possible answers, naming the chain would give its answer
    away), with a hint on how to decide; a chain claimed to be a boundary but not a cycle
    gets the hint that every boundary is a cycle.

    See Also
    --------
    shapelab.homology.is_cycle : the reference for ``cycle``.
    shapelab.homology.is_boundary : the reference for ``boundary``.

    Examples
    --------
    >>> disk = [[0], [1], [2], [0, 1], [1, 2], [0, 2], [0, 1, 2]]
    >>> chains = [[[0, 1], [1, 2], [0, 2]], [[0, 1]]]
    >>> ok = cycles_and_boundaries([True, False], [True, False], chains, disk)
    ✓ cycles and boundaries: correct.
    >>> bad = cycles_and_boundaries([True, False], [False, False], chains, disk)
    ✗ cycles and boundaries: not quite: `bounds`: 1 of 2 entries is wrong (a chain c is a boundary when ∂x = c has a solution x one dimension up: c as an extra column leaves the rank of that boundary matrix unchanged).
    """
    from .. import homology

    name = "cycles and boundaries"
    want_c = [homology.is_cycle(c, simplices) for c in chains]
    want_b = [homology.is_boundary(c, simplices) for c in chains]
    problems = []
    hints = {
        "cycle": "a chain is a cycle when its boundary is empty (for edges: each vertex lies on an even number of them)",
        "bounds": "a chain c is a boundary when ∂x = c has a solution x one dimension up: c as an extra column leaves "
        "the rank of that boundary matrix unchanged",
    }
    for label, got, want in (("cycle", cycle, want_c), ("bounds", boundary, want_b)):
        if not isinstance(got, (list, tuple, np.ndarray)) or np.ndim(got) != 1 or len(got) != len(want):
            problems.append(f"`{label}` should be a list of {len(want)} truth values, one per chain")
            continue
        if not all(isinstance(x, (bool, np.bool_)) for x in got):
            problems.append(f"`{label}` should hold True or False, one per chain")
            continue
        wrong = sum(bool(g) != w for g, w in zip(got, want))
        if wrong:
            problems.append(
                f"`{label}`: {wrong} of {len(want)} entries {'is' if wrong == 1 else 'are'} wrong ({hints[label]})"
            )
    if all(isinstance(x, (list, tuple, np.ndarray)) and np.ndim(x) == 1 for x in (cycle, boundary)):
        if len(cycle) == len(boundary) == len(chains) and any(bool(b) and not bool(c) for c, b in zip(cycle, boundary)):
            problems.append("you call a chain a boundary but not a cycle: every boundary is a cycle (∂∂ = 0)")
    passed = not problems
    msg = f"✓ {name}: correct." if passed else f"✗ {name}: not quite: " + "; ".join(problems) + "."
    print(msg)
    return CheckResult(name, passed, len(chains), msg)
