"""Exact geometric predicates for the regular triangulation (Notes §23.1).

Which simplex belongs to the regular triangulation DT, which ball is hidden, on which
side of a facet a point lies: these are *signs of determinants*, and the lifting map
of §23.1 turns all of them into two predicates on the weighted centres
:math:`(z_i, w_i = r_i^2)`:

* ``orient(p_0, ..., p_k)`` -- the sign of :math:`\\det[p_1 - p_0, \\dots, p_k - p_0]`,
  positive when the simplex is positively oriented;
* ``power(p_0, ..., p_k, q)`` -- the sign of the :math:`(k+2) \\times (k+2)`
  determinant with rows :math:`(1, p_j, \\lVert p_j\\rVert^2 - w_j)`.  Subtracting
  the first row gives

  .. math:: D = \\operatorname{orient}(p_0..p_k) \\cdot
            \\bigl(\\hat h_q - \\ell(q)\\bigr),

  with :math:`\\ell` the affine function whose graph passes through the lifted
  :math:`p_j`: for a positively oriented simplex, :math:`D < 0` iff the lifted
  :math:`q` lies *below* the lifted hyperplane of the simplex, i.e. iff
  :math:`\\pi_q(c) < \\rho` for the simplex's orthosphere :math:`(c, \\rho)`
  (:math:`q` "in conflict": the facet between them is not locally regular, or
  :math:`q` is not hidden).

Both are evaluated the way Shewchuk's and CGAL's filtered predicates are: in floating
point first, with a bound on the rounding error of the evaluation
(:math:`C\\,u\\,\\operatorname{perm}`, ``perm`` the same expansion with absolute
values, :math:`u = 2^{-53}`); only where :math:`|D|` does not exceed the bound is
the determinant recomputed *exactly*, with Python integers, from the input's own
binary values (every float64 is an integer times a power of two, so all inputs are
integers at one common scale).  The sign is therefore a function of the input alone,
the same on every CPU, BLAS and compiler.  The rows a vectorised call leaves undecided
are evaluated together: numpy int64 determinants at the coarsest common scale where a
bound on the magnitudes shows that they cannot overflow (grids and other dyadic
input: small integers), numpy arrays of Python integers elsewhere, and the ties'
Simulation of Simplicity batched as well.

Ties (``D = 0``: five co-spherical centres in 3D, four cocircular in 2D, a ball whose
lifted centre lies exactly on a lifted facet) are broken by *Simulation of
Simplicity* (Edelsbrunner and Mücke 1990) applied to the heights only: each lifted
height :math:`\\lVert z_j\\rVert^2 - w_j` is lowered by :math:`\\varepsilon_j` with
:math:`\\varepsilon_{j} \\gg \\varepsilon_{j'}` when ball :math:`j` comes before
:math:`j'` (the ``priority`` order, the input order).  Then

.. math:: D(\\varepsilon) = D - \\sum_j \\varepsilon_j C_j,

with :math:`C_j` the cofactor of :math:`h_j` (an orientation of the other
:math:`k+1` points), so the sign of a tie is :math:`-\\operatorname{sign} C_{j^*}` for
the first :math:`j^*` in priority whose cofactor is not zero.  Coordinates are never
perturbed, so no zero-volume simplex can appear; and the perturbed weights are those
of a nearby input in general position, so the result is the regular triangulation
of that input: unique, and consistent across all tests.  Of two balls with the same
centre and radius the earlier one wins (its weight is larger by :math:`\\varepsilon`),
as in :func:`shapelab.regular_triangulation`'s treatment of duplicates.

This module only answers signs; :mod:`shapelab._engine.certify` checks a triangulation with
them and :mod:`shapelab._engine.incremental` builds one with them.
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np
import numpy.typing as npt

from .._toolkit.tolerances import FILTER_UNDERFLOW

__all__ = ["WeightedPoints", "affine_basis", "det", "flat_simplices", "permanent", "projection_axes"]

_U = 2.0**-53
_TINY = FILTER_UNDERFLOW  # below this a float bound may be spoilt by underflow: decide exactly
_BATCH_MIN = 8  # undecided rows from which the exact stage runs batched (numpy integers)
_INT_BITS = 61  # int64 exact stage: values and determinants below 2**61 in magnitude


def _expand4(M, plus: bool):
    """4x4 expansion through the six 2x2 minors of the last two rows."""
    a, b, c, d = M
    if plus:
        m01, m02, m03 = c[0] * d[1] + c[1] * d[0], c[0] * d[2] + c[2] * d[0], c[0] * d[3] + c[3] * d[0]
        m12, m13, m23 = c[1] * d[2] + c[2] * d[1], c[1] * d[3] + c[3] * d[1], c[2] * d[3] + c[3] * d[2]
        return (
            a[0] * (b[1] * m23 + b[2] * m13 + b[3] * m12)
            + a[1] * (b[0] * m23 + b[2] * m03 + b[3] * m02)
            + a[2] * (b[0] * m13 + b[1] * m03 + b[3] * m01)
            + a[3] * (b[0] * m12 + b[1] * m02 + b[2] * m01)
        )
    m01, m02, m03 = c[0] * d[1] - c[1] * d[0], c[0] * d[2] - c[2] * d[0], c[0] * d[3] - c[3] * d[0]
    m12, m13, m23 = c[1] * d[2] - c[2] * d[1], c[1] * d[3] - c[3] * d[1], c[2] * d[3] - c[3] * d[2]
    return (
        a[0] * (b[1] * m23 - b[2] * m13 + b[3] * m12)
        - a[1] * (b[0] * m23 - b[2] * m03 + b[3] * m02)
        + a[2] * (b[0] * m13 - b[1] * m03 + b[3] * m01)
        - a[3] * (b[0] * m12 - b[1] * m02 + b[2] * m01)
    )


def det(M):
    """Determinant of a small square matrix (n <= 4) given as a list of rows.

    Entries may be floats, Python integers or numpy arrays of either (object arrays
    of integers are evaluated exactly, elementwise).  The expansion is fixed, so a
    float evaluation has the error bound of :func:`permanent`.

    See Also
    --------
    permanent
        The same expansion without signs.

    References
    ----------
    .. [1] J. R. Shewchuk, "Adaptive precision floating-point arithmetic and fast robust
           geometric predicates", *Discrete Comput. Geom.* 18:305-363, 1997.
           doi:10.1007/PL00009321
    """
    n = len(M)
    if n == 1:
        return M[0][0]
    if n == 2:
        return M[0][0] * M[1][1] - M[0][1] * M[1][0]
    if n == 3:
        a, b, c = M
        return (
            a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0])
        )
    if n == 4:
        return _expand4(M, False)
    raise ValueError(f"det: matrices up to 4x4, got {n}x{n}")


def permanent(M):
    """The expansion of :func:`det` with every sign ``+``: for the absolute values of
    the entries, a bound on every partial sum of the determinant's expansion.

    See Also
    --------
    det
        The signed expansion.
    """
    n = len(M)
    if n == 1:
        return M[0][0]
    if n == 2:
        return M[0][0] * M[1][1] + M[0][1] * M[1][0]
    if n == 3:
        a, b, c = M
        return (
            a[0] * (b[1] * c[2] + b[2] * c[1]) + a[1] * (b[0] * c[2] + b[2] * c[0]) + a[2] * (b[0] * c[1] + b[1] * c[0])
        )
    if n == 4:
        return _expand4(M, True)
    raise ValueError(f"permanent: matrices up to 4x4, got {n}x{n}")


def _rowsum_bound(A):
    """Product of the row sums of a non-negative matrix: an upper bound of its
    :func:`permanent` (every term takes one entry from each row), cheaper to
    evaluate; the vectorised filters use it."""
    out = None
    for row in A:
        s = row[0]
        for e in row[1:]:
            s = s + e
        out = s if out is None else out * s
    return out


# error factors C of |fl(D) - D| <= C u perm, generous against the standard bounds
# (gamma_n for n = entry errors + products + sums of the expansion), k = simplex dim
_C_ORIENT = {1: 4.0, 2: 12.0, 3: 40.0}
_C_POWER = {1: 24.0, 2: 48.0, 3: 128.0}


def _sign(x) -> int:
    return (x > 0) - (x < 0)


def _exponent_ints(values: np.ndarray):
    """Integer mantissas ``M`` (int64) and exponents ``e`` with ``values = M 2**e``."""
    m, e = np.frexp(values)
    M = np.ldexp(m, 53).astype(np.int64)
    return M, e.astype(np.int64) - 53


def _power3(U, W, row):
    """The 4x4 power determinant of one 3D row and its permanent, unrolled (the
    incremental algorithm's inner loop)."""
    a, b, c, d, e = row
    ax, ay, az = U[a]
    wa = W[a]
    bx, by, bz = U[b]
    bx -= ax
    by -= ay
    bz -= az  # noqa: E702
    s = bx * bx + by * by + bz * bz
    bh, bm = s - W[b] + wa, s + W[b] + wa
    cx, cy, cz = U[c]
    cx -= ax
    cy -= ay
    cz -= az  # noqa: E702
    s = cx * cx + cy * cy + cz * cz
    ch, cm = s - W[c] + wa, s + W[c] + wa
    dx, dy, dz = U[d]
    dx -= ax
    dy -= ay
    dz -= az  # noqa: E702
    s = dx * dx + dy * dy + dz * dz
    dh, dm = s - W[d] + wa, s + W[d] + wa
    ex, ey, ez = U[e]
    ex -= ax
    ey -= ay
    ez -= az  # noqa: E702
    s = ex * ex + ey * ey + ez * ez
    eh, em = s - W[e] + wa, s + W[e] + wa
    m01, m02, m03 = dx * ey - dy * ex, dx * ez - dz * ex, dx * eh - dh * ex
    m12, m13, m23 = dy * ez - dz * ey, dy * eh - dh * ey, dz * eh - dh * ez
    D = (
        bx * (cy * m23 - cz * m13 + ch * m12)
        - by * (cx * m23 - cz * m03 + ch * m02)
        + bz * (cx * m13 - cy * m03 + ch * m01)
        - bh * (cx * m12 - cy * m02 + cz * m01)
    )
    bx, by, bz, cx, cy, cz = abs(bx), abs(by), abs(bz), abs(cx), abs(cy), abs(cz)
    dx, dy, dz, ex, ey, ez = abs(dx), abs(dy), abs(dz), abs(ex), abs(ey), abs(ez)
    m01, m02, m03 = dx * ey + dy * ex, dx * ez + dz * ex, dx * em + dm * ex
    m12, m13, m23 = dy * ez + dz * ey, dy * em + dm * ey, dz * em + dm * ez
    P = (
        bx * (cy * m23 + cz * m13 + cm * m12)
        + by * (cx * m23 + cz * m03 + cm * m02)
        + bz * (cx * m13 + cy * m03 + cm * m01)
        + bm * (cx * m12 + cy * m02 + cz * m01)
    )
    return D, P


class WeightedPoints:
    """Weighted points and their exact predicates.

    Parameters
    ----------
    coords : ndarray, shape (n, d)
        The centres, as given (their float64 values are the exact input).
    radii : ndarray, shape (n,)
        The radii; the weight is ``radii**2``, squared exactly.
    axes : sequence of int, optional
        The coordinate axes the triangulation lives in (``k = len(axes)``, default all
        ``d``).  For centres that lie in a line or a plane of 3D the triangulation is
        computed on their projection to the coordinate plane (or axis) most parallel
        to it; the lifted height then uses the full coordinates, relative to point 0:
        :math:`t_j = \\lVert z_j - z_0\\rVert^2 - w_j`, which for centres exactly in
        the flat differs from :math:`\\lVert z_j\\rVert^2 - w_j` by an affine function,
        so the triangulation is the same.
    priority : ndarray of int, shape (n,), optional
        The order of Simulation of Simplicity (default: the row order); smaller
        comes first.

    Attributes
    ----------
    stats : dict
        Counts of rows decided by the floating-point filter and exactly.

    See Also
    --------
    shapelab._engine.certify.certify
        Uses the predicates on these points.

    References
    ----------
    .. [1] J. R. Shewchuk, "Adaptive precision floating-point arithmetic and fast robust
           geometric predicates", *Discrete Comput. Geom.* 18:305-363, 1997.
           doi:10.1007/PL00009321
    .. [2] H. Edelsbrunner and E. P. Mücke, "Simulation of Simplicity: a technique to
           cope with degenerate cases in geometric algorithms", *ACM Trans. Graph.*
           9(1):66-104, 1990. doi:10.1145/77635.77639

    Examples
    --------
    The corners of the unit square and its centre, as points (radius 0):

    >>> import numpy as np
    >>> from shapelab.predicates import WeightedPoints
    >>> P = WeightedPoints(np.array([[0., 0], [1, 0], [1, 1], [0, 1], [0.5, 0.5]]), np.zeros(5))
    >>> P.orient(np.array([[0, 1, 2], [0, 2, 1]])).tolist()  # counter-clockwise, clockwise
    [1, -1]

    The power test of the triangle (0, 1, 2) against the fourth corner is an exact tie
    (four co-circular points), broken by Simulation of Simplicity; the centre lies inside
    the circumcircle, below the lifted plane (negative: in conflict):

    >>> P.power(np.array([[0, 1, 2, 3], [0, 1, 2, 4]])).tolist()
    [1, -1]
    """

    def __init__(
        self,
        coords: npt.ArrayLike,
        radii: npt.ArrayLike,
        axes: Sequence[int] | None = None,
        priority: npt.ArrayLike | None = None,
    ) -> None:
        x = np.ascontiguousarray(coords, dtype=np.float64)
        r = np.ascontiguousarray(radii, dtype=np.float64)
        n, d = x.shape
        self.n, self.d = n, d
        self.axes = tuple(range(d)) if axes is None else tuple(int(a) for a in axes)
        self.k = len(self.axes)
        self.x = x
        self.r = r
        self.w = r * r
        self.u = np.ascontiguousarray(x[:, list(self.axes)]) if self.k != d else x
        self.global_height = self.k != d
        if self.global_height and n:
            y = x - x[0]
            sq = np.einsum("ij,ij->i", y, y)
            self.t = sq - self.w
            self.tmag = sq + self.w
        self._lists = None
        self._uT = None
        self.priority = np.arange(n, dtype=np.int64) if priority is None else np.asarray(priority, dtype=np.int64)
        self.stats = {"orient_filtered": 0, "orient_exact": 0, "power_filtered": 0, "power_exact": 0, "power_ties": 0}
        # exact integers at one common scale 2**E (lazily, per point)
        allv = np.concatenate([x.ravel(), r])
        nz = allv[allv != 0]
        if nz.size:
            _, e = _exponent_ints(nz)
            self._E = int(e.min())
        else:
            self._E = 0
        self._xi = [None] * n
        self._w_int = [None] * n
        self._t_int = [None] * n
        self._ints = None
        self._ints_obj = None

    # ------------------------------------------------------------------ exact ints
    def _to_int(self, v: float) -> int:
        if v == 0.0:
            return 0
        mant, ex = math.frexp(v)
        return int(mant * 2**53) << (ex - 53 - self._E)

    def point_int(self, i: int):
        """Exact coordinates of point ``i`` (tuple of d ints, scale :math:`2^E`)."""
        p = self._xi[i]
        if p is None:
            p = tuple(self._to_int(float(v)) for v in self.x[i])
            self._xi[i] = p
            ri = self._to_int(float(self.r[i]))
            self._w_int[i] = ri * ri
        return p

    def _height_int(self, i: int) -> int:
        """Global lifted height of point ``i`` (k < d only), scale :math:`2^{2E}`."""
        t = self._t_int[i]
        if t is None:
            p, p0 = self.point_int(i), self.point_int(0)
            t = sum((a - b) * (a - b) for a, b in zip(p, p0)) - self._w_int[i]
            self._t_int[i] = t
        return t

    def exact_u(self, i: int):
        """Exact triangulation coordinates of point ``i`` (k ints, scale :math:`2^E`)."""
        p = self.point_int(i)
        return p if self.k == self.d else tuple(p[a] for a in self.axes)

    # ------------------------------------------------------------------ exact rows
    def _orient_exact(self, row) -> int:
        P = [self.exact_u(int(i)) for i in row]
        return _sign(det([[a - b for a, b in zip(p, P[0])] for p in P[1:]]))

    def _power_det_exact(self, row) -> int:
        row = [int(i) for i in row]
        P = [self.exact_u(i) for i in row]
        if self.k == 3 and not self.global_height:
            return _sign(_power3(P, [self._w_int[i] for i in row], range(5))[0])
        if self.global_height:
            T = [self._height_int(i) for i in row]
            M = [[a - b for a, b in zip(p, P[0])] + [t - T[0]] for p, t in zip(P[1:], T[1:])]
        else:
            w0 = self._w_int[row[0]]
            M = []
            for i, p in zip(row[1:], P[1:]):
                v = [a - b for a, b in zip(p, P[0])]
                M.append(v + [sum(c * c for c in v) - self._w_int[i] + w0])
        return _sign(det(M))

    def _power_exact(self, row) -> int:
        """Sign of D(ε) for one row (k+2 point indices), exactly."""
        s = self._power_det_exact(row)
        if s:
            return s
        self.stats["power_ties"] += 1
        k = self.k
        order = sorted(range(len(row)), key=lambda j: self.priority[int(row[j])])
        for j in order:
            rest = [row[a] for a in range(len(row)) if a != j]
            o = self.orient1(rest)  # filtered: the cofactors are usually not zero
            if o:
                cof = o if (j + k + 1) % 2 == 0 else -o
                return -cof
        return 0  # every (k+1)-subset flat: the points span less than k dimensions

    # ------------------------------------------------------------------ vectorised
    _BLOCK = 1 << 15

    def _blocks(self, rows, width: int, one):
        rows = np.asarray(rows, dtype=np.int64).reshape(-1, width)
        m = rows.shape[0]
        out = np.zeros(m, dtype=np.int8)
        # overflow or underflow (inputs near 1e±150) leaves a non-finite or tiny bound:
        # those rows are decided exactly, so the floating-point warnings are noise
        with np.errstate(all="ignore"):
            for a in range(0, m, self._BLOCK):
                out[a : a + self._BLOCK] = one(rows[a : a + self._BLOCK])
        return out

    def _coords_T(self):
        if getattr(self, "_uT", None) is None:
            self._uT = np.ascontiguousarray(self.u.T)
        return self._uT

    def orient(self, rows) -> np.ndarray:
        """Orientation signs (int8) of the simplices ``rows`` (m, k+1)."""
        return self._blocks(rows, self.k + 1, self._orient_block)

    def _orient_block(self, rows):
        k = self.k
        G = self._coords_T()[:, np.ascontiguousarray(rows.T)]  # (k, k+1, m)
        V = [[G[c, i] - G[c, 0] for c in range(k)] for i in range(1, k + 1)]
        D = det(V)
        P = _rowsum_bound([[np.abs(e) for e in r] for r in V])
        return self._decide(rows, D, _C_ORIENT[k] * _U * P, "orient", self._orient_exact)

    def _decide(self, rows, D, bound, kind: str, exact):
        """Signs of ``D`` where it exceeds its error ``bound``; ``exact(row)`` elsewhere."""
        ok = (np.abs(D) > bound) & (bound > _TINY) & np.isfinite(D) & np.isfinite(bound)
        out = np.where(ok, np.sign(np.where(ok, D, 0.0)), 0).astype(np.int8)
        undecided = np.flatnonzero(~ok)
        self.stats[kind + "_filtered"] += int(ok.size - undecided.size)
        self.stats[kind + "_exact"] += int(undecided.size)
        if undecided.size >= _BATCH_MIN:
            out[undecided] = self._exact_batch(rows[undecided], kind)
            return out
        for t in undecided:
            out[t] = exact(rows[t])
        return out

    # ------------------------------------------------------------------ exact, batched
    def _int_arrays(self):
        """The input as integers at one common scale, for the batched exact stage:
        ``(U, W, T)`` (coordinates along the axes, weights, and for ``k < d`` the global
        heights), int64 when every value fits with room, else object arrays of Python
        integers.  The scale is the lowest set bit of all values (``2^F``), so dyadic
        input (grids, halves) gives small integers."""
        if self._ints is None:
            vals = np.concatenate([self.x.ravel(), self.r])
            M, e = _exponent_ints(vals)
            nz = M != 0
            aM = np.abs(M)
            low = np.zeros(M.shape, dtype=np.int64)
            low[nz] = np.log2((aM[nz] & -aM[nz]).astype(np.float64)).astype(np.int64)
            F = int((e + low)[nz].min()) if nz.any() else 0
            bits = int((53 + e - F)[nz].max()) if nz.any() else 0
            shift = np.where(nz, e + low - F, 0)
            core = np.where(nz, M >> low, 0)
            if bits <= _INT_BITS:
                ints = core << shift
            else:
                ints = core.astype(object) << shift.astype(object)
            nd = self.n * self.d
            X, R = ints[:nd].reshape(self.n, self.d), ints[nd:]
            W = R * R  # int64 may wrap: only ring operations follow, bounds come from Xf, Rf
            U = X[:, list(self.axes)]
            T = Uf = Wf = Tm = None
            if self.global_height and self.n:
                Y = X - X[0]
                T = (Y * Y).sum(axis=1) - W
            if ints.dtype != object:  # float magnitudes for the overflow bounds
                Xf, Rf = X.astype(np.float64), R.astype(np.float64)
                Uf, Wf = Xf[:, list(self.axes)], Rf * Rf
                if T is not None:
                    Yf = np.abs(Xf - Xf[0])
                    Tm = (Yf * Yf).sum(axis=1) + Wf  # a bound on |T| (times 1 + 2**-50)
            self._ints = (np.ascontiguousarray(U), W, T, Uf, Wf, Tm, X, R)
        return self._ints

    def _exact_batch(self, rows, kind: str) -> np.ndarray:
        """Exact signs of many rows at once (the rows the filter left undecided):
        integer determinants, int64 where a bound shows no overflow, else Python
        integers; ties of the power test broken by Simulation of Simplicity."""
        if kind == "orient":
            return self._orient_int(rows)
        s = self._power_int(rows)
        tie = np.flatnonzero(s == 0)
        if tie.size:
            self.stats["power_ties"] += int(tie.size)
            s[tie] = self._sos_batch(rows[tie])
        return s

    def _int_det(self, V, A):
        """Signs of det(V) for integer matrices V (rows of column arrays), and the mask
        of rows where int64 may have overflowed (``A``: float bounds of the entries'
        magnitudes; int64 arithmetic wraps modulo 2**64, so below the bound it is exact)."""
        D = det(V)
        if D.dtype == np.int64:
            big = ~(_rowsum_bound(A) < 2.0**_INT_BITS)  # the bound has 2**-45 relative slack
            return np.sign(D).astype(np.int8), big
        return np.array([_sign(v) for v in D.ravel()], dtype=np.int8), np.zeros(D.shape, dtype=bool)

    def _object_ints(self):
        """:meth:`_int_arrays` as Python integers (the int64 ones may have wrapped)."""
        if self._ints_obj is None:
            U, W, T = self._int_arrays()[:3]
            if U.dtype == object:
                self._ints_obj = (U, W, T)
            else:
                Uo = U.astype(object)
                R = self._int_arrays()[7].astype(object)
                Wo = R * R
                To = None
                if T is not None:
                    X = self._int_arrays()[6].astype(object)
                    Y = X - X[0]
                    To = (Y * Y).sum(axis=1) - Wo
                self._ints_obj = (Uo, Wo, To)
        return self._ints_obj

    def _orient_int(self, rows, obj=False) -> np.ndarray:
        k = self.k
        obj = obj or self._int_arrays()[3] is None
        U, Uf = (self._object_ints()[0], None) if obj else (self._int_arrays()[0], self._int_arrays()[3])
        r0 = rows[:, 0]
        V = [[U[rows[:, i], c] - U[r0, c] for c in range(k)] for i in range(1, k + 1)]
        if obj:
            return self._int_det(V, None)[0]
        A = [[np.abs(Uf[rows[:, i], c] - Uf[r0, c]) for c in range(k)] for i in range(1, k + 1)]
        s, big = self._int_det(V, A)
        if big.any():
            s[big] = self._orient_int(rows[big], obj=True)
        return s

    def _power_int(self, rows, obj=False) -> np.ndarray:
        k = self.k
        obj = obj or self._int_arrays()[3] is None
        if obj:
            (U, W, T), Uf = self._object_ints(), None
        else:
            U, W, T, Uf, Wf, Tm = self._int_arrays()[:6]
        r0 = rows[:, 0]
        V, A = [], []
        for i in range(1, k + 2):
            ri = rows[:, i]
            v = [U[ri, c] - U[r0, c] for c in range(k)]
            a = None if obj else [np.abs(Uf[ri, c] - Uf[r0, c]) for c in range(k)]
            if T is not None:
                h = T[ri] - T[r0]
                hm = None if obj else Tm[ri] + Tm[r0]
            else:
                sq = v[0] * v[0]
                for c in range(1, k):
                    sq = sq + v[c] * v[c]
                h = sq - W[ri] + W[r0]
                if not obj:
                    sm = a[0] * a[0]
                    for c in range(1, k):
                        sm = sm + a[c] * a[c]
                    hm = sm + Wf[ri] + Wf[r0]
            V.append(v + [h])
            if not obj:
                A.append(a + [hm])
        if obj:
            return self._int_det(V, None)[0]
        s, big = self._int_det(V, A)
        if big.any():
            s[big] = self._power_int(rows[big], obj=True)
        return s

    def _sos_batch(self, rows) -> np.ndarray:
        """Simulation of Simplicity for tied power rows (see :meth:`_power_exact`):
        ``-cofactor`` of the first point in priority whose cofactor is not zero."""
        k = self.k
        w = k + 2
        pri = self.priority[rows]
        order = np.argsort(pri, axis=1, kind="stable")
        out = np.zeros(rows.shape[0], dtype=np.int8)
        todo = np.arange(rows.shape[0])
        for step in range(w):
            if todo.size == 0:
                break
            j = order[todo, step]
            keep = np.array([[c for c in range(w) if c != jj] for jj in range(w)])[j]
            sub = np.take_along_axis(rows[todo], keep, axis=1)
            o = self.orient(sub).astype(np.int64)
            cof = np.where((j + k + 1) % 2 == 0, o, -o)
            hit = o != 0
            out[todo[hit]] = -cof[hit]
            todo = todo[~hit]
        return out

    def power(self, rows) -> np.ndarray:
        """Signs (int8) of the power determinant D(ε) of the rows (m, k+2):
        ``k+1`` simplex vertices, then the query point (see the module docstring)."""
        return self._blocks(rows, self.k + 2, self._power_block)

    def _power_block(self, rows):
        k = self.k
        rT = np.ascontiguousarray(rows.T)
        G = self._coords_T()[:, rT]  # (k, k+2, m)
        if self.global_height:
            T = self.t[rT]
            TM = self.tmag[rT]
        else:
            W = self.w[rT]
        V, A = [], []
        for i in range(1, k + 2):
            v = [G[c, i] - G[c, 0] for c in range(k)]
            if self.global_height:
                h = T[i] - T[0]
                hm = TM[i] + TM[0]
            else:
                sq = v[0] * v[0]
                for c in range(1, k):
                    sq += v[c] * v[c]
                h = sq - W[i] + W[0]
                hm = sq + W[i] + W[0]
            V.append(v + [h])
            A.append([np.abs(e) for e in v] + [hm])
        D = det(V)
        P = _rowsum_bound(A)
        return self._decide(rows, D, _C_POWER[k] * _U * P, "power", self._power_exact)

    # ------------------------------------------------------------------ scalar
    def _as_lists(self):
        if self._lists is None:
            gh = self.global_height
            self._lists = (
                self.u.tolist(),
                self.w.tolist(),
                self.t.tolist() if gh else None,
                self.tmag.tolist() if gh else None,
            )
        return self._lists

    def orient1(self, row) -> int:
        """:meth:`orient` of one row (a sequence of k+1 ints), without numpy."""
        U = self._as_lists()[0]
        p0 = U[row[0]]
        k = self.k
        V = [[U[i][c] - p0[c] for c in range(k)] for i in row[1:]]
        D = det(V)
        P = permanent([[abs(e) for e in r] for r in V])
        bound = _C_ORIENT[k] * _U * P
        if abs(D) > bound and bound > _TINY and math.isfinite(D):
            return 1 if D > 0 else -1
        self.stats["orient_exact"] += 1
        return self._orient_exact(row)

    def power1(self, row) -> int:
        """:meth:`power` of one row (k+2 ints), without numpy."""
        U, W, T, TM = self._as_lists()
        k = self.k
        if T is None and k == 3:
            D, P = _power3(U, W, row)
            bound = _C_POWER[3] * _U * P
            if abs(D) > bound and bound > _TINY and D - D == 0.0:
                return 1 if D > 0 else -1
            self.stats["power_exact"] += 1
            return self._power_exact(row)
        i0 = row[0]
        p0 = U[i0]
        V, A = [], []
        for i in row[1:]:
            v = [U[i][c] - p0[c] for c in range(k)]
            if T is not None:
                h = T[i] - T[i0]
                hm = TM[i] + TM[i0]
            else:
                sq = sum(c * c for c in v)
                wi, w0 = W[i], W[i0]
                h = sq - wi + w0
                hm = sq + wi + w0
            V.append(v + [h])
            A.append([abs(e) for e in v] + [hm])
        D = det(V)
        P = permanent(A)
        bound = _C_POWER[k] * _U * P
        if abs(D) > bound and bound > _TINY and math.isfinite(D):
            return 1 if D > 0 else -1
        self.stats["power_exact"] += 1
        return self._power_exact(row)


# ----------------------------------------------------------------------------------
# Affine dimension, exactly
# ----------------------------------------------------------------------------------
def _exact_ints(values: np.ndarray):
    """The float64 ``values`` as Python integers at one common scale :math:`2^E`
    (object array of the same shape, exactly ``values * 2**-E``) and ``E``."""
    v = np.asarray(values, dtype=np.float64)
    M, e = _exponent_ints(v)
    nz = M != 0
    E = int(e[nz].min()) if nz.any() else 0
    shift = np.where(nz, e - E, 0)
    return M.astype(object) << shift.astype(object), E


def _minors(rows, r: int, d: int, fn=det):
    """The ``r x r`` minors (one per set of ``r`` columns, in lexicographic order) of
    the ``r x d`` matrices whose rows are ``rows`` (entries: scalars or arrays,
    broadcast); ``fn=permanent`` on absolute values gives their error bounds."""
    from itertools import combinations

    return [fn([[row[c] for c in cols] for row in rows]) for cols in combinations(range(d), r)]


def affine_basis(coords) -> list:
    """An affinely independent subset of the points that spans their affine hull,
    decided exactly (Notes §23.1).

    Parameters
    ----------
    coords : array_like, shape (n, d), d <= 3
        The points; their float64 values are the exact input.

    Returns
    -------
    list of int
        ``k + 1`` row indices, ``k`` the exact affine dimension of the points (``[]``
        for no points).  Every point lies exactly in the affine hull of these rows.

    See Also
    --------
    projection_axes : the coordinate axes a lower-dimensional flat projects to.

    Notes
    -----
    Greedy: starting from row 0, add at each step the point with the largest
    minor of the difference vectors (farthest from the current flat) among those
    the floating-point filter certifies to be off the flat (the error bound of
    :meth:`WeightedPoints.orient`); if the filter certifies none, the undecided
    points are tested with Python integers, and when every minor of every point is
    exactly zero the flat is the affine hull.  No rank threshold is involved: a
    set flat up to a relative 1e-12 but not exactly flat is full-dimensional.

    References
    ----------
    .. [1] J. R. Shewchuk, "Adaptive precision floating-point arithmetic and fast
       robust geometric predicates", Discrete Comput. Geom. 18 (1997) 305-363.

    Examples
    --------
    >>> affine_basis([[0.0, 0.0], [1.0, 0.0], [2.0, 1e-12], [3.0, 0.0]])
    [0, 3, 2]
    >>> affine_basis([[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]])
    [0, 2]
    """
    x = np.ascontiguousarray(coords, dtype=np.float64)
    n, d = x.shape
    if n == 0:
        return []
    if n > 4096:
        # a full-dimensional sample proves full dimension (its rows are points of x)
        step = n // 1024
        sub = affine_basis(x[::step])
        if len(sub) == d + 1:
            return [step * i for i in sub]
    basis = [0]
    X = np.ascontiguousarray(x.T)
    exact = None
    with np.errstate(all="ignore"):
        for r in range(1, d + 1):
            b0 = x[basis[0]]
            rows = [x[b] - b0 for b in basis[1:]] + [[X[c] - b0[c] for c in range(d)]]
            D = _minors(rows, r, d)
            P = _minors([[np.abs(e) for e in row] for row in rows], r, d, permanent)
            score = np.zeros(n)
            for Dm, Pm in zip(D, P):
                Dm = np.broadcast_to(Dm, (n,))
                bound = _C_ORIENT[r] * _U * np.broadcast_to(Pm, (n,))
                ok = (np.abs(Dm) > bound) & (bound > _TINY) & np.isfinite(Dm) & np.isfinite(bound)
                score = np.maximum(score, np.where(ok, np.abs(Dm), 0.0))
            if score.max() > 0:
                basis.append(int(np.argmax(score)))
                continue
            # nothing certified: every point is on the flat up to the filter; decide exactly
            if exact is None:
                exact = _exact_ints(x)[0]
            e0 = exact[basis[0]]
            erows = [exact[b] - e0 for b in basis[1:]] + [[exact[:, c] - e0[c] for c in range(d)]]
            off = np.zeros(n, dtype=bool)
            for Dm in _minors(erows, r, d):
                off |= np.broadcast_to(np.asarray(Dm != 0, dtype=bool), (n,))
            if not off.any():
                break
            basis.append(int(np.argmax(off)))
    return basis


def flat_simplices(z) -> np.ndarray:
    """Which simplices have affinely dependent vertices, decided exactly (Notes §23.1).

    Parameters
    ----------
    z : array_like, shape (m, j + 1, d), j <= d <= 3
        ``m`` simplices of ``j + 1`` vertices each; their float64 values are the exact
        input.

    Returns
    -------
    ndarray of bool, shape (m,)
        True where the ``j`` edges :math:`z_i - z_0` have rank below ``j`` (two equal
        vertices, three collinear, four coplanar): no orthosphere, or no single one.

    Notes
    -----
    A simplex is flat exactly when every ``j x j`` minor of its edge matrix is zero.
    Each minor is evaluated in floating point with the error bound of
    :func:`affine_basis`; a simplex with a minor certified non-zero is not flat, and
    the rest are decided with Python integers from the input's binary values.  No
    rank threshold is involved: a simplex thin to 1e-15 but not flat is not flat.

    See Also
    --------
    affine_basis : the exact affine dimension of a point set.

    Examples
    --------
    >>> flat_simplices([[[0.0, 0.0], [1.0, 1.0], [2.0, 2.0]], [[0.0, 0.0], [1e14, 0.0], [0.0, 1.0]]]).tolist()
    [True, False]
    """
    x = np.asarray(z, dtype=np.float64)
    m, k1, d = x.shape
    r = k1 - 1
    if r == 0 or m == 0:
        return np.zeros(m, dtype=bool)
    with np.errstate(all="ignore"):
        rows = [[x[:, i, c] - x[:, 0, c] for c in range(d)] for i in range(1, k1)]
        certain = np.zeros(m, dtype=bool)
        for Dm, Pm in zip(_minors(rows, r, d), _minors([[np.abs(e) for e in row] for row in rows], r, d, permanent)):
            bound = _C_ORIENT.get(r, np.inf) * _U * Pm  # 4 x 4 (4D): decided exactly
            certain |= (np.abs(Dm) > bound) & (bound > _TINY) & np.isfinite(Dm) & np.isfinite(bound)
    flat = ~certain
    todo = np.flatnonzero(flat)
    if todo.size:
        e = _exact_ints(x[todo])[0]  # (t, j + 1, d) Python integers at one scale
        erows = [[e[:, i, c] - e[:, 0, c] for c in range(d)] for i in range(1, k1)]
        off = np.zeros(todo.size, dtype=bool)
        for Dm in _minors(erows, r, d):
            off |= np.asarray(Dm != 0, dtype=bool)
        flat[todo[off]] = False
    return flat


def projection_axes(coords, basis) -> tuple:
    """The coordinate axes onto which the affine hull of ``coords[basis]`` projects
    best (Notes §23.1): the ``k = len(basis) - 1`` axes whose ``k x k`` minor of the
    difference vectors :math:`z_{b_i} - z_{b_0}` is largest in absolute value,
    compared exactly (Python integers); ties go to the lexicographically first axes.

    The minor is the volume of the projected simplex, so it is non-zero exactly when
    the projection is one-to-one on the flat: the exact predicates of a line or
    plane in 3D (or a line in 2D) are evaluated on these axes
    (:class:`WeightedPoints` ``axes``).  For an orthonormal basis ``Q`` of the flat
    the minors are ``det(C) det(Q[:, axes])``: the same choice as the most parallel
    axes, without a tolerance.

    Parameters
    ----------
    coords : array_like, shape (n, d)
    basis : sequence of int
        Affinely independent rows (:func:`affine_basis`).

    Returns
    -------
    tuple of int

    See Also
    --------
    affine_basis : the exact affine dimension and a spanning subset.

    References
    ----------
    .. [1] H. Edelsbrunner and E. P. Mücke, "Simulation of Simplicity", ACM Trans.
       Graphics 9 (1990) 66-104.

    Examples
    --------
    >>> projection_axes([[0.0, 0.0, 0.0], [1.0, 0.0, 3.0]], [0, 1])
    (2,)
    """
    from itertools import combinations

    x = np.asarray(coords, dtype=np.float64)
    basis = [int(b) for b in basis]
    k, d = len(basis) - 1, x.shape[1]
    if k <= 0:
        return ()
    X, _ = _exact_ints(x[basis])
    V = [X[i] - X[0] for i in range(1, k + 1)]
    best, best_v = None, -1
    for axes, m in zip(combinations(range(d), k), _minors(V, k, d)):
        if abs(m) > best_v:
            best, best_v = axes, abs(m)
    if best_v == 0:
        raise ValueError(f"projection_axes: the rows {basis} are affinely dependent")
    return tuple(best)
