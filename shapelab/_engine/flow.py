"""The discrete flow's machinery (not required reading).

* its exact decisions: whether a top simplex flows across a facet is the sign of a
  polynomial in the input, evaluated in floating point with a bound on its rounding
  error and, where the bound cannot decide, recomputed exactly on integers
  (:func:`beyond`); with the neighbours across the facets (:func:`neighbours`), kept
  on the filtration (:func:`static`);
* the measured quantities of a region that are not its definition: its lining and the
  growth-model pair ``(closes_at, fills_at)`` of the class rooted in it
  (:func:`region_measures`).

The definitions and the proof are in :mod:`shapelab.cavities.flow`.
"""

from __future__ import annotations

import numbers
from fractions import Fraction

import numpy as np

from .._toolkit.derived import derived
from .._toolkit.tolerances import FILTER_UNDERFLOW
from .._toolkit.validate import readonly
from .mouths import merge_tree_of
from .persistence import is_roundoff

__all__ = [
    "exact_values",
    "gram",
    "sign",
    "flow_value",
    "beyond",
    "scaled_integers",
    "neighbours",
    "static",
    "empty_flow",
    "region_measures",
]

U_ = 2.0**-53
C_ = 64.0  # generous against the ~24 roundings of the 3D expression (see the module docstring)
TINY_ = FILTER_UNDERFLOW  # below this a float bound may be spoilt by underflow: decide exactly


def exact_values(x, name, ndim):
    """``x`` (a number, list or array of depth ``ndim``) as nested lists of Fractions,
    finite, each float taken exactly; a clear error naming ``name`` otherwise."""
    if isinstance(x, (str, bytes)):
        raise TypeError(f"flow_side_exact: {name} must hold numbers, got {type(x).__name__}")
    if ndim == 0 or not hasattr(x, "__len__"):
        if ndim:
            raise ValueError(f"flow_side_exact: {name} must be an array of depth {ndim}, got a scalar {x!r}")
        if isinstance(x, Fraction):
            return x
        if isinstance(x, (bool, np.bool_)) or not isinstance(x, (numbers.Integral, numbers.Real)):
            raise TypeError(f"flow_side_exact: {name} must hold real numbers, got {type(x).__name__}")
        v = float(x)
        if not np.isfinite(v):
            raise ValueError(f"flow_side_exact: {name} must be finite, got {v!r}")
        return Fraction(v)
    return [exact_values(e, name, ndim - 1) for e in x]


def gram(Z):
    """The Gram determinant of the facet's edge vectors (exact for Fractions)."""
    U = [[Z[i][c] - Z[0][c] for c in range(len(Z[0]))] for i in range(1, len(Z))]
    if len(U) == 1:
        return dot_(U[0], U[0])
    return dot_(U[0], U[0]) * dot_(U[1], U[1]) - dot_(U[0], U[1]) ** 2


def sign(x) -> int:
    return (x > 0) - (x < 0)


def dot_(a, b):
    s = a[0] * b[0]
    for i in range(1, len(a)):
        s = s + a[i] * b[i]
    return s


def flow_value(Z, W, A, wa, absmode=False):
    """``D (pi_a(y_nu) - rho_nu)``, or with ``absmode`` its error-bound companion (the
    same expansion on absolute values, every sign ``+``), for scalars or numpy arrays."""
    p, wp = Z[0], W[0]
    d = len(p)
    U = [[Z[i][c] - p[c] for c in range(d)] for i in range(1, len(Z))]
    v = [A[c] - p[c] for c in range(d)]
    if absmode:
        U = [[abs(e) for e in u] for u in U]
        v = [abs(e) for e in v]
    vv = dot_(v, v)
    if len(U) == 1:
        (u,) = U
        G11 = dot_(u, u)
        c1 = dot_(u, v)
        if absmode:
            return G11 * (vv + wa + wp) + (G11 + wp + W[1]) * c1
        return G11 * (vv - wa + wp) - (G11 + wp - W[1]) * c1
    u1, u2 = U
    G11, G12, G22 = dot_(u1, u1), dot_(u1, u2), dot_(u2, u2)
    c1, c2 = dot_(u1, v), dot_(u2, v)
    if absmode:
        D = G11 * G22 + G12 * G12
        return (
            D * (vv + wa + wp) + (G11 + wp + W[1]) * (G22 * c1 + G12 * c2) + (G22 + wp + W[2]) * (G11 * c2 + G12 * c1)
        )
    D = G11 * G22 - G12 * G12
    b1, b2 = G11 + wp - W[1], G22 + wp - W[2]
    return D * (vv - wa + wp) - (b1 * (G22 * c1 - G12 * c2) + b2 * (G11 * c2 - G12 * c1))


def beyond(F) -> np.ndarray:
    """``(n, d+1)`` int8: the sign for top simplex ``i`` and its facet opposite vertex
    ``j`` (``-1``: the orthocentre is strictly beyond that facet)."""
    balls = F.balls
    d = balls.dim
    S = np.asarray(F.simplices(d), dtype=np.int64)
    n = S.shape[0]
    out = np.zeros((n, d + 1), dtype=np.int8)
    if n == 0:
        return out
    z = np.asarray(balls.centers, dtype=np.float64)
    # the filtration's own weights (r*r rounded once, then taken as exact), so that a
    # facet is crossed exactly when the filtration finds it attached by this coface
    w = np.asarray(balls.weights, dtype=np.float64)
    for j in range(d + 1):
        fcols = [c for c in range(d + 1) if c != j]
        Zc = [[z[S[:, c], k] for k in range(d)] for c in fcols]
        Wc = [w[S[:, c]] for c in fcols]
        A = [z[S[:, j], k] for k in range(d)]
        wa = w[S[:, j]]
        with np.errstate(all="ignore"):
            val = flow_value(Zc, Wc, A, wa)
            bound = C_ * U_ * flow_value(Zc, Wc, A, wa, absmode=True)
        ok = (np.abs(val) > bound) & (bound > TINY_) & np.isfinite(val) & np.isfinite(bound)
        out[:, j] = np.where(ok, np.sign(np.where(ok, val, 0.0)), 0)
        undecided = np.flatnonzero(~ok)
        if undecided.size == 0:
            continue
        Zi, Wi = scaled_integers(z, w, np.unique(S[undecided]))
        for i in undecided.tolist():
            row = S[i].tolist()
            Zf = [Zi[row[c]] for c in fcols]
            Wf = [Wi[row[c]] for c in fcols]
            out[i, j] = sign(flow_value(Zf, Wf, Zi[row[j]], Wi[row[j]]))
    return out


def scaled_integers(z, w, balls):
    """The centres and weights of ``balls`` as Python integers ``z * 2**k`` and
    ``w * 2**(2k)``, one ``k`` making every one of them an integer (floats are dyadic
    rationals).  ``_flow_value`` is homogeneous (degree 4 in 2D, 6 in 3D, a weight
    counting 2), so on these integers it is the exact value times a positive power of
    two: the same sign as with :class:`fractions.Fraction`, at a fraction of the cost
    (a grid-like input leaves a third of its decisions to the exact road)."""
    zr = {b: [float(c).as_integer_ratio() for c in z[b]] for b in balls.tolist()}
    wr = {b: float(w[b]).as_integer_ratio() for b in balls.tolist()}
    k = max(
        [0]
        + [den.bit_length() - 1 for row in zr.values() for _, den in row]
        + [(den.bit_length()) // 2 for _, den in wr.values()]
    )
    Zi = {b: [num << (k - den.bit_length() + 1) for num, den in row] for b, row in zr.items()}
    Wi = {b: num << (2 * k - den.bit_length() + 1) for b, (num, den) in wr.items()}
    return Zi, Wi


# ======================================================== bookkeeping of the flow
def neighbours(F) -> np.ndarray:
    """``(n, d+1)``: the top simplex across each facet (``-1``: the outside)."""
    d = F.balls.dim
    B = np.asarray(F.boundary(d), dtype=np.int64)
    n = B.shape[0]
    nf = len(F.values(d - 1))
    flat = B.ravel()
    owner = np.repeat(np.arange(n), d + 1)
    order = np.argsort(flat, kind="stable")
    fs, ow = flat[order], owner[order]
    first = np.full(nf, -1, dtype=np.int64)
    second = np.full(nf, -1, dtype=np.int64)
    start = np.r_[True, fs[1:] != fs[:-1]]
    first[fs[start]] = ow[start]
    dup = ~start
    second[fs[dup]] = ow[dup]
    other = np.where(first[flat] == owner, second[flat], first[flat])
    return other.reshape(n, d + 1)


def static(F):
    """``(beyond(F), neighbours(F))``, computed once and kept on ``F`` (they do not
    depend on τ)."""
    st = derived(F, "flow.static", lambda F: {"beyond": beyond(F), "neighbour": neighbours(F)})
    return st["beyond"], st["neighbour"]


def empty_flow(d: int) -> tuple:
    """The arrays of a :class:`shapelab.DiscreteFlow` with no top simplex: ``empty``,
    ``neighbour``, ``flows``, ``sink``, ``to_infinity``, ``region``."""
    e = np.zeros(0, dtype=bool)
    z = np.zeros((0, d + 1), dtype=np.int64)
    return (
        readonly(e),
        readonly(z),
        readonly(z.astype(bool)),
        readonly(e),
        readonly(e),
        readonly(np.zeros(0, dtype=np.int64)),
    )


def region_measures(F):
    """A function ``(cell_ids, cells, tau) -> (lining, closes_at, fills_at)`` for the
    regions of one flow: the region's lining atoms (the vertices of its cells that
    exist at ``tau``, as :func:`shapelab.cavities.complement.lining_of`) and the pair
    ``(born, dies)`` of the most persistent merge-tree class rooted at one of its cells
    (ties: the earlier birth, then the lower row; no class of positive length beyond
    round-off: the time its last cell fills, twice; :class:`shapelab.FlowPocket`)."""
    d = F.balls.dim
    cv = np.asarray(F.values(d), dtype=np.float64)
    kill = merge_tree_of(F).kill_value
    vval = np.full(len(F.balls), np.inf)
    vval[np.asarray(F.simplices(0), dtype=np.int64).ravel()] = F.values(0)

    def measure(cid, cells, tau):
        verts = np.unique(cells)
        lining = readonly(verts[vval[verts] <= tau], np.int64)
        pers = cv[cid] - kill[cid]
        ok = (pers > 0) & ~is_roundoff(F, kill[cid], cv[cid])
        if not ok.any():
            last = float(cv[cid].max())
            return lining, last, last
        c = cid[ok]
        o = np.lexsort((c, kill[c], -(cv[c] - kill[c])))
        r = int(c[o[0]])
        return lining, float(kill[r]), float(cv[r])

    return measure
