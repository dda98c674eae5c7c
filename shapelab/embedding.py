"""Embedding a distance matrix in the plane: classical multidimensional scaling.

Shape classification (notes §23.2, the first application of matching) compares a family
of shapes by a distance, for example the bottleneck distance between their persistence
diagrams (:func:`shapelab.diagrams.distance_matrix`).  To *see* the classes, place one
point per shape in the plane so that Euclidean distances approximate the given ones.
Classical scaling (Torgerson 1952; Gower 1966) does it in closed form: double-centre the
squared distances, :math:`B = -\\tfrac12 J D^{(2)} J` with :math:`J = I - \\tfrac1k
\\mathbf{1}\\mathbf{1}^T`, and take the top eigenvectors of :math:`B` scaled by the square
roots of their eigenvalues.  When the distances are Euclidean (distances between points
of some :math:`\\mathbb{R}^q`), :math:`B` is their Gram matrix and the embedding in
:math:`q` dimensions reproduces them exactly; negative eigenvalues measure how far a
distance is from Euclidean.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ._toolkit.tolerances import DISTANCE_MATRIX_SYMMETRY
from ._toolkit.validate import as_float_array, as_positive_int

if TYPE_CHECKING:
    from numpy.typing import ArrayLike

__all__ = ["Embedding", "classical_mds"]


@dataclass(frozen=True, eq=False)
class Embedding:
    """The result of :func:`classical_mds`.

    Attributes
    ----------
    points : ndarray, shape (k, dim)
        One point per row of the distance matrix, centred at the origin.
    eigenvalues : ndarray, shape (k,)
        All eigenvalues of the double-centred matrix :math:`B`, largest first; the
        first ``dim`` give the embedding, negative ones say the distance is not
        Euclidean.

    See Also
    --------
    classical_mds
        Produces it.
    """

    points: np.ndarray
    eigenvalues: np.ndarray

    @property
    def explained(self) -> float:
        """Share of the positive spectrum the embedding keeps, in [0, 1]."""
        pos = self.eigenvalues[self.eigenvalues > 0]
        kept = self.eigenvalues[: self.points.shape[1]]
        return float(kept[kept > 0].sum() / pos.sum()) if pos.size else 1.0


def classical_mds(D: ArrayLike, dim: int = 2) -> Embedding:
    """Classical multidimensional scaling of a distance matrix.

    Parameters
    ----------
    D : array_like, shape (k, k)
        Symmetric, non-negative, zero on the diagonal.
    dim : int
        Dimension of the embedding (≥ 1).

    Returns
    -------
    Embedding
        Points (each axis's sign is fixed so that its largest entry in absolute value
        is positive) and the spectrum.  Where two kept eigenvalues are equal, the
        axes within their eigenspace are not unique: any rotation of them is as good,
        and which one is returned may depend on the LAPACK in use.

    See Also
    --------
    shapelab.diagrams.distance_matrix
        Distances between persistence diagrams to embed.

    References
    ----------
    .. [1] W. S. Torgerson, "Multidimensional scaling: I. Theory and method",
           *Psychometrika* 17:401-419, 1952. doi:10.1007/BF02288916
    .. [2] J. C. Gower, "Some distance properties of latent root and vector methods used
           in multivariate analysis", *Biometrika* 53(3-4):325-338, 1966.
           doi:10.1093/biomet/53.3-4.325

    Examples
    --------
    >>> X = np.array([[0.0, 0.0], [3.0, 0.0], [0.0, 4.0]])
    >>> D = np.linalg.norm(X[:, None] - X[None], axis=2)
    >>> E = classical_mds(D, 2)
    >>> np.allclose(np.linalg.norm(E.points[:, None] - E.points[None], axis=2), D)
    True
    """
    D = as_float_array(D, "D")
    if D.ndim != 2 or D.shape[0] != D.shape[1]:
        raise ValueError(f"D must be a square matrix, got shape {D.shape}")
    if not np.all(np.isfinite(D)):
        raise ValueError("D must be finite (an infinite distance cannot be embedded)")
    scale = float(np.abs(D).max()) if D.size else 0.0
    if np.any(D < 0) or not np.allclose(D, D.T, rtol=0, atol=DISTANCE_MATRIX_SYMMETRY * scale):
        raise ValueError("D must be symmetric with non-negative entries")
    if np.any(np.abs(np.diag(D)) > DISTANCE_MATRIX_SYMMETRY * scale):
        raise ValueError("D must be zero on the diagonal")
    dim = as_positive_int(dim, "dim")
    k = D.shape[0]
    if dim > k:
        raise ValueError(f"dim must be at most the number of points ({k}), got {dim}")
    D = (D + D.T) / 2
    J = np.eye(k) - 1.0 / k
    B = -0.5 * J @ (D**2) @ J
    w, V = np.linalg.eigh((B + B.T) / 2)
    order = np.argsort(-w, kind="stable")
    w, V = w[order], V[:, order]
    X = V[:, :dim] * np.sqrt(np.maximum(w[:dim], 0.0))
    flip = np.sign(X[np.argmax(np.abs(X), axis=0), np.arange(dim)])
    X = X * np.where(flip == 0, 1.0, flip)
    X.flags.writeable = False
    w.flags.writeable = False
    return Embedding(X, w)
