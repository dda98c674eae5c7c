"""The inputs of the notes' figures and of the lessons' 2D pictures (Notes §23.1).

Disks (and a few balls) in arbitrary units, each built to show one thing the notes
draw: a dual complex with two triangles, the two kinds of dent, holes of three sizes.
Everything is generated from documented geometry, deterministically.

======================  =========================================================
:func:`ring`            a ring of disks (or balls) around one hole (tunnel)
:func:`figure_23_1`     a dozen disks whose dual complex has two triangles
:func:`figure_23_2`     the two kinds of dent of Figure 23.2
:func:`swiss_cheese`    2D disks with round holes of three sizes and a long slit
:func:`nested_pockets`  2D: a pocket with two chambers, the inner behind a neck
:func:`mixed_dent`      2D: a dent that is a pocket for one growth model only
======================  =========================================================
"""

from __future__ import annotations

import numpy as np

from .._toolkit.validate import as_finite_scalar, as_positive_int
from ..balls import Balls
from ._common import cos_sin, dist_segment

__all__ = ["ring", "figure_23_1", "figure_23_2", "swiss_cheese", "nested_pockets", "mixed_dent", "hex_disk"]


# ----------------------------------------------------------------- 2D figures
def ring(n: int = 12, *, radius: float = 3.0, disk_radius: float = 1.0, dim: int = 2) -> Balls:
    """n equal disks (or balls) with centres evenly spaced on a circle: one hole.

    Geometry: centres :math:`R(\\cos 2\\pi k/n, \\sin 2\\pi k/n)` (in the plane z = 0
    for ``dim=3``), all of radius r.  Neighbours overlap when
    :math:`R\\sin(\\pi/n) < r`; the hole (a tunnel in 3D) is then alive from
    :math:`\\tau = R^2\\sin^2(\\pi/n) - r^2` (neighbours touch) until
    :math:`\\tau = R^2 - r^2` (the centre is covered).  All centres are co-circular,
    a deliberately degenerate input.

    See Also
    --------
    voids
        Its one hole.

    Examples
    --------
    >>> r = ring(10, radius=2.5, disk_radius=0.9)
    >>> len(r), r.dim
    (10, 2)
    """
    n = as_positive_int(n, "n", minimum=3)
    R = as_finite_scalar(radius, "radius", positive=True)
    r = as_finite_scalar(disk_radius, "disk_radius", nonnegative=True)
    if dim not in (2, 3) or isinstance(dim, bool):
        raise ValueError(f"dim must be 2 or 3, got {dim!r}")
    t = 2 * np.pi * np.arange(n) / n
    cos_t, sin_t = cos_sin(t)
    c = np.column_stack([R * cos_t, R * sin_t])
    if dim == 3:
        c = np.column_stack([c, np.zeros(n)])
    return Balls(c, r)


def figure_23_1() -> Balls:
    """Thirteen disks in the spirit of Figure 23.1 (a dual complex with two triangles).

    Hand-placed centres and radii (no randomness): a chain of overlapping disks, a
    cluster of three whose common intersection is non-empty twice over (two
    triangles of K at τ = 0), and a few isolated or just-touching disks so that the
    filtration shows vertices, edges and triangles entering at different times.

    See Also
    --------
    dual_complex
        Its dual complex.
    shapelab.plot.dual_complex
        Draws it.

    Examples
    --------
    >>> len(figure_23_1())
    13
    """
    c = np.array(
        [
            [0.0, 0.0],
            [1.6, 0.3],
            [0.8, 1.3],  # triangle 1
            [2.4, 1.6],  # with 1, 2: triangle 2
            [3.9, 1.2],
            [5.1, 0.4],
            [6.5, 0.9],  # a chain of edges
            [4.5, 3.0],
            [5.8, 2.9],  # a pair
            [-1.7, 1.9],
            [-1.0, 3.2],  # an edge, late triangle with 2
            [2.0, 4.0],  # alone at tau = 0
            [7.9, 2.4],  # alone at tau = 0
        ]
    )
    r = np.array([1.0, 1.0, 0.9, 0.95, 0.8, 0.75, 0.8, 0.7, 0.8, 0.7, 0.8, 0.6, 0.6])
    return Balls(c, r)


def hex_disk(radius: float, spacing: float) -> np.ndarray:
    """Points of the triangular lattice of spacing ``spacing`` inside the disk of radius
    ``radius`` about the origin, sorted by y then x: the body of the 2D figures.

    See Also
    --------
    figure_23_2, nested_pockets : cut their dents out of it.

    Examples
    --------
    >>> hex_disk(1.0, 1.0).tolist()
    [[-0.5, -0.8660254037844386], [0.5, -0.8660254037844386], [-1.0, 0.0], [0.0, 0.0], [1.0, 0.0], [-0.5, 0.8660254037844386], [0.5, 0.8660254037844386]]
    """
    k = int(np.ceil(radius / spacing)) + 2
    j, i = np.meshgrid(np.arange(-k, k + 1), np.arange(-k, k + 1), indexing="ij")
    x = (i + 0.5 * (j % 2)) * spacing
    y = j * spacing * np.sqrt(3.0) / 2.0
    p = np.column_stack([x.ravel(), y.ravel()])
    p = p[np.hypot(p[:, 0], p[:, 1]) <= radius + 1e-12]
    return p[np.lexsort((p[:, 0], p[:, 1]))]


def figure_23_2(*, body_radius: float = 6.0, spacing: float = 1.0, disk_radius: float = 0.65) -> tuple[Balls, Balls]:
    """The two kinds of dent of Figure 23.2, as two sets of disks ``(left, right)``.

    Both shapes start from the same body: the points of a triangular lattice of
    spacing s = 1 inside a disk of radius 6, each the centre of a disk of radius
    0.65 (more than the lattice's covering radius :math:`s/\\sqrt3 \\approx 0.577`,
    so the body has no holes).  Then a dent is carved by removing lattice points
    (distances in units of s):

    * **left** — a *flask*: every point within 2 of the chamber centre (0, 2.5), and
      within 0.9 of the vertical segment from (0, 2.5) up and out of the body, is
      removed.  The mouth (free width ≈ 2 − 2·0.65 = 0.7) is narrower than the
      chamber (free radius ≈ 1.35), so as the disks grow the mouth closes at
      τ ≈ 1 − 0.65² ≈ 0.58 while the chamber is free until τ ≈ 2² − 0.65² ≈ 3.6: the
      dent becomes a hole before it fills.  It **is a pocket** of the growth model.
    * **right** — a *funnel*: the same chamber, every point within 2 of (0, 2.5), but
      its mouth as wide as the chamber and widening outwards: every point above the
      chamber's centre with :math:`|x| < 2 + (y - 2.5)/2` is removed.  The two dents
      have the same depth and the same chamber; only the mouth's width differs, which
      is the notes' point.  Every cross-section of the funnel is at least as wide as the
      chamber, so as the disks grow it fills from the bottom up and never closes: it
      **is not a pocket**.

    Returns
    -------
    (Balls, Balls)
        The left and the right shape, each centred at the origin.

    See Also
    --------
    pockets
        The dents' pockets.
    shapelab.plot.pockets
        Draws them.

    Examples
    --------
    >>> flask, funnel = figure_23_2()
    >>> len(flask), len(funnel)
    (112, 100)
    """
    R = as_finite_scalar(body_radius, "body_radius", positive=True)
    s = as_finite_scalar(spacing, "spacing", positive=True)
    r = as_finite_scalar(disk_radius, "disk_radius", positive=True)
    p = hex_disk(R, s)
    chamber = np.array([0.0, 2.5 * s])
    flask = (np.hypot(*(p - chamber).T) < 2.0 * s) | (
        dist_segment(
            np.column_stack([p, np.zeros(len(p))]),
            np.array([chamber[0], chamber[1], 0.0]),
            np.array([0.0, R + 2 * s, 0.0]),
        )
        < 0.9 * s
    )
    x, y = p[:, 0], p[:, 1]
    funnel = (np.hypot(*(p - chamber).T) < 2.0 * s) | (
        (y >= chamber[1]) & (np.abs(x) < 2.0 * s + 0.5 * (y - chamber[1]))
    )
    return Balls(p[~flask], r), Balls(p[~funnel], r)


def swiss_cheese(*, spacing: float = 1.0, disk_radius: float = 0.65) -> Balls:
    """2D disks with four holes: round ones of three sizes and a long thin slit.

    Geometry: the triangular lattice of spacing s = 1 in the rectangle
    [−12, 12] × [−6, 6], disks of radius 0.65 (the body has no holes, as in
    :func:`figure_23_2`).  Removed (distances in units of s):

    * three round holes, every point within :math:`\\rho + 0.65` of (−7, 2), (0, 2)
      and (7, 2) for free radii ρ = 0.5, 0.9 and 1.3;
    * a slit, the lattice row y = −3·(√3/2) for −10 ≤ x ≤ 10 (21 points).  Its
      neighbours are the rows √3/2 above and below, so the slit is only
      :math:`2(\\sqrt3/2 - 0.65) \\approx 0.43` wide but 20 long.

    The slit has the largest area and the smallest persistence: its rows touch at
    τ = 3/4 − 0.65² ≈ 0.33, cutting it into 1 × √3 rectangles, all filled at
    τ = 1 − 0.65² ≈ 0.58, long before even the smallest round hole.  Persistence
    measures a hole's *thickness*, not its size (lesson 11).

    Returns
    -------
    Balls

    See Also
    --------
    voids
        Its holes.

    Examples
    --------
    >>> len(swiss_cheese())
    272
    """
    s = as_finite_scalar(spacing, "spacing", positive=True)
    r = as_finite_scalar(disk_radius, "disk_radius", positive=True)
    j, i = np.meshgrid(np.arange(-8, 9), np.arange(-14, 15), indexing="ij")
    x = (i + 0.5 * (j % 2)) * s
    y = j * s * np.sqrt(3.0) / 2.0
    p = np.column_stack([x.ravel(), y.ravel()])
    p = p[(np.abs(p[:, 0]) <= 12 * s + 1e-9) & (np.abs(p[:, 1]) <= 6 * s + 1e-9)]
    remove = np.zeros(len(p), bool)
    for cx, rho in ((-7.0, 0.5), (0.0, 0.9), (7.0, 1.3)):
        remove |= np.hypot(p[:, 0] - cx * s, p[:, 1] - 2.0 * s) < (rho * s + r)
    row = -3 * s * np.sqrt(3.0) / 2.0
    remove |= (np.abs(p[:, 1] - row) < 1e-9 * s) & (np.abs(p[:, 0]) <= 10 * s + 1e-9)
    p = p[~remove]
    return Balls(p[np.lexsort((p[:, 0], p[:, 1]))], r)


def nested_pockets(*, disk_radius: float = 0.65) -> Balls:
    """2D disks with a two-chamber pocket: the pocket hierarchy (Notes §23.1).

    Geometry (units of the lattice spacing 1): the triangular lattice inside a disk of
    radius 8, disks of radius 0.65, with removed:

    * chamber A: every point within 2.25 of (0, 4.5) (free radius ≈ 1.6);
    * chamber B: every point within 2.85 of (0, −1.5) (free radius ≈ 2.2);
    * the mouth, from A up and out: points with |x| ≤ 0.5 above y = 4.5; on every
      other row the mouth is only 2 − 2·0.65 = 0.7 wide, so it closes at
      τ = 1 − 0.65² ≈ 0.58;
    * the neck between A and B: points with |x| ≤ 1 for −1.5 ≤ y ≤ 4.5; its
      narrowest rows keep disks at x = ±1.5, so it closes at τ = 1.5² − 0.65² ≈ 1.83.

    As the disks grow, the mouth closes first and A ∪ B becomes one hole; then the neck
    closes and the hole splits in two; the smaller chamber A fills first.  At τ = 0
    both the whole flask and chamber B are pockets, nested.

    Returns
    -------
    Balls

    See Also
    --------
    pockets
        The pocket hierarchy.

    Examples
    --------
    >>> len(nested_pockets())
    186
    """
    r = as_finite_scalar(disk_radius, "disk_radius", positive=True)
    p = hex_disk(8.0, 1.0)
    x, y = p[:, 0], p[:, 1]
    remove = np.hypot(x, y - 4.5) < 2.25
    remove |= np.hypot(x, y + 1.5) < 2.85
    remove |= (np.abs(x) <= 0.5 + 1e-9) & (y >= 4.5)
    remove |= (np.abs(x) <= 1.0 + 1e-9) & (y >= -1.5) & (y <= 4.5)
    return Balls(p[~remove], r)


def mixed_dent(
    *, small_radius: float = 0.3, big_radius: float = 3.0, bowl_radius: float = 3.0, gap: float = 3.6
) -> Balls:
    """2D: a dent that is a pocket when disks grow by a probe, but not in the notes' model.

    Geometry: a half-ring of small disks (radius 0.3, centres 0.45 apart along the
    lower half of the circle of radius 3 about the origin) forms a bowl; two big disks
    (radius 3) sit at (±(gap/2 + 3), 1) over its rim, leaving a mouth ``gap`` = 3.6
    wide between them.

    * **Probe growth** (every radius :math:`r_i + p`, as a family of solvent probes;
      CASTp itself uses one probe, 1.4 Å, and the discrete flow):
      all disks grow at the same speed, the mouth between the big disks closes at
      p = gap/2 = 1.8 while the bowl is still free: a pocket.
    * **The notes' growth** (radius :math:`\\sqrt{r_i^2 + \\tau}`): small disks grow much
      faster (:math:`dr/d\\tau = 1/(2r)`); the bowl fills from below before the big disks
      meet (they would at τ = (gap/2 + 3)² − 9 ≈ 14): never a void, no pocket.

    Whether a dent is a pocket depends on how the balls grow (lesson 08).

    Returns
    -------
    Balls
        The small disks first, then the two big ones.

    See Also
    --------
    pockets
        Pockets with and without a probe.

    Examples
    --------
    >>> len(mixed_dent())
    24
    """
    rs = as_finite_scalar(small_radius, "small_radius", positive=True)
    rb = as_finite_scalar(big_radius, "big_radius", positive=True)
    rho = as_finite_scalar(bowl_radius, "bowl_radius", positive=True)
    g = as_finite_scalar(gap, "gap", positive=True)
    n = int(round(np.pi * rho / 0.45)) + 1
    ang = np.linspace(np.pi, 2 * np.pi, n)
    small = np.column_stack(cos_sin(ang)) * rho
    big = np.array([[-(g / 2 + rb), 1.0], [g / 2 + rb, 1.0]])
    return Balls(np.vstack([small, big]), np.r_[np.full(n, rs), np.full(2, rb)])
