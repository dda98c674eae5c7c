"""Generated molecules: the C60 cage, carbon nanotubes, a bowl, a protein-like globule
(Notes §23.1).

Everything here is *generated* from documented geometry: nothing is downloaded, and
every random choice comes from a seeded :class:`numpy.random.Generator`, so the same
call gives the same balls on every machine.  Lengths are in Å.  The carbon radius used
throughout is Bondi's van der Waals radius of carbon, 1.70 Å (A. Bondi, *J. Phys.
Chem.* **68**, 441 (1964)); see :data:`shapelab.io.VDW_RADII`.

=========================  =========================================================
:func:`fullerene_c60`      the C60 cage: one void
:func:`nanotube`           an (n, m) carbon nanotube: one tunnel
:func:`bowl`               a spherical shell with a round opening: one pocket
:func:`globule`            a protein-like globule: a buried void, a pocket, a groove
:func:`globule_structure`  the same globule as a :class:`~shapelab.io.PDBStructure`
=========================  =========================================================
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from .._toolkit.validate import as_finite_scalar, as_positive_int
from ..balls import Balls
from ._common import ball_jitter, cos_sin, dist_segment, seeded_rng

if TYPE_CHECKING:
    from ..io import PDBStructure

__all__ = [
    "fullerene_c60",
    "c60_edges",
    "nanotube",
    "nanotube_radius",
    "bowl",
    "globule",
    "globule_structure",
    "GRAPHENE_LATTICE_CONSTANT",
    "CARBON_RADIUS",
]

#: The golden ratio φ = (1 + √5)/2.
PHI = (1.0 + np.sqrt(5.0)) / 2.0
#: Graphene lattice constant a = √3 · 1.42 Å ≈ 2.46 Å (the C–C bond is 1.42 Å).
GRAPHENE_LATTICE_CONSTANT = 2.46
#: Bondi's (1964) van der Waals radius of carbon, in Å.
CARBON_RADIUS = 1.70


# --------------------------------------------------------------------------- C60
def _truncated_icosahedron() -> np.ndarray:
    """The 60 vertices of the truncated icosahedron with edge length 2.

    They are the *even* (cyclic) permutations of (0, ±1, ±3φ), (±1, ±(2+φ), ±2φ) and
    (±φ, ±2, ±φ³), all sign combinations.
    """
    base = [(0.0, 1.0, 3 * PHI), (1.0, 2 + PHI, 2 * PHI), (PHI, 2.0, PHI**3)]
    pts = set()
    for b in base:
        for sx in (1, -1):
            for sy in (1, -1):
                for sz in (1, -1):
                    v = (sx * b[0], sy * b[1], sz * b[2])
                    for k in range(3):  # the three cyclic (even) permutations
                        p = (v[k % 3], v[(k + 1) % 3], v[(k + 2) % 3])
                        pts.add(tuple(round(c, 12) + 0.0 for c in p))
    out = np.array(sorted(pts), dtype=np.float64)
    assert out.shape == (60, 3)
    return out


def fullerene_c60(
    *,
    bond_length: float = 1.4,
    atom_radius: float = CARBON_RADIUS,
    jitter: float = 0.0,
    seed: int | np.random.Generator = 0,
) -> Balls:
    """Buckminsterfullerene C60: 60 carbon balls on a truncated icosahedron.

    Geometry: the vertices of the truncated icosahedron (even permutations of
    (0, ±1, ±3φ), (±1, ±(2+φ), ±2φ), (±φ, ±2, ±φ³), which have edge length 2),
    scaled so that every one of the 90 edges has length ``bond_length``, centred at
    the origin.  All atoms lie on a sphere of radius
    :math:`R = \\tfrac{b}{2}\\sqrt{9\\varphi^2 + 1} \\approx 2.478\\,b` (3.47 Å for
    b = 1.4 Å).  (Real C60 has two bond lengths, 1.401 and 1.458 Å by gas-phase electron diffraction, Hedberg et al. 1991; one is enough here.)

    Topology: with the carbon radius 1.70 Å the faces are closed (a hexagon's centre is
    1.4 Å from its atoms, a pentagon's 1.19 Å), so the union has exactly **one void**,
    the inside of the cage.  It is sealed at :math:`\\tau = b^2 - r^2` (the hexagons
    close) and filled at :math:`\\tau = R^2 - r^2` (the centre is covered).

    Parameters
    ----------
    bond_length : float, default 1.4
        C–C bond length b in Å.
    atom_radius : float, default 1.70
        Radius of every ball (Bondi's carbon).
    jitter : float, default 0
        Move every centre by a seeded random vector of length ≤ ``jitter`` (Å), which
        breaks the degeneracies below.
    seed : int or Generator

    Returns
    -------
    Balls
        60 balls in 3D.  Without jitter the input is deliberately degenerate: all 60
        centres are co-spherical and each hexagon is co-circular.

    See Also
    --------
    c60_edges
        Its bonds.
    nanotube
        Another carbon cage.

    Examples
    --------
    >>> c60 = fullerene_c60()
    >>> len(c60), float(c60.radii[0])
    (60, 1.7)
    """
    b = as_finite_scalar(bond_length, "bond_length", positive=True)
    r = as_finite_scalar(atom_radius, "atom_radius", nonnegative=True)
    jit = as_finite_scalar(jitter, "jitter", nonnegative=True)
    c = _truncated_icosahedron() * (b / 2.0)
    if jit > 0:
        c = c + ball_jitter(seeded_rng(seed), len(c), jit)
    return Balls(c, r)


def c60_edges(balls: Balls | None = None, *, tol: float = 1e-6) -> np.ndarray:
    """The 90 bonds of C60 as an (90, 2) array of atom indices (pairs at bond length).

    Parameters
    ----------
    balls : Balls, optional
        A C60 from :func:`fullerene_c60` (default: ``fullerene_c60()``).
    tol : float
        Relative tolerance on the bond length.

    See Also
    --------
    fullerene_c60
        The atoms.

    Examples
    --------
    >>> c60_edges().shape  # 90 bonds, each a pair of atom indices
    (90, 2)
    """
    balls = fullerene_c60() if balls is None else balls
    c = balls.centers
    d = np.linalg.norm(c[:, None] - c[None], axis=-1)
    iu = np.triu_indices(len(c), 1)
    dmin = d[iu].min()
    mask = np.abs(d[iu] - dmin) <= tol * dmin
    return np.column_stack([iu[0][mask], iu[1][mask]]).astype(np.int64)


# ------------------------------------------------------------------- nanotube
def nanotube_radius(n: int, m: int, *, a: float = GRAPHENE_LATTICE_CONSTANT) -> float:
    """Radius :math:`a\\sqrt{n^2 + nm + m^2}/(2\\pi)` of an (n, m) nanotube, in Å.

    See Also
    --------
    nanotube
        The tube.

    Examples
    --------
    >>> round(float(nanotube_radius(8, 8)), 3)  # Å
    5.425
    """
    n = as_positive_int(n, "n", minimum=0)
    m = as_positive_int(m, "m", minimum=0)
    a = as_finite_scalar(a, "a", positive=True)
    return a * np.sqrt(n * n + n * m + m * m) / (2 * np.pi)


def nanotube(
    n: int = 8,
    m: int = 8,
    *,
    length: float = 12.0,
    atom_radius: float = CARBON_RADIUS,
    a: float = GRAPHENE_LATTICE_CONSTANT,
    slit: float = 0.0,
    jitter: float = 0.0,
    seed: int | np.random.Generator = 0,
) -> Balls:
    """A single-walled (n, m) carbon nanotube: a graphene sheet rolled up.

    Geometry: graphene has lattice vectors :math:`a_1 = a(1, 0)`,
    :math:`a_2 = a(\\tfrac12, \\tfrac{\\sqrt3}{2})` with two atoms per cell, at 0 and
    :math:`(a_1 + a_2)/3` (bond :math:`a/\\sqrt3 = 1.42` Å for a = 2.46 Å).  The chiral
    vector :math:`C_h = n a_1 + m a_2` has length
    :math:`|C_h| = a\\sqrt{n^2+nm+m^2}`; the strip :math:`0 \\le u < |C_h|` (u along
    :math:`C_h`), :math:`0 \\le v < L` (v across) is rolled into a cylinder of radius
    :math:`|C_h|/2\\pi` about the z axis: :math:`(u, v) \\mapsto (R\\cos\\theta,
    R\\sin\\theta, v)`, :math:`\\theta = 2\\pi u/|C_h|`.  (n, n) is "armchair",
    (n, 0) "zigzag".  The tube axis is z, from z = 0 to z < L; the ends are open.

    Topology: with carbon radius 1.70 Å the hexagons are covered (their centres are
    1.42 Å from their atoms) while the inside stays free, so the union has exactly
    **one tunnel** (β₁ = 1) and no void.

    With ``slit`` > 0 the atoms whose arc position :math:`R\\theta` lies within
    ``slit``/2 of the line θ = 0 are removed along the whole length: the tube becomes
    a **groove** (a gutter) that turns into a tunnel when its lips close as the
    balls grow — if the slit is narrow enough (lesson 10).

    Parameters
    ----------
    n, m : int
        Chiral indices, n ≥ 1, 0 ≤ m.
    length : float
        Tube length L in Å.
    atom_radius : float
        Ball radius in Å.
    a : float
        Lattice constant in Å.
    slit : float
        Arc width in Å of the strip of atoms removed (0: a closed tube).
    jitter : float, default 0
        Move every centre by a seeded random vector of length ≤ ``jitter`` (Å): the
        exact tube is degenerate (co-cylindrical, and rings of co-circular atoms).
    seed : int or Generator

    See Also
    --------
    nanotube_radius
        Its radius.
    tunnels
        Its tunnel.

    Examples
    --------
    >>> tube = nanotube(8, 8, length=12.0)
    >>> len(tube), tube.dim
    (160, 3)
    """
    n = as_positive_int(n, "n", minimum=1)
    m = as_positive_int(m, "m", minimum=0)
    L = as_finite_scalar(length, "length", positive=True)
    r = as_finite_scalar(atom_radius, "atom_radius", nonnegative=True)
    a = as_finite_scalar(a, "a", positive=True)
    a1 = a * np.array([1.0, 0.0])
    a2 = a * np.array([0.5, np.sqrt(3.0) / 2.0])
    ch = n * a1 + m * a2
    C = float(np.linalg.norm(ch))
    cu = ch / C
    cv = np.array([-cu[1], cu[0]])
    # lattice points whose (u, v) may fall in [0, C) x [0, L): bound |i|, |j|
    reach = (C + L) / a * 2.0 + 2.0
    k = int(np.ceil(reach))
    i, j = np.meshgrid(np.arange(-k, k + 1), np.arange(-k, k + 1), indexing="ij")
    cells = i.reshape(-1, 1) * a1 + j.reshape(-1, 1) * a2
    basis = np.array([[0.0, 0.0], (a1 + a2) / 3.0])
    pts = (cells[:, None, :] + basis[None]).reshape(-1, 2)
    u = pts @ cu
    v = pts @ cv
    eps = 1e-9 * max(C, L)
    keep = (u >= -eps) & (u < C - eps) & (v >= -eps) & (v < L - eps)
    u, v = u[keep], v[keep]
    order = np.lexsort((u, v))
    u, v = u[order], v[order]
    R = C / (2 * np.pi)
    sl = as_finite_scalar(slit, "slit", nonnegative=True)
    if sl >= C:
        raise ValueError(f"slit must be narrower than the circumference {C:.4g} Å, got {sl!r}")
    theta = 2 * np.pi * u / C
    if sl > 0:  # arc distance from the line theta = 0, both ways round
        arc = np.minimum(u, C - u)
        keep = arc >= sl / 2.0
        theta, v = theta[keep], v[keep]
    cos_t, sin_t = cos_sin(theta)
    centers = np.column_stack([R * cos_t, R * sin_t, v])
    if len(centers) == 0:
        raise ValueError(f"length={L} is too short to hold a ring of atoms")
    jit = as_finite_scalar(jitter, "jitter", nonnegative=True)
    if jit > 0:
        centers = centers + ball_jitter(seeded_rng(seed), len(centers), jit)
    return Balls(centers, r)


# ----------------------------------------------------------------------- bowl
def _fibonacci_sphere(N: int) -> np.ndarray:
    i = np.arange(N)
    z = 1.0 - (2.0 * i + 1.0) / N
    phi = i * np.pi * (3.0 - np.sqrt(5.0))  # the golden angle
    s = np.sqrt(1.0 - z * z)
    cos_p, sin_p = cos_sin(phi)
    return np.column_stack([s * cos_p, s * sin_p, z])


def bowl(
    *,
    radius: float = 6.0,
    opening: float = 50.0,
    spacing: float = 2.0,
    atom_radius: float = CARBON_RADIUS,
    jitter: float = 0.0,
    seed: int | np.random.Generator = 0,
) -> Balls:
    """A deep bowl: a spherical shell of atoms with a round opening, one pocket.

    Geometry: about :math:`N = 4\\pi R^2 / (\\tfrac{\\sqrt3}{2} s^2)` points of a
    Fibonacci (golden-angle) lattice on the sphere of radius R (neighbour spacing
    ≈ s), of which those within ``opening`` degrees of the +z pole are removed.  The
    mouth is the circle of radius :math:`R\\sin(\\text{opening})` at height
    :math:`R\\cos(\\text{opening})`.  Optional jitter moves each centre by a seeded
    uniform vector of length ≤ ``jitter``.

    Topology (growth model, Notes §23.1): at τ = 0 the inside is open to the
    outside (no void).  As the balls grow, the mouth closes at about
    :math:`\\tau \\approx R^2\\sin^2(\\text{opening}) - r^2` while the centre is still
    free until :math:`\\tau \\approx R^2 - r^2`, so the inside is a **pocket**
    (the left kind of Figure 23.2) as long as the opening is below 90°.

    Parameters
    ----------
    radius : float
        Shell radius R in Å.
    opening : float
        Half-angle of the opening in degrees, in (0, 180).
    spacing : float
        Approximate neighbour spacing s in Å.
    atom_radius : float
    jitter : float
    seed : int or Generator

    See Also
    --------
    pockets
        Its one pocket.

    Examples
    --------
    >>> len(bowl())
    108
    """
    R = as_finite_scalar(radius, "radius", positive=True)
    op = as_finite_scalar(opening, "opening", positive=True)
    if not op < 180.0:
        raise ValueError(f"opening must be in (0, 180) degrees, got {op!r}")
    s = as_finite_scalar(spacing, "spacing", positive=True)
    r = as_finite_scalar(atom_radius, "atom_radius", nonnegative=True)
    jit = as_finite_scalar(jitter, "jitter", nonnegative=True)
    N = max(4, int(round(4 * np.pi * R * R / (np.sqrt(3.0) / 2.0 * s * s))))
    p = _fibonacci_sphere(N)
    keep = p[:, 2] < np.cos(np.radians(op))
    c = R * p[keep]
    if jit > 0:
        c = c + ball_jitter(seeded_rng(seed), len(c), jit)
    if len(c) == 0:
        raise ValueError("opening leaves no atoms")
    return Balls(c, r)


# -------------------------------------------------------------------- globule
_AMINO = (
    "ALA",
    "ARG",
    "ASN",
    "ASP",
    "CYS",
    "GLN",
    "GLU",
    "GLY",
    "HIS",
    "ILE",
    "LEU",
    "LYS",
    "MET",
    "PHE",
    "PRO",
    "SER",
    "THR",
    "TRP",
    "TYR",
    "VAL",
)
#: Protein-like heavy-atom composition (fractions), Bondi radii in Å.
_COMPOSITION = (("C", 0.62, 1.70), ("N", 0.17, 1.55), ("O", 0.19, 1.52), ("S", 0.02, 1.80))


_LAYOUT = {
    "void": (-0.35, 0.0, 0.35),
    "pocket": (0.5, 0.0, 0.35),
    "mouth": (0.0, 0.0, 1.0),
    "groove": (0.0, -0.6),
    "slit": (0.0, -1.0),
}


def _globule_geometry(
    seed, semi_axes, spacing, void_radius, pocket_radius, mouth_radius, groove_radius, slit_halfwidth, jitter
):
    """Centres, element symbols and the feature geometry of :func:`globule`."""
    rng = seeded_rng(seed)
    ax = np.asarray(semi_axes, dtype=np.float64)
    if ax.shape != (3,) or not np.all(np.isfinite(ax)) or np.any(ax <= 0):
        raise ValueError(f"semi_axes must be three positive numbers, got {semi_axes!r}")
    d = as_finite_scalar(spacing, "spacing", positive=True)
    fv = as_finite_scalar(void_radius, "void_radius", nonnegative=True)
    fp = as_finite_scalar(pocket_radius, "pocket_radius", nonnegative=True)
    fm = as_finite_scalar(mouth_radius, "mouth_radius", nonnegative=True)
    fg = as_finite_scalar(groove_radius, "groove_radius", nonnegative=True)
    fs = as_finite_scalar(slit_halfwidth, "slit_halfwidth", nonnegative=True)
    jit = as_finite_scalar(jitter, "jitter", nonnegative=True)

    # body-centred cubic lattice with nearest-neighbour distance d (cube edge 2d/√3)
    e = 2.0 * d / np.sqrt(3.0)
    k = np.ceil(ax / e).astype(int) + 1
    g = np.stack(np.meshgrid(*(np.arange(-kk, kk + 1) for kk in k), indexing="ij"), -1).reshape(-1, 3)
    lat = np.concatenate([g * e, (g + 0.5) * e])
    lat = lat[np.sum((lat / ax) ** 2, axis=1) <= 1.0]
    lat = lat[np.lexsort(lat.T[::-1])]
    n = len(lat)
    # elements, drawn once per lattice site so that carving does not reshuffle them
    sym = np.array([c[0] for c in _COMPOSITION])
    prob = np.array([c[1] for c in _COMPOSITION])
    rad = np.array([c[2] for c in _COMPOSITION])
    kind = rng.choice(len(sym), size=n, p=prob / prob.sum())
    r = rad[kind]
    pos = lat + (ball_jitter(rng, n, jit) if jit > 0 else 0.0)

    void_c = np.array(_LAYOUT["void"]) * ax
    pocket_c = np.array(_LAYOUT["pocket"]) * ax
    mouth_end = pocket_c + 2.0 * ax.max() * np.array(_LAYOUT["mouth"], dtype=np.float64)
    g0 = np.array([0.0, *_LAYOUT["groove"]]) * ax  # a point of the groove's axis (along x)
    sd = np.array([0.0, *_LAYOUT["slit"]], dtype=np.float64)
    sd /= np.linalg.norm(sd)

    remove = np.linalg.norm(pos - void_c, axis=1) < fv + r
    remove |= np.linalg.norm(pos - pocket_c, axis=1) < fp + r
    remove |= dist_segment(pos, pocket_c, mouth_end) < fm + r
    q = pos - g0
    q[:, 0] = 0.0
    remove |= np.linalg.norm(q, axis=1) < fg + r
    # the slit: the half-plane through the groove's axis spanned by x and sd
    along = q @ sd
    normal = np.linalg.norm(q - along[:, None] * sd, axis=1)
    slit = np.where(along >= 0.0, normal, np.linalg.norm(q, axis=1))
    remove |= slit < fs + r
    keep = ~remove
    features = {
        "void_center": void_c,
        "pocket_center": pocket_c,
        "mouth_axis": (pocket_c, mouth_end),
        "groove_point": g0,
        "slit_direction": sd,
    }
    return pos[keep], sym[kind[keep]], r[keep], features


def globule(
    seed: int | np.random.Generator = 0,
    *,
    semi_axes: tuple[float, float, float] = (13.0, 11.0, 10.0),
    spacing: float = 2.1,
    void_radius: float = 2.0,
    pocket_radius: float = 2.2,
    mouth_radius: float = 0.6,
    groove_radius: float = 1.5,
    slit_halfwidth: float = 0.6,
    jitter: float = 0.08,
) -> Balls:
    """A protein-like globule with a buried void, a pocket and a groove (3D, Å).

    Geometry (all carved deliberately, then documented here):

    * **Body.** A body-centred cubic (BCC) lattice with nearest-neighbour distance
      ``spacing`` = 2.1 Å, clipped to the ellipsoid with ``semi_axes`` (a, b, c) =
      (13, 11, 10) Å, each site jittered by ≤ ``jitter`` Å.  Elements are drawn with
      a protein's heavy-atom composition (C 62 %, N 17 %, O 19 %, S 2 %) and Bondi
      radii (1.70, 1.55, 1.52, 1.80 Å).  BCC is the thinnest lattice covering of
      space: every point is within 0.645·2.1 = 1.35 Å of a site, less than the
      smallest radius, so the uncarved body has no holes; and its Delaunay
      triangulation is non-degenerate.
    * **Buried void.** Around (−0.38a, 0, 0.2c) every atom i with
      :math:`\\lVert z_i - v\\rVert < f_v + r_i` is removed, leaving a free ball of
      radius ``void_radius`` = 2 Å.
    * **Pocket.** A free ball of radius ``pocket_radius`` = 2.2 Å around
      (0.38a, 0, 0.3c), joined to the outside by a free cylinder of radius
      ``mouth_radius`` = 0.6 Å along +z: a chamber with a narrow mouth, which closes
      into a void as the balls grow (the left kind of Figure 23.2).
    * **Groove.** A free cylinder of radius ``groove_radius`` = 1.5 Å along the x axis
      at (y, z) = (0, −0.65c), open at both ends, under a slit of half-width
      ``slit_halfwidth`` = 0.6 Å to the bottom surface.  When the balls grow, the slit
      closes first and the groove turns into a **tunnel** (Notes §23.1: "a groove on
      the surface of a molecule can be transformed into a tunnel").

    "Removed if closer than f + r_i" guarantees the free space contains each carved
    shape; the lattice makes the real free space a little larger.

    Parameters
    ----------
    seed : int or Generator
        Seeds the jitter and the elements.
    semi_axes, spacing, void_radius, pocket_radius, mouth_radius, groove_radius,
    slit_halfwidth, jitter
        The geometry above (Å).

    Returns
    -------
    Balls
        About 650 balls for the defaults.  :func:`globule_structure` gives the same
        atoms with elements and pseudo-residues.

    See Also
    --------
    globule_structure
        With atom labels.
    report
        Its voids and pockets.

    Examples
    --------
    >>> len(globule(seed=0))
    665
    """
    pos, _, r, _ = _globule_geometry(
        seed, semi_axes, spacing, void_radius, pocket_radius, mouth_radius, groove_radius, slit_halfwidth, jitter
    )
    return Balls(pos, r)


def globule_structure(seed: int | np.random.Generator = 0, *, residue_size: int = 8, **kwargs: float) -> PDBStructure:
    """:func:`globule` with elements, atom names and pseudo-residues, as a PDBStructure.

    The atoms are threaded into one chain by a greedy nearest-neighbour walk starting
    at the atom with the smallest x, and cut into consecutive pseudo-residues of
    ``residue_size`` atoms, named by seeded draws from the 20 amino-acid codes.  These
    are *labels*, not real amino acids: they make reports such as "lining residues"
    read like a real protein's.  Keyword arguments go to :func:`globule`.

    Returns
    -------
    shapelab.io.PDBStructure

    See Also
    --------
    globule
        The balls alone.
    example_pdb
        The same molecule as a file.

    Examples
    --------
    >>> s = globule_structure(seed=0)
    >>> len(s), s.residue_label(0)
    (665, 'A:SER1')
    """
    from .._toolkit.validate import readonly as _readonly
    from ..io import PDBStructure  # io imports balls only; no cycle

    size = as_positive_int(residue_size, "residue_size")
    defaults = dict(
        semi_axes=(13.0, 11.0, 10.0),
        spacing=2.1,
        void_radius=2.0,
        pocket_radius=2.2,
        mouth_radius=0.6,
        groove_radius=1.5,
        slit_halfwidth=0.6,
        jitter=0.08,
    )
    unknown = set(kwargs) - set(defaults)
    if unknown:
        raise TypeError(f"unexpected keyword argument(s) {sorted(unknown)}")
    defaults.update(kwargs)
    rng = seeded_rng(seed)
    pos, sym, r, _ = _globule_geometry(rng, **defaults)
    # greedy chain through the atoms
    n = len(pos)
    d2 = np.sum((pos[:, None] - pos[None]) ** 2, axis=-1)
    visited = np.zeros(n, bool)
    order = np.empty(n, np.int64)
    cur = int(np.argmin(pos[:, 0]))
    for t in range(n):
        order[t] = cur
        visited[cur] = True
        if t + 1 < n:
            row = np.where(visited, np.inf, d2[cur])
            cur = int(np.argmin(row))
    pos, sym, r = pos[order], sym[order], r[order]
    res_index = np.arange(n) // size
    res_names = np.array(_AMINO)[rng.integers(0, len(_AMINO), size=res_index[-1] + 1)]
    names = []
    counts: dict = {}
    for i in range(n):
        key = (res_index[i], sym[i])
        counts[key] = counts.get(key, 0) + 1
        names.append(f"{sym[i]}{counts[key]}")
    return PDBStructure(
        balls=Balls(pos, r),
        atom_names=_readonly(np.array(names, dtype=str)),
        residue_names=_readonly(res_names[res_index]),
        residue_numbers=_readonly((res_index + 1).astype(np.int64)),
        chains=_readonly(np.full(n, "A")),
        elements=_readonly(sym.astype(str)),
        hetero=_readonly(np.zeros(n, bool)),
        probe=0.0,
    )
