"""Test helpers: protein-like inputs and a GUDHI oracle for the reduction alone.

Nothing here is part of the library.  :func:`protein_like` builds a seeded, compact
packing of heavy-atom chains at protein density (no download); :func:`gudhi_diagrams`
loads a GUDHI simplex tree with *our* simplices and values and computes persistence
over Z/2, so that comparing its diagrams with :func:`shapelab.topology.persistence`
tests the reduction independently of the geometry.
"""

from __future__ import annotations

from fractions import Fraction  # noqa: F401  (the oracles' number type)

import numpy as np

import shapelab as sl
from shapelab import topology as T

#: Bondi van der Waals radii (Å) and a protein's heavy-atom composition.
ELEMENTS = (("C", 0.62, 1.70), ("N", 0.17, 1.55), ("O", 0.19, 1.52), ("S", 0.02, 1.80))


def protein_like(
    n: int = 5000,
    *,
    seed: int = 0,
    probe: float = 0.0,
    bond: float = 1.5,
    angle_deg: float = 111.0,
    contact: float = 2.9,
    density: float = 0.05,
    max_tries: int = 40,
) -> sl.Balls:
    """A seeded compact packing of heavy-atom chains, like a globular protein (Å).

    Chains grow inside a sphere whose volume gives ``density`` atoms per Å^3 (globular
    proteins: about 0.05 heavy atoms per Å^3).  Each step puts the next atom at
    distance ``bond`` from the last one, at the bond angle ``angle_deg`` to the previous
    bond and a uniformly random dihedral, and rejects it when it leaves the sphere or
    comes closer than ``contact`` to any atom other than its two predecessors.  After
    ``max_tries`` rejections the chain ends and a new one starts at a random free point.
    The bond geometry is jittered by a few hundredths of an Å and a degree, so that no
    four centres are exactly co-spherical.  Radii are Bondi radii of C/N/O/S drawn with
    a protein's composition, plus ``probe``.

    Parameters
    ----------
    n : int
        Number of atoms.
    seed : int
    probe : float
        Added to every radius (1.4 Å: the solvent-accessible surface).
    bond, angle_deg, contact, density, max_tries
        The geometry above.

    Returns
    -------
    Balls
    """
    rng = np.random.default_rng(seed)
    R = (3.0 * n / (4.0 * np.pi * density)) ** (1.0 / 3.0)
    cell = contact
    grid: dict = {}
    X = np.empty((n, 3))
    cos_a = np.cos(np.radians(angle_deg))

    def free(p, skip):
        if p @ p > R * R:
            return False
        c = np.floor(p / cell).astype(int)
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for dz in (-1, 0, 1):
                    for j in grid.get((c[0] + dx, c[1] + dy, c[2] + dz), ()):
                        if j not in skip and np.sum((X[j] - p) ** 2) < contact * contact:
                            return False
        return True

    def add(i, p):
        X[i] = p
        c = tuple(np.floor(p / cell).astype(int))
        grid.setdefault(c, []).append(i)

    i = 0
    chain = []  # indices of the current chain
    while i < n:
        if len(chain) == 0:
            for _ in range(10000):
                p = rng.uniform(-R, R, 3)
                if free(p, ()):
                    break
            add(i, p)
            chain = [i]
            i += 1
            continue
        last = X[chain[-1]]
        placed = False
        for _ in range(max_tries):
            b = bond + 0.02 * rng.standard_normal()
            if len(chain) == 1:
                d = rng.standard_normal(3)
                d /= np.linalg.norm(d)
            else:
                u = last - X[chain[-2]]
                u /= np.linalg.norm(u)
                # unit vector at angle (pi - angle) to u, random dihedral
                ca = -cos_a + 0.01 * rng.standard_normal()
                sa = np.sqrt(max(0.0, 1.0 - ca * ca))
                w = rng.standard_normal(3)
                w -= (w @ u) * u
                w /= np.linalg.norm(w)
                d = ca * u + sa * w
            p = last + b * d
            if free(p, set(chain[-2:])):
                add(i, p)
                chain.append(i)
                i += 1
                placed = True
                break
        if not placed:
            chain = []
    radii = np.array([e[2] for e in ELEMENTS])
    prob = np.array([e[1] for e in ELEMENTS])
    kind = rng.choice(len(ELEMENTS), size=n, p=prob / prob.sum())
    return sl.Balls(X, radii[kind] + probe)


def random_balls(n: int, dim: int, *, seed: int = 0, rmax: float = None) -> sl.Balls:
    """``n`` balls with centres uniform in the unit cube and radii uniform in
    ``[0, rmax]`` (default: about the mean spacing), seeded."""
    rng = np.random.default_rng(seed)
    if rmax is None:
        rmax = 0.5 * n ** (-1.0 / dim)
    return sl.Balls(rng.random((n, dim)), rmax * rng.random(n))


def grid_balls(k: int, dim: int, radius: float = 0.3) -> sl.Balls:
    """The integer grid ``{0..k-1}^dim`` with equal radii: many tied values."""
    g = np.stack(np.meshgrid(*([np.arange(k)] * dim), indexing="ij"), -1).reshape(-1, dim)
    return sl.Balls(g.astype(np.float64), radius)


def gudhi_tree(F):
    """A GUDHI simplex tree holding exactly F's simplices with F's values."""
    import gudhi

    st = gudhi.SimplexTree()
    for k in range(int(F.dimension) + 1):
        s = np.asarray(F.simplices(k), dtype=np.int64)
        if s.shape[0]:
            st.insert_batch(np.ascontiguousarray(s.T), np.asarray(F.values(k), dtype=np.float64))
    return st


def gudhi_diagrams(F, dims=None, *, field: int = 2) -> dict:
    """GUDHI's persistence of F's own simplices and values, with coefficients in
    Z/``field`` (Z/2 by default, the field of ``persistence()``'s default; GUDHI's own
    default is Z/11, in which H1 pairs of real proteins can differ).

    Returns ``{k: (p, 2) array}`` with GUDHI's pairs, the round-off pairs (in the sense
    of :func:`shapelab.topology.is_roundoff`) dropped as ``persistence()`` drops them.
    """
    st = gudhi_tree(F)
    st.compute_persistence(homology_coeff_field=field, min_persistence=0, persistence_dim_max=True)
    d = F.balls.dim if dims is None else dims
    out = {}
    for k in range(d + 1):
        P = np.asarray(st.persistence_intervals_in_dimension(k), dtype=np.float64).reshape(-1, 2)
        P = P[P[:, 1] > P[:, 0]]
        out[k] = P[~T.is_roundoff(F, P[:, 0], P[:, 1])]
    return out


def _multiset_difference(A, B):
    """Rows of A not matched by an identical row of B, and vice versa."""
    A = A[np.lexsort((A[:, 1], A[:, 0]))]
    B = B[np.lexsort((B[:, 1], B[:, 0]))]
    if A.shape == B.shape and np.array_equal(A, B):
        return A[:0], B[:0]

    # rank of each row inside its run of equal rows, so that duplicates match one to one
    def keyed(P):
        if P.shape[0] == 0:
            return []
        same = np.r_[False, np.all(P[1:] == P[:-1], axis=1)]
        run = np.arange(P.shape[0]) - np.maximum.accumulate(np.where(~same, np.arange(P.shape[0]), 0))
        return list(zip(P[:, 0].tolist(), P[:, 1].tolist(), run.tolist()))

    ka, kb = keyed(A), keyed(B)
    sb, sa = set(kb), set(ka)
    ra = np.array([k[:2] for k in ka if k not in sb], dtype=np.float64).reshape(-1, 2)
    rb = np.array([k[:2] for k in kb if k not in sa], dtype=np.float64).reshape(-1, 2)
    return ra, rb


def bottleneck(A, B, *, full_below: int = 0) -> float:
    """Bottleneck distance between two diagrams (rows birth, death; inf allowed).

    Identical pairs are cancelled first and the distance is computed between what
    is left (an upper bound on the distance between the whole diagrams, and 0 if and
    only if they are equal as multisets), which keeps it fast on diagrams of 10^4
    pairs.  With ``full_below = m``, diagrams of at most ``m`` pairs are compared whole.
    """
    import gudhi

    A = np.asarray(A, dtype=np.float64).reshape(-1, 2)
    B = np.asarray(B, dtype=np.float64).reshape(-1, 2)
    if max(A.shape[0], B.shape[0]) > full_below:
        A, B = _multiset_difference(A, B)
    fa, fb = np.isinf(A[:, 1]), np.isinf(B[:, 1])
    if fa.sum() != fb.sum():
        return np.inf
    d = 0.0
    if fa.any():
        d = float(np.max(np.abs(np.sort(A[fa, 0]) - np.sort(B[fb, 0]))))
    return max(d, float(gudhi.bottleneck_distance(A[~fa], B[~fb], 0.0)))


def compare(F) -> dict:
    """``{k: bottleneck distance}`` between ``F.persistence()`` and the GUDHI oracle."""
    ours = F.persistence()
    theirs = gudhi_diagrams(F)
    return {k: bottleneck(ours.get(k, np.empty((0, 2))), theirs[k]) for k in theirs}


# ----------------------------------------------------------------- exact orthospheres
def exact_solve(G, b):
    """Exact Gaussian elimination of the square system ``G x = b`` (Fractions)."""
    n = len(b)
    M = [list(G[i]) + [b[i]] for i in range(n)]
    for c in range(n):
        p = next(r for r in range(c, n) if M[r][c] != 0)
        M[c], M[p] = M[p], M[c]
        for r in range(n):
            if r != c and M[r][c] != 0:
                f = M[r][c] / M[c][c]
                M[r] = [a - f * q for a, q in zip(M[r], M[c])]
    return [M[i][n] / M[i][i] for i in range(n)]


def exact_orthosphere(Z, W, s):
    """Centre and power of the smallest orthogonal sphere of the simplex ``s`` (rows of
    ``Z``, ``W``: Fractions), exactly (Notes §23.1: ``u`` in the span of the edges)."""
    z0, w0 = Z[s[0]], W[s[0]]
    A = [[a - b for a, b in zip(Z[i], z0)] for i in s[1:]]
    if not A:
        return list(z0), -w0
    G = [[sum(p * q for p, q in zip(a, b)) for b in A] for a in A]
    beta = [(sum(p * p for p in a) - W[i] + w0) / 2 for a, i in zip(A, s[1:])]
    lam = exact_solve(G, beta)
    u = [sum(lam[t] * A[t][k] for t in range(len(A))) for k in range(len(z0))]
    return [p + q for p, q in zip(z0, u)], sum(q * q for q in u) - w0
