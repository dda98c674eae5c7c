"""Betti numbers and persistence of an α-filtration (Notes §23.1, "Voids and pockets").

The growth model of Notes §23.1 turns the balls into a filtration
:math:`\\emptyset = K^1 \\subset K^2 \\subset \\dots \\subset K^m = D` of the Delaunay
(regular) triangulation :math:`D`; the dual complex :math:`K_\\tau` has the homotopy type
of the union of the balls grown to :math:`\\sqrt{r_i^2 + \\tau}` (nerve theorem), so its
Betti numbers :math:`\\beta_k(\\tau)` count the components (:math:`k = 0`), tunnels and
holes (:math:`k = 1`) and voids (:math:`k = 2` in 3D) of that union.  Persistence pairs
each feature's birth with its death as :math:`\\tau` grows; this is the hierarchy "big
voids against small ones" that the notes describe at the end of §23.1.

Where the notes are imprecise: "the topology of :math:`K(\\mathbb{P})` is the same as
that of :math:`\\mathbb{P}`" -- :math:`K_\\tau` and the union are homotopy equivalent
(the union deformation-retracts onto :math:`|K_\\tau|`), not homeomorphic; homotopy
equivalence is exactly what makes their Betti numbers and persistence agree.

Algorithms (Delfinado & Edelsbrunner's incremental method, made array-friendly):

* :math:`H_0` -- Kruskal on the 1-skeleton in filtration order.  An edge is *negative*
  (kills a component) iff it lies in the minimum spanning forest whose edge weights are
  the filtration ranks; SciPy computes that forest in C.  The elder rule pairs each
  negative edge with the younger of the two components it joins (one loop over the
  ``n - 1`` forest edges).
* :math:`H_{d-1}` -- Alexander duality.  The complement of :math:`K_\\tau` in the
  sphere :math:`S^d` is a graph: one node per top simplex not in :math:`K_\\tau` plus
  one *outside* node, one edge per :math:`(d-1)`-simplex not in :math:`K_\\tau`.
  Running time backwards, that graph only gains nodes and edges, so its components are
  a union–find in reverse filtration order; :math:`\\beta_{d-1}(\\tau)` is the number
  of its components minus one.  A :math:`(d-1)`-simplex is *positive* (creates a void
  or hole) iff it joins two components of the complement, i.e. iff it lies in the
  spanning forest of the dual graph taken in reverse order.  The persistence pairs
  are those of the dual :math:`H_0` by the elder rule, read forwards.
* :math:`\\beta_1` in 3D -- from the Euler characteristic,
  :math:`\\beta_1 = \\beta_0 + \\beta_2 - \\chi`, so Betti curves need no reduction.
* :math:`H_1` pairs in 3D -- the standard column reduction, restricted to the
  *negative* triangles (the others create voids, so their columns reduce to zero:
  "clearing") and to the rows of *positive* edges (rows of negative edges can be
  dropped without changing any pivot: "compression", Bauer, Kerber & Reininghaus
  2014).  Columns are Python sets, whose symmetric difference runs in C.

Every result is computed once per filtration object and kept on it
(:meth:`~shapelab.filtration.Filtration.derived`), so repeated ``betti(tau)`` calls
cost a binary search.

The filtration order is (value, dimension, row): within a dimension the rows of a
:class:`~shapelab.filtration.Filtration` are already in filtration order.  Persistence
pairs (as values) do not depend on how ties are broken, so they equal GUDHI's, which
break ties differently; zero-length pairs, which do depend on it, are omitted as GUDHI
does by default.

**Coefficients.**  Homology and persistence are computed over the field
:math:`\\mathbb{Z}/2` unless ``persistence(F, field=p)`` names another prime.  Only the
:math:`H_1` pairs of a 3-dimensional filtration can depend on the field (where a
2-chain's boundary is a multiple of a cycle, as a Möbius band's is: :func:`persistence`,
Notes); Betti numbers, :math:`H_0` and the voids never do.  Compare with GUDHI in the same field
(``compute_persistence(homology_coeff_field=p)``; GUDHI's default is 11).
"""

from __future__ import annotations

import numpy as np

from . import _topology as _impl  # noqa: F401 (the implementation; see its docstring)
from ._topology import reduce_boundary
from .filtration import as_filtration

__all__ = ["betti", "betti_curve", "persistence", "euler_characteristic_curve", "is_roundoff", "reduce_boundary"]

#: Relative length below which a pair counts as round-off (see :func:`is_roundoff`).
ROUNDOFF = _impl.ROUNDOFF


def betti(F, tau) -> tuple:
    """Betti numbers :math:`(\\beta_0, \\dots, \\beta_d)` of the dual complex :math:`K_\\tau`.

    Notes §23.1: :math:`K_\\tau` has the topology of the union of the balls grown to
    radii :math:`\\sqrt{r_i^2 + \\tau}`, so :math:`\\beta_0` counts its components,
    :math:`\\beta_1` its tunnels (holes in 2D) and :math:`\\beta_2` its voids (3D).

    Parameters
    ----------
    F : Filtration or Balls
        From :func:`shapelab.alpha_filtration` (or any object with the same accessors);
        Balls are turned into their filtration once and it is kept with them
        (the one input rule of the library).
    tau : float
        Growth time (``inf`` gives the whole triangulation, ``-inf`` the empty complex).

    Returns
    -------
    tuple of int
        Length ``d + 1`` for balls in :math:`\\mathbb{R}^d` (zeros above the filtration's
        own dimension when the centres are degenerate, e.g. coplanar in 3D).

    See Also
    --------
    betti_curve
        At many growth times.
    persistence
        The pairs behind the numbers.

    References
    ----------
    .. [1] C. J. A. Delfinado and H. Edelsbrunner, "An incremental algorithm for Betti
           numbers of simplicial complexes on the 3-sphere", *Comput. Aided Geom. Design*
           12(7):771-784, 1995. doi:10.1016/0167-8396(95)00016-Y
    .. [2] H. Edelsbrunner and J. L. Harer, *Computational Topology: An Introduction*,
           American Mathematical Society, 2010. doi:10.1090/mbk/069

    Examples
    --------
    >>> import numpy as np, shapelab as sl
    >>> t = np.linspace(0, 2 * np.pi, 12, endpoint=False)
    >>> ring = sl.Balls(np.c_[np.cos(t), np.sin(t)] * 3, 0.9)
    >>> sl.alpha_filtration(ring).betti(0.0)
    (1, 1, 0)
    """
    return _impl.betti(as_filtration(F, "betti"), tau)


def betti_curve(F, taus) -> np.ndarray:
    """Betti numbers at many growth times: an int array of shape ``(len(taus), d + 1)``.

    Row ``i`` is :func:`betti` at ``taus[i]`` (Notes §23.1, the hierarchy of features
    as the balls grow).  Costs two spanning forests once per filtration plus a binary
    search per τ: Delfinado–Edelsbrunner with :math:`\\beta_1` from the Euler
    characteristic in 3D.

    See Also
    --------
    betti
        At one growth time.
    shapelab.plot.betti_curve
        Draws it.

    References
    ----------
    .. [1] C. J. A. Delfinado and H. Edelsbrunner, "An incremental algorithm for Betti
           numbers of simplicial complexes on the 3-sphere", *Comput. Aided Geom. Design*
           12(7):771-784, 1995. doi:10.1016/0167-8396(95)00016-Y
    """
    return _impl.betti_curve(as_filtration(F, "betti_curve"), taus)


def euler_characteristic_curve(F, taus) -> np.ndarray:
    """:math:`\\chi(K_\\tau) = \\sum_k (-1)^k \\#\\{k\\text{-simplices with value} \\le \\tau\\}`.

    See Also
    --------
    betti_curve
        The Betti numbers whose alternating sum it is.

    References
    ----------
    .. [1] H. Edelsbrunner and J. L. Harer, *Computational Topology: An Introduction*,
           American Mathematical Society, 2010. doi:10.1090/mbk/069
    """
    return _impl.euler_characteristic_curve(as_filtration(F, "euler_characteristic_curve"), taus)


def is_roundoff(F, births, deaths) -> np.ndarray:
    """Which pairs are round-off of tied entry times rather than features.

    Tied entry times (co-circular or co-spherical balls: grids, symmetric cages) come
    out of floating-point arithmetic a few ulps apart, in GUDHI as here, and give
    pairs of length ~1e-15.  A pair counts as zero-length when
    ``death - birth <= ROUNDOFF * max(|birth|, |death|, scale)`` with
    ``ROUNDOFF = 2.5e-9``, at least twice the relative accuracy to which entry times
    are certified (:mod:`shapelab._toolkit.tolerances`): two tied entry times may come out
    that far apart.  ``scale`` is the size of the input in units of τ, the larger of
    the median :math:`r_i^2` and the median :math:`|z_i - z_j|^2 / 4` over the edges
    that join components (the :math:`H_0` forest), so that ties near τ = 0 (tangent
    balls of decimal input) count as round-off too.  It is geometric: a median of
    entry times would be dominated by the slivers of nearly flat centres (entry times
    up to ~1e30) and drop every finite pair.

    See Also
    --------
    persistence
        Drops these pairs.
    """
    return _impl.is_roundoff(as_filtration(F, "is_roundoff"), births, deaths)


def persistence(F, *, field=2) -> dict:
    """Persistence pairs of the α-filtration, per homology dimension, over the field
    :math:`\\mathbb{Z}/p` (``field=p``; :math:`\\mathbb{Z}/2` by default).

    Notes §23.1: growing the balls "distinguishes big voids or tunnels from smaller
    ones"; a feature's persistence is its death minus its birth, in units of τ.

    Parameters
    ----------
    F : Filtration
    field : int, default 2
        The prime ``p`` of the coefficient field :math:`\\mathbb{Z}/p` (GUDHI's
        ``homology_coeff_field``).  The default, :math:`\\mathbb{Z}/2`, is the field of
        the α-shape and persistence literature (Edelsbrunner, Letscher and Zomorodian
        2002; Edelsbrunner and Harer 2010); GUDHI's own default is :math:`\\mathbb{Z}/11`.

    Returns
    -------
    dict
        ``{k: (p, 2) float array}`` for ``k = 0..d``, rows ``(birth, death)`` in τ.
        Essential classes (only the components of the whole triangulation) have death
        ``inf``; zero-length pairs are omitted, and so are pairs shorter than the
        round-off of tied entry times (:func:`is_roundoff`: relative length below
        2.5e-9, twice the accuracy to which entry times are certified).  As multisets the pairs equal GUDHI's
        ``persistence_intervals_in_dimension(k)`` on the weighted alpha complex of the
        same balls computed *in the same field*
        (``compute_persistence(homology_coeff_field=p)``), up to those round-off pairs,
        which GUDHI reports too.  Rows are sorted by birth, then death; arrays are
        read-only.

    See Also
    --------
    betti, betti_curve : Betti numbers (field-independent).
    shapelab.diagrams.bottleneck_distance : compare two diagrams.

    Notes
    -----
    **Which diagrams depend on the field.**  Only :math:`H_1` of a 3-dimensional
    filtration.  :math:`H_0` (components) and :math:`H_{d-1}` (voids in 3D, holes in
    2D, read off the complement by Alexander duality) are the same over every field,
    and so are all Betti numbers of a complex in :math:`\\mathbb{R}^3` (its homology has
    no torsion).  But the *pairing* of :math:`H_1` classes can change: a 2-chain whose
    boundary is twice a cycle -- a Möbius band, whose rim runs twice around its core
    circle -- kills the rim in :math:`\\mathbb{Z}/2` (where :math:`2 = 0`) and only
    ties the rim to twice the core otherwise, so two loops may exchange their deaths.
    The pairs of two fields differ only where some 2-chain's boundary is a multiple of a
    cycle (relative to an earlier complex), as the band's is; real structures have such
    chains (lesson 09: 3MHT).

    Tunnels and their representative cycles (:func:`shapelab.tunnels`) are computed in
    :math:`\\mathbb{Z}/2`.

    References
    ----------
    .. [1] H. Edelsbrunner, D. Letscher, A. Zomorodian, "Topological persistence and
       simplification", Discrete Comput. Geom. 28 (2002) 511-533.
    .. [2] A. Zomorodian, G. Carlsson, "Computing persistent homology", Discrete Comput.
       Geom. 33 (2005) 249-274 (persistence over any field).
    .. [3] U. Bauer, M. Kerber, J. Reininghaus, "Clear and compress: computing persistent
       homology in chunks", Topological Methods in Data Analysis and Visualization III
       (2014) 103-117.

    Examples
    --------
    >>> import shapelab as sl
    >>> from shapelab.topology import persistence
    >>> F = sl.alpha_filtration(sl.Balls([[0, 0, 0], [1, 0, 0], [0, 1, 0]], [0.4, 0.4, 0.4]))
    >>> {k: len(v) for k, v in persistence(F).items()}
    {0: 3, 1: 0, 2: 0, 3: 0}
    >>> F.persistence(field=3)[0].shape  # H0: the same in every field
    (3, 2)
    """
    return _impl.persistence(as_filtration(F, "persistence"), field=field)
