"""The union measure's degenerate cases (not required reading): flat top simplices of
the dual complex, whose pieces are the limits of the general closed forms of
:mod:`shapelab.measure`, found through the affine dependency of their centres.
Used with ``precision="exact"``; the closed forms are passed in (the engine imports
no public module).
"""

from __future__ import annotations

from itertools import combinations

import numpy as np

from .._toolkit import tolerances as tol
from .._toolkit.geometry import cross, dot

__all__ = ["FLAT_TOL", "flatness", "pieces_flat"]


#: A top simplex whose volume is below this fraction of (longest edge)^d is treated
#: as flat: its orthocentre would be determined by rounding noise only.  Relative to
#: the simplex's own size (scale- and translation-invariant); the pieces of a flat
#: simplex are the limits of the general formulas (:func:`pieces_flat`).
FLAT_TOL = tol.MEASURE_FLAT


def flatness(Z):
    """|det(edges)| / (longest edge)^d of top simplices."""
    k1 = Z.shape[0]
    E = [Z[i] - Z[0] for i in range(1, k1)]
    det = np.abs(E[0][0] * E[1][1] - E[0][1] * E[1][0]) if k1 == 3 else np.abs(dot(E[0], cross(E[1], E[2])))
    L = np.max(np.stack([np.sqrt(dot(Z[b] - Z[a], Z[b] - Z[a])) for a, b in combinations(range(k1), 2)]), axis=0)
    return np.where(L > 0, det / np.where(L > 0, L, 1.0) ** (k1 - 1), 0.0)


def pieces_flat(Z, W, R, d, edge_pieces, triangle_pieces):
    """Pieces of flat top simplices (the limit of a degenerate configuration).

    A flat d-simplex is in K only when its lifted points are (nearly) affinely
    dependent too: :math:`\\sum_{i\\in +} \\lambda_i \\pi_i = \\sum_{j \\in -}
    |\\lambda_j| \\pi_j` with the signs of the affine dependency of the centres
    (e.g. four cocircular centres in a plane).  Then one constraint of each
    farthest cell :math:`W_l` is implied by the others, and the piece of l is its
    piece in the facet without that vertex: l's partner when l's side of the
    dependency has two vertices, the lone vertex of the other side when l's side
    has three; the piece is empty when l is alone on its side.
    """
    k1, _, m = Z.shape
    M = np.concatenate([np.moveaxis(Z, 2, 0).transpose(0, 2, 1), np.ones((m, 1, k1))], axis=1)
    lam = np.linalg.svd(M)[2][:, -1, :].T  # (k1, m): sum lam_i z_i = 0, sum lam_i = 0
    pos = lam > 0
    P = np.zeros((k1, m))
    S = np.zeros((k1, m))
    for drop in range(k1):
        face = [v for v in range(k1) if v != drop]
        if d == 2:
            Pf, Sf = edge_pieces(Z[face], W[face], R[face], 2)
        else:
            Pf, Sf = triangle_pieces(Z[face], W[face], R[face])
        for j, l in enumerate(face):
            same = pos == pos[l]
            n_same = same.sum(axis=0)
            use = ((n_same == 2) & same[drop]) | ((n_same == k1 - 1) & ~same[drop])
            P[l, use] = Pf[j, use]
            S[l, use] = Sf[j, use]
    return P, S
