"""Entry times of the α-filtration, certified (Notes §23.1).

What :func:`shapelab.alpha_filtration` runs with ``precision="exact"`` (the default):
the certified regular triangulation (:mod:`shapelab._engine.triangulation`), its
faces (:mod:`shapelab._engine.faces`), the certified orthospheres and attached flags
(:mod:`shapelab._engine.orthospheres`), the attached rule top-down, and the
filtration order.  The readable version of the same steps is in
:mod:`shapelab.filtration`.  A student may skip it.
"""

from __future__ import annotations

import numpy as np

from ..balls import Balls
from .faces import facets_from_neighbours, unique_facets
from .orthospheres import orthospheres_certified
from .triangulation import triangulate_local

__all__ = ["entry_times", "filtration_order"]


def entry_times(balls: Balls, *, with_attached: bool = False):
    """Steps 1-4 of :func:`shapelab.alpha_filtration`: faces, boundary matrices and entry times
    per dimension, in frame-local indices and units (``None`` if there are no balls).
    With ``with_attached``, a sixth item: the attachment flags per dimension (the
    top dimension's all False), aligned with the faces."""
    fr, simp, nbr = triangulate_local(balls)
    if simp.shape[0] == 0:
        return None
    dim = simp.shape[1] - 1
    nv = fr.keep.size
    w = fr.w

    # 1. all faces, top-down, with boundary matrices (local vertex indices)
    faces = [None] * (dim + 1)
    bnd = [None] * (dim + 1)
    faces[dim] = simp
    for j in range(dim, 0, -1):
        res = facets_from_neighbours(simp, nbr) if (j == dim and j >= 2) else None
        faces[j - 1], bnd[j] = res if res is not None else unique_facets(faces[j], nv)

    # 2. smallest orthogonal spheres and attachment, 3. top-down propagation
    vals = [None] * (dim + 1)
    flags = [None] * dim + [np.zeros(faces[dim].shape[0], dtype=bool)]
    rho, att = orthospheres_certified(balls, fr, faces[dim])
    vals[dim] = rho
    for j in range(dim, 0, -1):
        B = bnd[j]
        if j > 1:
            rho_f, att_f = orthospheres_certified(balls, fr, faces[j - 1])
        else:
            rho_f, att_f = -w[faces[0][:, 0]], None
        nf = faces[j - 1].shape[0]
        attached = np.zeros(nf, dtype=bool)
        attached[B[att]] = True
        cof = np.full(nf, np.inf)
        for i in range(j + 1):
            np.minimum.at(cof, B[:, i], vals[j])
        vals[j - 1] = np.where(attached, cof, rho_f)
        if with_attached:
            flags[j - 1] = attached
        del cof, attached
        att = att_f
    # 4. non-decreasing against round-off (GUDHI's make_filtration_non_decreasing)
    for j in range(1, dim + 1):
        for i in range(j + 1):
            np.maximum(vals[j], vals[j - 1][bnd[j][:, i]], out=vals[j])
    if with_attached:
        return fr, faces, bnd, vals, dim, flags
    return fr, faces, bnd, vals, dim


def filtration_order(v: np.ndarray, rows: np.ndarray) -> np.ndarray:
    """Permutation sorting by value, ties broken lexicographically by the rows.

    One ``np.lexsort`` on integer keys: the order-preserving integer image of the
    values (``-0.0`` counted as ``0.0``, so equal floats give equal keys) and the rows
    packed into as few int64 words as their columns fit in (most significant column
    first).  Rows are distinct, so the order is total and does not depend on the
    algorithm; ``lexsort`` is stable besides.
    """
    m = v.size
    if m == 0:
        return np.zeros(0, dtype=np.int64)
    key = (v + 0.0).view(np.int64)  # + 0.0: -0.0 -> 0.0
    if np.any(key < 0):  # negative floats: reversed, below the positive ones
        key = np.where(key < 0, np.int64(-(2**63)) - key - 1, key)
    w = rows.shape[1]
    bits = max(1, int(rows.max()).bit_length())
    per = max(1, 62 // bits)  # columns per int64 word
    words = []
    for a in range(0, w, per):
        word = rows[:, a].astype(np.int64)
        for c in range(a + 1, min(w, a + per)):
            word <<= np.int64(bits)
            word |= rows[:, c]
        words.append(word)
    return np.lexsort(words[::-1] + [key])
