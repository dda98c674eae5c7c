"""The α-filtration of a union of balls and its dual complexes (Notes §23.1).

Grow every ball :math:`B_i = (z_i, r_i)` to radius :math:`\\sqrt{r_i^2 + \\tau}`.  The
dual complex at time :math:`\\tau` is the nerve of the clipped cells

.. math:: K(\\tau) = \\{\\sigma \\subseteq DT : \\textstyle\\bigcap_{i\\in\\sigma}
          B_i(\\tau) \\cap \\Pi(B_i) \\neq \\emptyset\\},

and as :math:`\\tau` runs from :math:`-\\infty` to :math:`+\\infty` these complexes form
a nested sequence :math:`\\emptyset \\subset K^1 \\subset \\dots \\subset K^m = DT`.
Notes §23.1 call this sequence "the dual-complex"; the usual name is the
(weighted) *α-filtration*, and the notes' :math:`\\alpha` is :math:`\\sqrt{\\tau}`.

Each simplex :math:`\\sigma` of DT has an *entry time*: the least :math:`\\tau` with
:math:`\\sigma \\in K(\\tau)`.  It is computed from two ingredients:

* the *smallest orthogonal sphere* of :math:`\\sigma`: the point :math:`c_\\sigma` of
  the affine hull of :math:`\\sigma` with equal power distance to all its balls, and
  that common power :math:`\\rho_\\sigma = \\pi_i(c_\\sigma)` (for a vertex,
  :math:`c = z_i` and :math:`\\rho = -r_i^2`);
* the Gabriel test: :math:`\\sigma` is *attached* (not Gabriel) if some vertex
  :math:`v` of a coface has :math:`\\pi_v(c_\\sigma) < \\rho_\\sigma`, i.e. another ball
  claims :math:`c_\\sigma` before :math:`\\sigma`'s balls reach it.

Then, from the top dimension down, an unattached simplex enters at
:math:`\\rho_\\sigma` and an attached one enters with its earliest coface.  This is the
rule of GUDHI's ``AlphaComplex`` with weights, and the values agree with it to
round-off (tested).  In the weighted case the rule also applies to vertices: a ball
whose centre is covered by a neighbour's power enters later than :math:`-r_i^2`.

The seam ``precision``
----------------------
:func:`alpha_filtration` states the algorithm in the notes' words and, with
``precision="fast"``, runs it in floating point.  With ``precision="exact"`` (the
default) the engine (:mod:`shapelab._engine.alpha`) computes the same entry times with
a certified triangulation, an error bound per orthosphere and exact fallbacks, so the
filtration is the same on every machine.

Where the notes are imprecise
-----------------------------
* The sequence :math:`\\phi = K^1 \\subset \\dots \\subset K^m = D` is called "the
  dual-complex"; it is the α-*filtration* (of the dual complexes).
* :math:`K^1 = \\emptyset`, yet "the first dual complex is the set of vertices plus
  the two thick edges": the notes mean the first *non-empty* complex shown.
* :math:`D` is "the Delaunay triangulation defined by the set of centers"; for balls
  of different radii it is the *regular* triangulation, and hidden balls are not
  vertices of it (see :mod:`shapelab.triangulation`).
* :math:`\\alpha = \\sqrt{\\tau}` is real only for :math:`\\tau \\ge 0`, while the
  filtration starts at :math:`\\tau = \\min_i(-r_i^2) \\le 0`; we index by τ throughout.
* A vertex does not always enter at :math:`-r_i^2`, when its ball "appears": it
  enters when :math:`B_i(\\tau)` first meets its own cell :math:`\\Pi(B_i)`, which is
  later if a neighbour's power covers :math:`z_i`.
* "The topology of :math:`K(\\mathbb{P})` is the same as that of :math:`\\mathbb{P}`":
  :math:`K` and the union have the same *homotopy type* (nerve theorem), they are
  not homeomorphic (a triangle of :math:`K` can stand for a region of any shape).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np

from ._engine import alpha as engine
from ._engine import persistence as _topology
from ._toolkit.derived import KeepsDerived
from ._toolkit.validate import FlatSimplexError, as_bbox, as_precision, as_tau, check_balls, freeze
from .balls import Balls
from .triangulation import clipped_cells, orthosphere, power_diagram, regular_triangulation

__all__ = ["alpha_filtration", "dual_complex", "Filtration", "Complex", "BoundaryMatrix"]


# ----------------------------------------------------------------------------------
# Results
# ----------------------------------------------------------------------------------
def _check_k(k, dim_max: int) -> int:
    if isinstance(k, (bool, np.bool_)) or not isinstance(k, (int, np.integer)):
        raise TypeError(f"k must be an integer dimension, got {type(k).__name__}")
    k = int(k)
    if not 0 <= k <= dim_max:
        raise ValueError(f"k must be between 0 and {dim_max}, got {k}")
    return k


class _SimplicialMixin:
    """Accessors shared by :class:`Filtration` and :class:`Complex`."""

    def simplices(self, k: int) -> np.ndarray:
        """The k-simplices, shape (n_k, k+1), int32 indices into ``balls``.

        int32, as in ``scipy.spatial.Delaunay.simplices``: it halves the memory of
        the filtration (a ball index never needs more; ``Balls`` holds fewer than
        2**31 balls in any machine's memory).

        Vertices ascend within each row; rows are in filtration order
        (non-decreasing entry time, ties broken lexicographically).  For
        ``dimension < k <= d`` the array is empty.
        """
        k = _check_k(k, self.balls.dim)
        if k > self.dimension:
            return freeze(np.zeros((0, k + 1), dtype=np.int32))
        return self._simplices[k][: self._counts[k]]

    def values(self, k: int) -> np.ndarray:
        """Entry times τ of the k-simplices, shape (n_k,), non-decreasing."""
        k = _check_k(k, self.balls.dim)
        if k > self.dimension:
            return freeze(np.zeros(0))
        return self._values[k][: self._counts[k]]

    def boundary(self, k: int) -> np.ndarray:
        """Facet rows of the k-simplices, shape (n_k, k+1), int32, for k >= 1.

        Entry ``[i, j]`` is the row index into ``simplices(k-1)`` of the facet of
        simplex ``i`` opposite its vertex ``simplices(k)[i, j]``.
        """
        k = _check_k(k, self.balls.dim)
        if k == 0:
            raise ValueError("k must be >= 1 for boundary(k): vertices have no facets")
        if k > self.dimension:
            return freeze(np.zeros((0, k + 1), dtype=np.int32))
        return self._boundary[k][: self._counts[k]]

    def __len__(self) -> int:
        return int(sum(self._counts))

    def counts(self) -> tuple:
        """Number of simplices per dimension, ``(n_0, ..., n_dimension)``."""
        return tuple(int(c) for c in self._counts)


@dataclass(frozen=True, eq=False, repr=False)
class Complex(_SimplicialMixin):
    """The dual complex :math:`K(\\tau)` of the balls grown by ``tau`` (Notes §23.1).

    A sub-complex of the regular triangulation: the simplices whose entry time is at
    most ``tau``.  Obtain it with :meth:`Filtration.complex_at` or
    :func:`dual_complex`.

    Attributes
    ----------
    balls : Balls
    tau : float
    dimension : int
        Largest k with a k-simplex (-1 if empty).

    See Also
    --------
    dual_complex
        Builds it.
    Filtration.complex_at
        The complex of a filtration at τ.
    """

    balls: Balls
    tau: float
    dimension: int
    _simplices: tuple
    _values: tuple
    _boundary: tuple
    _counts: tuple

    def euler_characteristic(self) -> int:
        """:math:`\\chi(K) = \\sum_k (-1)^k n_k`."""
        return int(sum((-1) ** k * int(c) for k, c in enumerate(self._counts)))

    def __repr__(self) -> str:
        return f"Complex(tau={self.tau!r}, counts={self.counts()})"


class BoundaryMatrix(NamedTuple):
    """The boundary matrix of a filtration over :math:`\\mathbb{Z}/2`
    (:meth:`Filtration.boundary_matrix`).

    Column (and row) ``i`` is the simplex ``F.simplices(dims[i])[rows[i]]``, which
    enters at ``values[i]``.

    See Also
    --------
    Filtration.boundary_matrix : builds it.
    shapelab.persistence.reduce_boundary : reduces it.
    """

    #: (n, n) ``scipy.sparse.csc_matrix`` of 0/1 (uint8): entry ``[i, j]`` is 1 when
    #: simplex ``i`` is a facet of simplex ``j``.
    matrix: object
    #: (n,) int64: the dimension of each simplex.
    dims: np.ndarray
    #: (n,) int64: its row in ``F.simplices(dims[i])``.
    rows: np.ndarray
    #: (n,) float64: its entry time τ, non-decreasing.
    values: np.ndarray


@dataclass(frozen=True, eq=False, repr=False)
class Filtration(_SimplicialMixin, KeepsDerived):
    """The α-filtration (Notes §23.1, "the dual-complex") of a set of balls.

    Every simplex of the regular triangulation DT with the growth time τ at which it
    enters the dual complex of the balls of radii :math:`\\sqrt{r_i^2+\\tau}`.  The notes'
    :math:`\\alpha` is :math:`\\sqrt{\\tau}`.  Values agree (to round-off) with GUDHI's
    ``AlphaComplex(points=centers, weights=radii**2)``.

    Attributes
    ----------
    balls : Balls
    dimension : int
        Largest k with a k-simplex (-1 if there are no balls).

    See Also
    --------
    alpha_filtration
        Builds it.
    shapelab.persistence.persistence
        Its persistence pairs.
    """

    balls: Balls
    dimension: int
    _simplices: tuple
    _values: tuple
    _boundary: tuple
    _counts: tuple
    #: Results derived from the filtration (persistence pairs, merge tree, cycles,
    #: edge lookups), by key; filled on first use by :meth:`derived`.
    _derived: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    def clipped_cells(self, tau=0.0, *, bbox=None, arc_resolution: int = 96) -> tuple:
        """The cells :math:`B_i(\\tau) \\cap \\Pi(B_i)` of 2D balls as polygons (Notes
        §23.1, Figure 23.1): :func:`shapelab.triangulation.clipped_cells` with the power
        diagram of these balls computed once per filtration and box and kept on it,
        so that a drawing at many τ (a slider) clips the same diagram.

        Parameters
        ----------
        tau : float
            Growth time (finite).
        bbox : array_like (2, 2), optional
            The box the power cells are clipped to; it must hold the grown disks.
            By default the disks' box at ``tau`` padded by 1 (a new diagram per τ).
        arc_resolution : int
            Points per full circle on the arcs.

        Returns
        -------
        tuple of ndarray
            One (k_i, 2) counter-clockwise polygon per ball, (0, 2) when empty.
        """
        balls = check_balls(self.balls, "F.balls", dim=2)
        t = as_tau(tau, finite=True)
        if bbox is None:
            w = balls.weights + max(t, 0.0)
            r = np.sqrt(w)[:, None]
            bbox = (
                np.array([(balls.centers - r).min(axis=0) - 1.0, (balls.centers + r).max(axis=0) + 1.0])
                if len(balls)
                else np.array([[0.0, 0.0], [1.0, 1.0]])
            )
        box = as_bbox(bbox, 2)
        diagram = self.derived(f"power.diagram[{box.tobytes().hex()}]", lambda F: power_diagram(F.balls, bbox=box))
        return clipped_cells(balls, tau=t, diagram=diagram, arc_resolution=arc_resolution)

    def complex_at(self, tau) -> Complex:
        """The dual complex :math:`K(\\tau)`: all simplices with entry time ≤ ``tau``.

        ``tau`` may be ``±inf``; ``complex_at(inf)`` is the whole triangulation and
        ``complex_at(0.0)`` the dual complex of the balls as given.
        """
        t = as_tau(tau)
        counts = tuple(int(np.searchsorted(v, t, side="right")) for v in self._values)
        dim = max((k for k, c in enumerate(counts) if c > 0), default=-1)
        return Complex(self.balls, t, dim, self._simplices, self._values, self._boundary, counts)

    def attached(self, k: int) -> np.ndarray:
        """Which k-simplices are *attached*: enter with a coface, not at their own time.

        Parameters
        ----------
        k : int
            Dimension, ``0 <= k <= balls.dim``.

        Returns
        -------
        ndarray of bool, shape (n_k,)
            Aligned with :meth:`simplices` and :meth:`values`: ``True`` where the
            k-simplex is attached.  Top-dimensional simplices are never attached.

        Notes
        -----
        Notes §23.1 (the growth model).  Let :math:`(c_\\sigma, \\rho_\\sigma)` be the
        smallest orthogonal sphere of :math:`\\sigma`: the point of the affine hull of
        :math:`\\sigma` with equal power :math:`\\rho_\\sigma` from all its balls.
        :math:`\\sigma` is *unattached* if no other ball is closer to :math:`c_\\sigma`
        in power, :math:`\\pi_v(c_\\sigma) \\ge \\rho_\\sigma` for every vertex
        :math:`v` of a coface (equivalently, of every ball); then
        :math:`c_\\sigma` lies in the power face dual to :math:`\\sigma` and
        :math:`\\sigma` enters at :math:`\\rho_\\sigma`.  Otherwise it is *attached*:
        its cells first meet at a point of that face where the power is higher than
        :math:`\\rho_\\sigma`, on the boundary of the face, i.e. together with a
        coface, and it enters at the earliest entry time of its cofaces [1]_, [2]_.
        The test is exact (the sign of a barycentric coordinate of the coface's
        orthocentre, certified or in rational arithmetic); in a tie
        (:math:`\\pi_v(c_\\sigma) = \\rho_\\sigma`) the simplex counts as unattached,
        and both rules give the same time.  A vertex is attached when a neighbour's
        power covers its centre (:math:`c = z_i`, :math:`\\rho = -r_i^2`).

        Computed on first use (one more pass over the triangulation) and kept on
        the filtration.

        See Also
        --------
        values : the entry times; ``values(k)[attached(k)]`` are coface times.
        shapelab.power_distance : :math:`\\pi_v(x)`.

        References
        ----------
        .. [1] H. Edelsbrunner, "The union of balls and its dual shape", *Discrete
           Comput. Geom.* 13 (1995) 415-440.
        .. [2] H. Edelsbrunner and J. L. Harer, *Computational Topology*, AMS, 2010,
           §III.4 (alpha complexes).

        Examples
        --------
        Three unit disks on an obtuse triangle: the orthogonal circle of the long
        edge is centred at (2, 0) with :math:`\\rho = 2^2 - 1 = 3`, and the third
        centre has power :math:`1 - 1 = 0 < 3` there, so the edge is attached and
        enters with the triangle (circumcentre (2, -1.5), :math:`6.25 - 1`):

        >>> import shapelab as sl
        >>> F = sl.alpha_filtration(sl.Balls([[0, 0], [4, 0], [2, 1]], 1.0))
        >>> F.simplices(1).tolist()
        [[0, 2], [1, 2], [0, 1]]
        >>> F.attached(1).tolist()
        [False, False, True]
        >>> F.values(1).tolist(), F.values(2).tolist()
        ([0.25, 0.25, 5.25], [5.25])
        """
        k = _check_k(k, self.balls.dim)
        if k > self.dimension:
            return freeze(np.zeros(0, dtype=bool))
        return self.derived("filtration.attached", _attached_flags)[k]

    def betti(self, tau) -> tuple:
        """Betti numbers of :math:`K(\\tau)` (see :func:`shapelab.persistence.betti`)."""
        return _topology.betti(self, tau)

    def betti_curve(self, taus) -> np.ndarray:
        """Betti numbers at each τ (see :func:`shapelab.persistence.betti_curve`)."""
        return _topology.betti_curve(self, taus)

    def boundary_matrix(self) -> BoundaryMatrix:
        """The boundary matrix :math:`D` of the filtration over :math:`\\mathbb{Z}/2`,
        columns and rows in filtration order (Notes §23.1, "Voids and pockets").

        Every simplex of the filtration is one column and one row, ordered by entry
        time, then dimension, then row of :meth:`simplices` (the order in which
        :func:`shapelab.persistence.persistence` reads the filtration).  Column ``j`` holds
        the boundary of simplex ``j``: a 1 in the row of each of its facets.

        Returns
        -------
        BoundaryMatrix
            ``(matrix, dims, rows, values)``: the (n, n) ``scipy.sparse.csc_matrix``
            of 0/1 (uint8), and for each column its dimension, its row in
            ``simplices(dims[i])`` and its entry time τ.

        See Also
        --------
        shapelab.persistence.reduce_boundary : the standard column reduction of ``D``.
        shapelab.persistence.persistence : the pairs, computed without this matrix.

        Notes
        -----
        A face enters no later than its cofaces, and at a tie the lower dimension
        comes first, so :math:`D` is strictly upper triangular.  Reducing its columns
        (:func:`shapelab.persistence.reduce_boundary`) pairs the simplices that create a
        homology class with those that destroy one [1]_, [2]_.  Dense, it has
        :math:`n^2` entries: meant for small filtrations (lessons, tests).

        References
        ----------
        .. [1] H. Edelsbrunner, D. Letscher, A. Zomorodian, "Topological persistence and
           simplification", Discrete Comput. Geom. 28 (2002) 511-533.
        .. [2] H. Edelsbrunner, J. Harer, *Computational Topology: An Introduction*,
           AMS (2010), §VII.1.

        Examples
        --------
        >>> import shapelab as sl
        >>> F = sl.alpha_filtration(sl.Balls([[0, 0], [2, 0], [1, 1.5]], [0.5, 0.5, 0.5]))
        >>> B = F.boundary_matrix()
        >>> B.dims.tolist()
        [0, 0, 0, 1, 1, 1, 2]
        >>> F.simplices(1).tolist()  # the two sides of length 1.80 enter first
        [[0, 2], [1, 2], [0, 1]]
        >>> B.matrix.toarray()
        array([[0, 0, 0, 1, 0, 1, 0],
               [0, 0, 0, 0, 1, 1, 0],
               [0, 0, 0, 1, 1, 0, 0],
               [0, 0, 0, 0, 0, 0, 1],
               [0, 0, 0, 0, 0, 0, 1],
               [0, 0, 0, 0, 0, 0, 1],
               [0, 0, 0, 0, 0, 0, 0]], dtype=uint8)
        """
        from scipy.sparse import csc_matrix

        top = self.dimension
        dims = np.concatenate([np.full(int(self._counts[k]), k, dtype=np.int64) for k in range(top + 1)] or [[]])
        rows = np.concatenate([np.arange(int(self._counts[k]), dtype=np.int64) for k in range(top + 1)] or [[]])
        values = np.concatenate([np.asarray(self.values(k), dtype=np.float64) for k in range(top + 1)] or [[]])
        dims, rows = dims.astype(np.int64), rows.astype(np.int64)
        order = np.lexsort((rows, dims, values))
        dims, rows, values = dims[order], rows[order], values[order]
        n = order.size
        pos = [np.empty(int(self._counts[k]), dtype=np.int64) for k in range(top + 1)]
        for k in range(top + 1):
            pos[k][rows[dims == k]] = np.flatnonzero(dims == k)
        r_idx, c_idx = [], []
        for k in range(1, top + 1):
            cols = np.flatnonzero(dims == k)
            facets = np.asarray(self.boundary(k), dtype=np.int64)[rows[cols]]
            r_idx.append(pos[k - 1][facets].ravel())
            c_idx.append(np.repeat(cols, k + 1))
        r = np.concatenate(r_idx) if r_idx else np.zeros(0, dtype=np.int64)
        c = np.concatenate(c_idx) if c_idx else np.zeros(0, dtype=np.int64)
        D = csc_matrix((np.ones(r.size, dtype=np.uint8), (r, c)), shape=(n, n))
        D.sort_indices()
        for a in (dims, rows, values):
            a.flags.writeable = False
        return BoundaryMatrix(D, dims, rows, values)

    def persistence(self, *, field=2) -> dict:
        """Persistence diagrams over :math:`\\mathbb{Z}/p`, ``p = field`` (default 2; see
        :func:`shapelab.persistence.persistence`)."""
        return _topology.persistence(self, field=field)

    def __repr__(self) -> str:
        return f"Filtration(n_balls={len(self.balls)}, dimension={self.dimension}, counts={self.counts()})"


def as_filtration(F, who: str):
    """The filtration a function works on: ``F`` itself, or ``alpha_filtration(F)``
    when ``F`` is a :class:`~shapelab.Balls` (built once and kept with the balls:
    :meth:`shapelab.Balls.derived`).  The one input rule of the library.

    ``F`` may also be any object with the filtration's accessors and ``.balls``
    (``dimension``, ``simplices(k)``, ``values(k)``, ``boundary(k)``).  ``who`` names
    the calling function in the error message.
    """
    if isinstance(F, Balls):
        return F.derived("filtration.alpha", alpha_filtration)
    missing = [a for a in ("balls", "dimension", "simplices", "values", "boundary") if not hasattr(F, a)]
    if missing or not isinstance(F.balls, Balls):
        what = f"it has no {missing[0]!r}" if missing else "its .balls is not a shapelab.Balls"
        raise TypeError(
            f"{who}: F must be a Filtration (shapelab.alpha_filtration(balls)) or a shapelab.Balls; "
            f"{what} (got {type(F).__name__})"
        )
    return F


# ----------------------------------------------------------------------------------
# The algorithm
# ----------------------------------------------------------------------------------
def _empty_filtration(balls: Balls) -> Filtration:
    d = balls.dim
    simp = tuple(freeze(np.zeros((0, k + 1), dtype=np.int32)) for k in range(d + 1))
    vals = tuple(freeze(np.zeros(0)) for _ in range(d + 1))
    bnd = (None,) + tuple(freeze(np.zeros((0, k + 1), dtype=np.int32)) for k in range(1, d + 1))
    return Filtration(balls, -1, simp, vals, bnd, tuple(0 for _ in range(d + 1)))


def alpha_filtration(balls: Balls, *, precision: str = "exact") -> Filtration:
    """The α-filtration of the balls: every simplex of DT with its entry time τ.

    Parameters
    ----------
    balls : Balls
    precision : {"exact", "fast"}
        ``"exact"`` (default): the certified triangulation, each entry time within
        relative 1e-9 (typically a few ulp) of the exact one for the float64 input
        and the attached test exact (:mod:`shapelab._engine.orthospheres`): the same
        on every machine.  ``"fast"``: the steps below in floating point; on generic
        input the same simplices and times to about 1e-12 (tested), on degenerate
        input (co-spherical centres, right angles, duplicates) they may differ.

    Returns
    -------
    Filtration

    See Also
    --------
    dual_complex
        The complex at one growth time.
    Filtration
        What it returns.
    regular_triangulation
        The triangulation it filters.
    orthosphere
        The sphere that gives a simplex its own time.

    Notes
    -----
    Notes §23.1 (the growth model).  The balls grown by τ have radii
    :math:`\\sqrt{r_i^2 + \\tau}`; a simplex σ of DT enters the dual complex when the
    grown balls' cells first share a point.  The algorithm (GUDHI's [3]_):

    1. DT by the lifting map (:func:`regular_triangulation`), and all faces of its
       simplices.
    2. For every simplex σ its orthosphere :math:`(c_\\sigma, \\rho_\\sigma)`
       (:func:`orthosphere`): the grown balls of σ first meet, at :math:`c_\\sigma`,
       at :math:`\\tau = \\rho_\\sigma` (a vertex: :math:`c = z_i`,
       :math:`\\rho = -r_i^2`).
    3. From the top dimension down: a face τ of a coface σ, opposite σ's vertex v,
       is *attached* when v is closer in power to τ's orthocentre than τ's own balls,
       :math:`\\pi_v(c_\\tau) < \\rho_\\tau`: another ball claims :math:`c_\\tau`
       first, so τ's cells meet later, on the boundary of its dual face, together
       with a coface [1]_, [2]_.  An attached simplex enters with its earliest coface
       (the minimum over its cofaces, attained at one it is attached to); the others
       at :math:`\\rho_\\tau`.
    4. A face never enters after a coface (round-off cannot make it so).

    ``precision="exact"`` runs the same steps in the engine
    (:mod:`shapelab._engine.alpha`), in the triangulation's centred and scaled frame
    (τ scales with :math:`s^2`, translation leaves it fixed), with the faces paired
    by the triangulation's neighbours instead of sorted.

    References
    ----------
    .. [1] H. Edelsbrunner, "The union of balls and its dual shape", *Discrete Comput.
           Geom.* 13:415-440, 1995. doi:10.1007/BF02574053
    .. [2] H. Edelsbrunner and E. P. Mücke, "Three-dimensional alpha shapes", *ACM Trans.
           Graph.* 13(1):43-72, 1994. doi:10.1145/174462.156635
    .. [3] The GUDHI Project, *GUDHI User and Reference Manual*, "Alpha complex",
           https://gudhi.inria.fr/doc/latest/group__alpha__complex.html

    Examples
    --------
    Three unit disks on an obtuse triangle: the long edge is attached (the third
    centre is closer in power to its midpoint) and enters with the triangle.

    >>> import shapelab as sl
    >>> F = alpha_filtration(sl.Balls([[0, 0], [4, 0], [2, 1]], 1.0))
    >>> F.simplices(1).tolist(), F.values(1).tolist()
    ([[0, 2], [1, 2], [0, 1]], [0.25, 0.25, 5.25])
    >>> F.values(2).tolist()
    [5.25]

    The fast path: the same simplices, the same times up to round-off.

    >>> import numpy as np
    >>> G = alpha_filtration(sl.Balls([[0, 0], [4, 0], [2, 1]], 1.0), precision="fast")
    >>> G.simplices(1).tolist(), np.allclose(G.values(1), F.values(1), rtol=1e-12)
    ([[0, 2], [1, 2], [0, 1]], True)
    """
    check_balls(balls)
    if as_precision(precision) == "exact":
        res = engine.entry_times(balls)
        if res is None:
            return _empty_filtration(balls)
        fr, faces, bnd, vals, dim = res
        return _filtration(balls, faces, bnd, vals, dim, fr.keep, fr.scale**2)
    if len(balls) == 0:
        return _empty_filtration(balls)
    # 1. the regular triangulation and all faces of its simplices, top down;
    #    bnd[j][s, i] is the row in faces[j-1] of the facet of faces[j][s] opposite
    #    its vertex i
    simp = regular_triangulation(balls, precision="fast")
    dim = simp.shape[1] - 1
    faces, bnd = {dim: simp}, {}
    for j in range(dim, 0, -1):
        facets = np.stack([np.delete(faces[j], i, axis=1) for i in range(j + 1)], axis=1)
        faces[j - 1], inv = np.unique(facets.reshape(-1, j), axis=0, return_inverse=True)
        bnd[j] = inv.reshape(-1, j + 1)
    # 2. every simplex's orthosphere (c, rho)
    z, w = balls.centers, balls.weights
    try:
        ortho = {j: orthosphere(z[faces[j]], w[faces[j]]) for j in range(dim + 1)}
    except FlatSimplexError:  # a flat simplex left by Qhull: no orthosphere
        raise ValueError(
            "precision='fast': Qhull left a (nearly) flat simplex (degenerate centres, "
            "e.g. a grid or co-spherical); use precision='exact'"
        ) from None
    # 3. top down: the facet opposite vertex v of a coface is attached if
    #    pi_v(c) < rho; attached faces enter with their earliest coface
    vals = {dim: ortho[dim][1]}
    for j in range(dim, 0, -1):
        c, rho = ortho[j - 1]
        B, V = bnd[j], faces[j]
        d = c[B] - z[V]
        attached = np.zeros(rho.size, dtype=bool)
        attached[B[np.einsum("mik,mik->mi", d, d) - w[V] < rho[B]]] = True
        earliest = np.full(rho.size, np.inf)
        np.minimum.at(earliest, B, np.broadcast_to(vals[j][:, None], B.shape))
        vals[j - 1] = np.where(attached, earliest, rho)
    # 4. no face after a coface
    for j in range(1, dim + 1):
        vals[j] = np.maximum(vals[j], vals[j - 1][bnd[j]].max(axis=1))
    return _filtration(balls, faces, bnd, vals, dim)


def _filtration(balls: Balls, faces, bnd, vals, dim: int, keep=None, s2: float = 1.0) -> Filtration:
    """The :class:`Filtration` of faces, boundary rows and entry times per dimension:
    each dimension sorted in filtration order (by value, ties lexicographically),
    indices mapped to the input by ``keep`` (the engine's frame; ``None``: they are
    input indices) and values scaled by ``s2``."""
    simp_out, vals_out, bnd_out = [], [], [None]
    inv_prev = None
    identity = keep is None or keep.size == len(balls)  # no duplicate centres: local = input
    for j in range(dim + 1):
        v = vals[j] * s2 if s2 != 1.0 else vals[j]
        # local indices are ordered like input indices (keep is ascending), so the
        # lexicographic tie-break can use them
        order = engine.filtration_order(v, faces[j])
        out = np.empty(faces[j].shape, dtype=np.int32)
        if identity and faces[j].dtype == out.dtype:  # gather straight into the output
            np.take(faces[j], order, axis=0, out=out)
        else:
            out[...] = faces[j][order] if keep is None else keep[faces[j][order]]
        simp_out.append(freeze(out))
        vals_out.append(freeze(np.take(v, order)))
        faces[j] = vals[j] = v = None  # free as we go
        if j >= 1:
            out = np.take(bnd[j], order, axis=0).astype(np.int32, copy=False)
            np.take(inv_prev, out, out=out)  # (out= is buffered: in place is safe)
            bnd_out.append(freeze(out))
            bnd[j] = None
        inv_prev = np.empty(order.size, dtype=np.int32)
        inv_prev[order] = np.arange(order.size, dtype=np.int32)
        del order
    for j in range(dim + 1, balls.dim + 1):
        simp_out.append(freeze(np.zeros((0, j + 1), dtype=np.int32)))
        vals_out.append(freeze(np.zeros(0)))
        bnd_out.append(freeze(np.zeros((0, j + 1), dtype=np.int32)))
    counts = tuple(int(a.shape[0]) for a in simp_out)
    return Filtration(balls, dim, tuple(simp_out), tuple(vals_out), tuple(bnd_out), counts)


def _attached_flags(F: Filtration) -> tuple:
    """The attachment flag of every simplex of ``F``, per dimension, in the order of
    ``F.simplices(k)`` (what :meth:`Filtration.attached` returns): the entry times
    are recomputed with the flags and sorted exactly as :func:`alpha_filtration`
    sorts them, and the rows are checked to be ``F``'s own."""
    res = engine.entry_times(F.balls, with_attached=True)
    if res is None:
        return ()
    fr, faces, _, vals, dim, flags = res
    s2 = fr.scale**2
    out = []
    for j in range(dim + 1):
        v = vals[j] * s2 if s2 != 1.0 else vals[j]
        order = engine.filtration_order(v, faces[j])
        rows = fr.keep[faces[j][order]]
        if not np.array_equal(rows, F.simplices(j)):  # pragma: no cover - F built elsewhere
            raise ValueError("F: its simplices are not those of alpha_filtration(F.balls)")
        out.append(freeze(flags[j][order]))
    return tuple(out)


def dual_complex(balls: Balls) -> Complex:
    """The dual complex K of the union of the balls as given (Notes §23.1).

    Same as ``alpha_filtration(balls).complex_at(0.0)``: the nerve of the clipped
    cells :math:`B_i \\cap \\Pi(B_i)`.

    See Also
    --------
    alpha_filtration
        Every growth time at once.
    shapelab.oracles.sampled_nerve
        The same nerve by sampling, an oracle.

    References
    ----------
    .. [1] H. Edelsbrunner, "The union of balls and its dual shape", *Discrete Comput.
           Geom.* 13:415-440, 1995. doi:10.1007/BF02574053

    Examples
    --------
    Three disks that overlap pairwise around a hole: a cycle, no triangle.

    >>> import shapelab as sl
    >>> K = dual_complex(sl.Balls([[0, 0], [1.8, 0], [0.9, 1.5]], 1.0))
    >>> K.counts(), K.euler_characteristic()
    ((3, 3, 0), 0)
    """
    return alpha_filtration(balls).complex_at(0.0)
