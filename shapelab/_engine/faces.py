"""The faces of a triangulation and its boundary matrices, fast (Notes §23.1).

What :func:`shapelab.alpha_filtration` does with ``np.unique`` in its readable path
(``precision="fast"``), done here without sorting where the triangulation's neighbour
relation already pairs the facets, and with one in-place integer sort elsewhere: the
same faces, in the same order.  A student may skip this module.
"""

from __future__ import annotations

import numpy as np

__all__ = ["drop_cols", "facets_from_neighbours", "unique_facets"]


def drop_cols(w: int):
    """Column lists: for each i, the columns of a w-row without column i."""
    return [[c for c in range(w) if c != i] for i in range(w)]


def facets_from_neighbours(simp: np.ndarray, nbr: np.ndarray):
    """Facets of top simplices using the neighbour relation (no sorting).

    Each interior facet is shared by exactly two top simplices; the one with the
    smaller index owns it.  Returns ``(facets, boundary)`` (int32) or ``None`` if
    the neighbour relation is inconsistent (then the caller falls back to sorting).
    """
    m, w = simp.shape
    own = nbr < 0
    own |= np.arange(m, dtype=nbr.dtype)[:, None] < nbr
    ids = np.cumsum(own.ravel(), dtype=np.int32).reshape(m, w)
    ids -= 1
    p = np.flatnonzero(~own.ravel())
    t = p // w
    i = p - t * w
    nb = nbr.ravel()[p]
    back = nbr[nb] == t[:, None]
    j = np.argmax(back, axis=1)
    if not np.all(back[np.arange(j.size), j]):
        return None
    del back
    # the shared facet must have the same vertices on both sides (checked by the
    # sums of its vertex indices; the back pointers above were checked exactly)
    fs = simp.sum(axis=1, dtype=np.int64)[:, None] - simp
    if not np.array_equal(fs.ravel()[p], fs[nb, j]):
        return None
    del fs, t, i
    ids.ravel()[p] = ids[nb, j]
    del p, nb, j
    cols = np.array(drop_cols(w), dtype=np.intp)
    q = np.flatnonzero(own.ravel())
    ro = q // w
    facets = simp[ro[:, None], cols[q - ro * w]]
    return facets, ids


def unique_facets(simp: np.ndarray, nv: int):
    """All facets of the rows of ``simp`` (vertices ascending): unique facets
    (rows ascending, lexicographically sorted) and the (m, j+1) boundary matrix
    whose column i is the row of the facet opposite vertex i (both int32).

    The facets are encoded as integers (base ``nv``) with the position packed into
    the low bits, so one in-place SIMD ``np.sort`` replaces ``np.unique`` (which
    would ``argsort``: ~8x slower here); everything else is in place or int32.
    """
    m, w = simp.shape
    fw = w - 1
    if fw == 1:  # facets are vertices: a lookup table
        pos = np.full(nv, -1, dtype=np.int32)
        verts = np.flatnonzero(np.bincount(simp.ravel(), minlength=nv)).astype(np.int32)
        pos[verts] = np.arange(verts.size, dtype=np.int32)
        return verts[:, None], pos[simp[:, ::-1]]
    M = m * w
    ib = max(1, int(M - 1).bit_length())
    key_bits = max(1, int(nv - 1).bit_length()) * fw
    if key_bits + ib > 63:  # pragma: no cover - beyond ~2e6 balls in 3D
        allf = np.concatenate([simp[:, c] for c in drop_cols(w)])
        faces, inv = np.unique(allf, axis=0, return_inverse=True)
        return faces.astype(np.int32), inv.reshape(w, m).T.astype(np.int32)
    base = np.int64(nv)
    packed = np.empty((m, w), dtype=np.int64)  # row-major: position t * w + i
    for i, c in enumerate(drop_cols(w)):
        col = packed[:, i]
        col[...] = simp[:, c[0]]
        for cc in c[1:]:
            col *= base
            col += simp[:, cc]
    packed = packed.ravel()
    packed <<= np.int64(ib)
    packed |= np.arange(M, dtype=np.int64)
    packed.sort()
    perm = np.empty(M, dtype=np.int32)
    np.bitwise_and(packed, np.int64((1 << ib) - 1), out=perm, casting="unsafe")
    packed >>= np.int64(ib)
    first = np.empty(M, dtype=bool)
    first[0] = True
    np.not_equal(packed[1:], packed[:-1], out=first[1:])
    uniq = packed[first]
    del packed
    rank = np.cumsum(first, dtype=np.int32)
    rank -= 1
    del first
    inv = np.empty(M, dtype=np.int32)
    inv[perm] = rank
    del perm, rank
    faces = np.empty((uniq.size, fw), dtype=np.int32)
    for t in range(fw - 1, -1, -1):
        faces[:, t] = uniq % base
        uniq //= base
    return faces, inv.reshape(m, w)
