"""A peer library's persistence diagrams, computed when it is installed, else shipped.

The course compares its own diagrams with other ways of computing the same thing
(Notes §23.1: the α-complex has the homotopy type of the union; lesson 19 checks that
its *diagrams* are the union's).  Two of those ways come from GUDHI (The GUDHI Project
2015): the Delaunay–Čech complex and a cubical complex of the distance function on a
voxel grid.  GUDHI is not one of the course's requirements: it has no wheel for Linux
on ARM64 (Graviton and Ampere hubs, Raspberry Pi, Chromebooks), and the macOS wheels of
its 3.12 and 3.13 releases (universal2, Apple silicon and Intel) need macOS 14 where the
course supports macOS 12, so a student's ``pip install`` could not be asked to build it.

So each function here computes with GUDHI when ``import gudhi`` works and otherwise
returns the diagrams GUDHI computed for the lesson's input, shipped in
``shapelab/data/gudhi_reference.json`` with their provenance (GUDHI's version, the
command, the input).  :attr:`PeerDiagrams.source` says which it was.  Shipped values
are used only for the very input they were computed for (the same points to 1e-12,
the same parameters); any other input without GUDHI raises and says how to install it.

``python -m course.peer_values`` (in the repository, with GUDHI installed) writes the
file again; ``tests/library/test_peers.py`` holds it equal to a live computation.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from importlib import resources
from typing import TYPE_CHECKING

import numpy as np

from ._toolkit.validate import as_finite_scalar, as_points

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

__all__ = ["PeerDiagrams", "delaunay_cech_diagrams", "voxel_diagrams", "distance_grid", "REFERENCE_FILE"]

#: The shipped values, in the package's data folder.
REFERENCE_FILE = "gudhi_reference.json"


@dataclass(frozen=True)
class PeerDiagrams:
    """Persistence diagrams from a peer library, in dimensions 0, 1 and 2.

    Attributes
    ----------
    diagrams : dict of int -> (k, 2) ndarray
        ``diagrams[p]``: the (birth, death) pairs of dimension ``p``; death ``inf`` for
        a class that never dies.  Zero-length pairs are left out, as GUDHI does.
    source : str
        Where they come from: ``"GUDHI 3.13.0, computed now"`` or
        ``"GUDHI 3.13.0, shipped values (...)"``.
    computed : bool
        True if GUDHI computed them in this process.
    """

    diagrams: dict
    source: str
    computed: bool

    def __getitem__(self, p: int) -> np.ndarray:
        return self.diagrams[p]


def _gudhi():
    try:
        import gudhi
    except ImportError:
        return None
    return gudhi


def _reference() -> dict:
    text = resources.files("shapelab").joinpath("data", REFERENCE_FILE).read_text(encoding="utf-8")
    return json.loads(text)


def _as_diagrams(intervals) -> dict:
    out = {}
    for p in (0, 1, 2):
        D = np.asarray(intervals.get(p, intervals.get(str(p), [])), dtype=float).reshape(-1, 2)
        out[p] = D[np.lexsort((D[:, 1], D[:, 0]))]
    return out


def _shipped(kind: str, points: np.ndarray, params: dict, how: str) -> PeerDiagrams:
    data = _reference()
    for entry in data["entries"]:
        if entry["kind"] != kind or entry["params"] != params:
            continue
        stored = np.asarray(entry["points"], dtype=float)
        if stored.shape == points.shape and np.allclose(stored, points, rtol=0.0, atol=1e-12):
            source = (
                f"GUDHI {data['gudhi_version']}, shipped values (GUDHI is not installed; "
                f"shapelab/data/{REFERENCE_FILE}, made by `{data['command']}`)"
            )
            return PeerDiagrams(_as_diagrams(entry["diagrams"]), source, False)
    raise ModuleNotFoundError(
        f"{how} needs GUDHI, which is not installed, and shapelab ships its values only for the "
        f"lessons' inputs; install it with `pip install gudhi` (wheels for Linux x86-64, macOS 14 "
        f"or later and Windows x86-64) to compute it for these points"
    )


def _from_tree(st, **kw) -> dict:
    st.compute_persistence(homology_coeff_field=2, **kw)
    return _as_diagrams({p: st.persistence_intervals_in_dimension(p) for p in (0, 1, 2)})


def delaunay_cech_diagrams(points: ArrayLike) -> PeerDiagrams:
    """The diagrams of the Delaunay–Čech filtration of ``points``, by GUDHI, over Z/2.

    Each simplex of the Delaunay triangulation enters at the radius of the smallest
    ball enclosing its vertices: its value in the Čech complex, the nerve of the balls
    (Notes §23.1, the dual complex as a nerve).  Values are radii ρ, the scale of
    ``sqrt(tau)`` of :func:`shapelab.alpha_filtration` on balls of radius 0.

    Parameters
    ----------
    points : (n, 3) array_like
        The centres.

    Returns
    -------
    PeerDiagrams
        Computed by ``gudhi.DelaunayCechComplex(points).create_simplex_tree(
        output_squared_values=False)`` when GUDHI is installed, else the shipped values
        for this input.

    Raises
    ------
    ModuleNotFoundError
        GUDHI is not installed and no values are shipped for these points.

    See Also
    --------
    voxel_diagrams : the same union's diagrams without a nerve.
    shapelab.alpha_filtration : the α-filtration, whose diagrams these equal.

    References
    ----------
    .. [1] U. Bauer and H. Edelsbrunner, "The Morse theory of Čech and Delaunay
       complexes", Trans. Amer. Math. Soc. 369:3741–3762, 2017.
    .. [2] The GUDHI Project, *GUDHI User and Reference Manual*, "Delaunay-Čech complex".

    Examples
    --------
    The lesson's torus (lesson 19), with or without GUDHI:

    >>> from shapelab.datasets import sample_shape
    >>> from shapelab.peers import delaunay_cech_diagrams
    >>> cech = delaunay_cech_diagrams(sample_shape("torus", 400, seed=5))
    >>> len(cech[0]), int(np.isinf(cech[0][:, 1]).sum())
    (400, 1)
    """
    X = as_points(points, "points")
    gudhi = _gudhi()
    if gudhi is None:
        return _shipped("delaunay_cech", X, {}, "delaunay_cech_diagrams")
    st = gudhi.DelaunayCechComplex(points=X).create_simplex_tree(output_squared_values=False)
    # persistence_dim_max: the simplex tree's top dimension too, else a single point has no H0
    return PeerDiagrams(_from_tree(st, persistence_dim_max=True), f"GUDHI {gudhi.__version__}, computed now", True)


def distance_grid(points, side: float, pad: float) -> np.ndarray:
    """The distance function :math:`d_X(y) = \\min_{x \\in X} \\|y - x\\|` at the corners
    of a grid of voxels of side ``side`` over the box of ``points`` padded by ``pad``.

    Parameters
    ----------
    points : (n, 3) array_like
    side : float
        The voxels' side, > 0.
    pad : float
        How far the grid reaches beyond the points' box, >= 0.

    Returns
    -------
    (a, b, c) ndarray
        ``d_X`` at the grid's corners, axis by axis in increasing coordinate.

    See Also
    --------
    voxel_diagrams : the cubical complex of this grid.
    """
    from scipy.spatial import cKDTree

    X = as_points(points, "points")
    side = as_finite_scalar(side, "side", positive=True)
    pad = as_finite_scalar(pad, "pad", nonnegative=True)
    axes = [np.arange(lo - pad, hi + pad + side, side) for lo, hi in zip(X.min(axis=0), X.max(axis=0))]
    corners = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1)
    return cKDTree(X).query(corners.reshape(-1, X.shape[1]))[0].reshape(corners.shape[:-1])


def voxel_diagrams(points: ArrayLike, side: float, pad: float) -> PeerDiagrams:
    """The diagrams of the distance function sampled on voxels, by GUDHI, over Z/2.

    :func:`distance_grid` gives :math:`d_X` at the corners of voxels of side ``side``;
    GUDHI's cubical complex (``CubicalComplex(vertices=...)``, a cube entering with its
    largest corner value) filters them.  No nerve at all: the union's sublevel sets,
    sampled.  Since :math:`d_X` is 1-Lipschitz these diagrams are within
    :math:`\\text{side}\\sqrt{3}` of the union's in the bottleneck distance (the stability
    theorem for interleaved filtrations, Chazal et al. 2009).

    Parameters
    ----------
    points : (n, 3) array_like
    side : float
        The voxels' side.
    pad : float
        How far the grid reaches beyond the points' box; past every finite death.

    Returns
    -------
    PeerDiagrams
        Computed by GUDHI when it is installed, else the shipped values for this input.

    Raises
    ------
    ModuleNotFoundError
        GUDHI is not installed and no values are shipped for this input.

    See Also
    --------
    delaunay_cech_diagrams : the same union's diagrams by a nerve.

    References
    ----------
    .. [1] F. Chazal, D. Cohen-Steiner, M. Glisse, L. J. Guibas and S. Y. Oudot,
       "Proximity of persistence modules and their diagrams", Proc. 25th Annu. Sympos.
       Comput. Geom., 237–246, 2009.
    .. [2] The GUDHI Project, *GUDHI User and Reference Manual*, "Cubical complex".

    Examples
    --------
    >>> from shapelab.datasets import sample_shape
    >>> from shapelab.peers import voxel_diagrams
    >>> # the lesson's torus (lesson 19), with or without GUDHI
    >>> vox = voxel_diagrams(sample_shape("torus", 400, seed=5), side=0.05, pad=0.7)
    >>> life = vox[1][:, 1] - vox[1][:, 0]
    >>> int((life > 0.2).sum())  # the torus's two loops
    2
    """
    X = as_points(points, "points")
    gudhi = _gudhi()
    if gudhi is None:
        side = as_finite_scalar(side, "side", positive=True)
        pad = as_finite_scalar(pad, "pad", nonnegative=True)
        return _shipped("voxels", X, {"side": side, "pad": pad}, "voxel_diagrams")
    cc = gudhi.CubicalComplex(vertices=distance_grid(X, side, pad))
    return PeerDiagrams(_from_tree(cc), f"GUDHI {gudhi.__version__}, computed now", True)
