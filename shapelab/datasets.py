"""Generated molecules and the inputs of the notes' figures (Notes §23.1).

Everything here is *generated* from documented geometry: nothing is downloaded, and
every random choice comes from a seeded :class:`numpy.random.Generator`, so the same
call gives the same balls on every machine.  Lengths are in Å for the molecules and
in arbitrary units for the 2D figure inputs.

====================  =========================================================
:func:`fullerene_c60`  the C60 cage: one void
:func:`nanotube`       an (n, m) carbon nanotube: one tunnel
:func:`bowl`           a spherical shell with a round opening: one pocket
:func:`globule`        a protein-like globule: a buried void, a pocket, a groove
:func:`ring`           a ring of disks (or balls) around one hole (tunnel)
:func:`figure_23_1`    a dozen disks whose dual complex has two triangles
:func:`figure_23_2`    the two kinds of dent of Figure 23.2
:func:`swiss_cheese`   2D disks with round holes of three sizes and a long slit
:func:`nested_pockets` 2D: a pocket with two chambers, the inner behind a neck
:func:`mixed_dent`     2D: a dent that is a pocket for one growth model only
:func:`example_pdb`    path of the shipped example PDB file (the globule)
:func:`structure`      a shipped *real* protein structure by name (see below)
:func:`trajectory_files`  a shipped MD trajectory: topology and coordinates files
====================  =========================================================

Real structures
---------------
Nine PDB files are shipped in ``shapelab/data/`` (gzip-compressed), copied once from
PyPI packages by ``course/fetch_structures.py``; :data:`STRUCTURES` records each one's
PDB id, title, what it teaches and its provenance, and :func:`structure` reads it:

===================  ======================================================
``"1hvr"``           HIV-1 protease + inhibitor: an active-site pocket
``"4ake"``, ``"1ake"``  adenylate kinase open / closed: a conformational change
``"1grm"``           gramicidin A dimer: a channel (tunnel)
``"t4l-l99a"``       T4 lysozyme L99A: an engineered buried cavity (void)
``"t4l-l99a-ligand"``  p-xylene, the ligand that fills that cavity
``"1fmo"``           protein kinase A: pockets, to compare with a peer
``"1fmo-kvfinder"``  pyKVFinder's cavities of 1fmo (grid points, not atoms)
``"3mht"``           a methyltransferase on DNA: persistence that depends on the field
===================  ======================================================

The carbon radius used throughout is Bondi's van der Waals radius of carbon, 1.70 Å
(A. Bondi, *J. Phys. Chem.* **68**, 441 (1964)); see :data:`shapelab.io.VDW_RADII`.
"""

from __future__ import annotations

import json
import types
from collections.abc import Callable
from dataclasses import dataclass
from importlib import resources
from pathlib import Path

import numpy as np

from ._toolkit.validate import as_finite_scalar, as_point, as_positive_int
from .balls import Balls

__all__ = [
    "fullerene_c60",
    "c60_edges",
    "nanotube",
    "nanotube_radius",
    "bowl",
    "globule",
    "globule_structure",
    "ring",
    "figure_23_1",
    "figure_23_2",
    "swiss_cheese",
    "nested_pockets",
    "mixed_dent",
    "example_pdb",
    "STRUCTURES",
    "StructureInfo",
    "structure",
    "structure_path",
    "trajectory_files",
    "noisy_sphere",
    "blob_curve",
    "ellipse_curve",
    "icosphere",
    "bumpy_sphere",
    "torus",
    "sample_shape",
    "shape_family",
    "GRAPHENE_LATTICE_CONSTANT",
    "CARBON_RADIUS",
]

#: The golden ratio φ = (1 + √5)/2.
PHI = (1.0 + np.sqrt(5.0)) / 2.0
#: Graphene lattice constant a = √3 · 1.42 Å ≈ 2.46 Å (the C–C bond is 1.42 Å).
GRAPHENE_LATTICE_CONSTANT = 2.46
#: Bondi's (1964) van der Waals radius of carbon, in Å.
CARBON_RADIUS = 1.70


def _rng(seed) -> np.random.Generator:
    if isinstance(seed, np.random.Generator):
        return seed
    if seed is None or isinstance(seed, (bool, np.bool_)):
        raise TypeError("seed must be an int or a numpy Generator (datasets are deterministic)")
    return np.random.default_rng(as_positive_int(seed, "seed", minimum=0))


def _cos_sin(t: np.ndarray):
    """``cos t`` and ``sin t`` rounded to multiples of :math:`2^{-32}`, the same on every
    machine.

    NumPy's trigonometric functions may differ in the last bit between CPUs (SIMD
    implementations), and the generated molecules are deliberately degenerate
    (co-circular rings, co-cylindrical tubes), where the exact triangulation follows
    those bits.  Rounding to a grid far coarser than one ulp makes the coordinates
    identical everywhere, except for a value within one ulp of a half-grid point
    (probability about :math:`2^{-20}` each); the shapes move by under
    :math:`2^{-33}` of their size.
    """
    q = 2.0**32
    return np.rint(np.cos(t) * q) / q, np.rint(np.sin(t) * q) / q


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


def fullerene_c60(*, bond_length=1.4, atom_radius=CARBON_RADIUS, jitter=0.0, seed=0) -> Balls:
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
    """
    b = as_finite_scalar(bond_length, "bond_length", positive=True)
    r = as_finite_scalar(atom_radius, "atom_radius", nonnegative=True)
    jit = as_finite_scalar(jitter, "jitter", nonnegative=True)
    c = _truncated_icosahedron() * (b / 2.0)
    if jit > 0:
        c = c + _ball_jitter(_rng(seed), len(c), jit)
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
    """
    balls = fullerene_c60() if balls is None else balls
    c = balls.centers
    d = np.linalg.norm(c[:, None] - c[None], axis=-1)
    iu = np.triu_indices(len(c), 1)
    dmin = d[iu].min()
    mask = np.abs(d[iu] - dmin) <= tol * dmin
    return np.column_stack([iu[0][mask], iu[1][mask]]).astype(np.int64)


# ------------------------------------------------------------------- nanotube
def nanotube_radius(n, m, *, a=GRAPHENE_LATTICE_CONSTANT) -> float:
    """Radius :math:`a\\sqrt{n^2 + nm + m^2}/(2\\pi)` of an (n, m) nanotube, in Å.

    See Also
    --------
    nanotube
        The tube.
    """
    n = as_positive_int(n, "n", minimum=0)
    m = as_positive_int(m, "m", minimum=0)
    a = as_finite_scalar(a, "a", positive=True)
    return a * np.sqrt(n * n + n * m + m * m) / (2 * np.pi)


def nanotube(
    n=8, m=8, *, length=12.0, atom_radius=CARBON_RADIUS, a=GRAPHENE_LATTICE_CONSTANT, slit=0.0, jitter=0.0, seed=0
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
    cos_t, sin_t = _cos_sin(theta)
    centers = np.column_stack([R * cos_t, R * sin_t, v])
    if len(centers) == 0:
        raise ValueError(f"length={L} is too short to hold a ring of atoms")
    jit = as_finite_scalar(jitter, "jitter", nonnegative=True)
    if jit > 0:
        centers = centers + _ball_jitter(_rng(seed), len(centers), jit)
    return Balls(centers, r)


# ----------------------------------------------------------------------- bowl
def _fibonacci_sphere(N: int) -> np.ndarray:
    i = np.arange(N)
    z = 1.0 - (2.0 * i + 1.0) / N
    phi = i * np.pi * (3.0 - np.sqrt(5.0))  # the golden angle
    s = np.sqrt(1.0 - z * z)
    cos_p, sin_p = _cos_sin(phi)
    return np.column_stack([s * cos_p, s * sin_p, z])


def bowl(*, radius=6.0, opening=50.0, spacing=2.0, atom_radius=CARBON_RADIUS, jitter=0.0, seed=0) -> Balls:
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
        c = c + _ball_jitter(_rng(seed), len(c), jit)
    if len(c) == 0:
        raise ValueError("opening leaves no atoms")
    return Balls(c, r)


def _ball_jitter(rng: np.random.Generator, n: int, amount: float, dim: int = 3) -> np.ndarray:
    """n vectors uniform in the ball of radius ``amount``."""
    v = rng.normal(size=(n, dim))
    v /= np.linalg.norm(v, axis=1, keepdims=True)
    return v * (amount * rng.random(n) ** (1.0 / dim))[:, None]


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


def _dist_segment(p: np.ndarray, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    ab = b - a
    t = np.clip(((p - a) @ ab) / (ab @ ab), 0.0, 1.0)
    return np.linalg.norm(p - (a + t[:, None] * ab), axis=1)


# feature positions as fractions of the semi-axes; mouth and slit are directions
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
    rng = _rng(seed)
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
    pos = lat + (_ball_jitter(rng, n, jit) if jit > 0 else 0.0)

    void_c = np.array(_LAYOUT["void"]) * ax
    pocket_c = np.array(_LAYOUT["pocket"]) * ax
    mouth_end = pocket_c + 2.0 * ax.max() * np.array(_LAYOUT["mouth"], dtype=np.float64)
    g0 = np.array([0.0, *_LAYOUT["groove"]]) * ax  # a point of the groove's axis (along x)
    sd = np.array([0.0, *_LAYOUT["slit"]], dtype=np.float64)
    sd /= np.linalg.norm(sd)

    remove = np.linalg.norm(pos - void_c, axis=1) < fv + r
    remove |= np.linalg.norm(pos - pocket_c, axis=1) < fp + r
    remove |= _dist_segment(pos, pocket_c, mouth_end) < fm + r
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
    seed=0,
    *,
    semi_axes=(13.0, 11.0, 10.0),
    spacing=2.1,
    void_radius=2.0,
    pocket_radius=2.2,
    mouth_radius=0.6,
    groove_radius=1.5,
    slit_halfwidth=0.6,
    jitter=0.08,
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
    """
    pos, _, r, _ = _globule_geometry(
        seed, semi_axes, spacing, void_radius, pocket_radius, mouth_radius, groove_radius, slit_halfwidth, jitter
    )
    return Balls(pos, r)


def globule_structure(seed=0, *, residue_size=8, **kwargs):
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
    """
    from ._toolkit.validate import readonly as _readonly
    from .io import PDBStructure  # io imports balls only; no cycle

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
    rng = _rng(seed)
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


def example_pdb() -> Path:
    """Path of ``shapelab/data/globule.pdb``, the shipped example molecule.

    It was written by ``python -m course.example_pdb``, i.e. by
    :func:`shapelab.io.write_pdb` from ``globule_structure(seed=0)`` (coordinates
    rounded to 0.001 Å, the PDB's precision).  Read it with
    ``shapelab.read_pdb(example_pdb())``.

    See Also
    --------
    read_pdb
        Reads it.
    globule_structure
        The same molecule.
    """
    return Path(str(resources.files("shapelab").joinpath("data", "globule.pdb")))


# ----------------------------------------------------------------- 2D figures
def ring(n=12, *, radius=3.0, disk_radius=1.0, dim=2) -> Balls:
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
    """
    n = as_positive_int(n, "n", minimum=3)
    R = as_finite_scalar(radius, "radius", positive=True)
    r = as_finite_scalar(disk_radius, "disk_radius", nonnegative=True)
    if dim not in (2, 3) or isinstance(dim, bool):
        raise ValueError(f"dim must be 2 or 3, got {dim!r}")
    t = 2 * np.pi * np.arange(n) / n
    cos_t, sin_t = _cos_sin(t)
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


def _hex_disk(radius: float, spacing: float) -> np.ndarray:
    """Points of the triangular lattice (spacing s) inside a disk."""
    k = int(np.ceil(radius / spacing)) + 2
    j, i = np.meshgrid(np.arange(-k, k + 1), np.arange(-k, k + 1), indexing="ij")
    x = (i + 0.5 * (j % 2)) * spacing
    y = j * spacing * np.sqrt(3.0) / 2.0
    p = np.column_stack([x.ravel(), y.ravel()])
    p = p[np.hypot(p[:, 0], p[:, 1]) <= radius + 1e-12]
    return p[np.lexsort((p[:, 0], p[:, 1]))]


def figure_23_2(*, body_radius=6.0, spacing=1.0, disk_radius=0.65):
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
    """
    R = as_finite_scalar(body_radius, "body_radius", positive=True)
    s = as_finite_scalar(spacing, "spacing", positive=True)
    r = as_finite_scalar(disk_radius, "disk_radius", positive=True)
    p = _hex_disk(R, s)
    chamber = np.array([0.0, 2.5 * s])
    flask = (np.hypot(*(p - chamber).T) < 2.0 * s) | (
        _dist_segment(
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


def swiss_cheese(*, spacing=1.0, disk_radius=0.65):
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


def nested_pockets(*, disk_radius=0.65):
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
    """
    r = as_finite_scalar(disk_radius, "disk_radius", positive=True)
    p = _hex_disk(8.0, 1.0)
    x, y = p[:, 0], p[:, 1]
    remove = np.hypot(x, y - 4.5) < 2.25
    remove |= np.hypot(x, y + 1.5) < 2.85
    remove |= (np.abs(x) <= 0.5 + 1e-9) & (y >= 4.5)
    remove |= (np.abs(x) <= 1.0 + 1e-9) & (y >= -1.5) & (y <= 4.5)
    return Balls(p[~remove], r)


def mixed_dent(*, small_radius=0.3, big_radius=3.0, bowl_radius=3.0, gap=3.6):
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
    """
    rs = as_finite_scalar(small_radius, "small_radius", positive=True)
    rb = as_finite_scalar(big_radius, "big_radius", positive=True)
    rho = as_finite_scalar(bowl_radius, "bowl_radius", positive=True)
    g = as_finite_scalar(gap, "gap", positive=True)
    n = int(round(np.pi * rho / 0.45)) + 1
    ang = np.linspace(np.pi, 2 * np.pi, n)
    small = np.column_stack(_cos_sin(ang)) * rho
    big = np.array([[-(g / 2 + rb), 1.0], [g / 2 + rb, 1.0]])
    return Balls(np.vstack([small, big]), np.r_[np.full(n, rs), np.full(2, rb)])


# ----------------------------------------------------------- real structures
@dataclass(frozen=True)
class StructureInfo:
    """One shipped real structure and where it came from (``shapelab/data/STRUCTURES.json``).

    Attributes
    ----------
    name : str
        The key of :data:`STRUCTURES` and the argument of :func:`structure`.
    pdb_id : str
        The PDB entry (``pdb_id_certain`` False when it is inferred, not stated).
    title, header_title : str
        A short title, and the title the file's own header gives (or why it has none).
    teaches : str
        What the course shows with it.
    ligands, modified_residues : tuple of str
        Residue names of HETATM groups that are a ligand, or part of the chain.
    file : str
        The shipped file in ``shapelab/data/`` (gzip-compressed).
    source : dict
        ``package``, ``version``, ``archive`` (the file pip downloaded), ``path`` (inside
        the package) and ``package_license``.
    sha256, sha256_original : str
        Of the shipped file, and of the package's file (= the uncompressed bytes).
    size, size_original : int
        In bytes.
    atoms : dict
        ATOM/HETATM record counts of the first model: ``records``, ``hetatm``,
        ``hydrogens``, ``water``.
    differs_from_pdb : bool
    differences, evidence : str
        How the file differs from the PDB's own entry, and how that is known.
    read : dict
        Keyword arguments :func:`structure` passes to :func:`shapelab.io.read_pdb`.

    See Also
    --------
    structure
        Reads the structure.
    structure_path
        Its path.
    """

    name: str
    pdb_id: str
    title: str
    header_title: str
    teaches: str
    ligands: tuple
    modified_residues: tuple
    file: str
    source: dict
    sha256: str
    sha256_original: str
    size: int
    size_original: int
    atoms: dict
    differs_from_pdb: bool
    differences: str
    evidence: str
    read: dict
    pdb_id_certain: bool = True


def _load_structures():
    text = resources.files("shapelab").joinpath("data", "STRUCTURES.json").read_text(encoding="utf-8")
    out = {}
    for e in json.loads(text)["structures"]:
        e = dict(e)
        e["ligands"] = tuple(e["ligands"])
        e["modified_residues"] = tuple(e["modified_residues"])
        for k in ("source", "atoms", "read"):
            e[k] = types.MappingProxyType(dict(e[k]))
        out[e["name"]] = StructureInfo(**e)
    return types.MappingProxyType(out)


#: The shipped real structures by name (read-only): each a :class:`StructureInfo`.
STRUCTURES = _load_structures()


def structure_path(name: str) -> Path:
    """Path of the shipped file of structure ``name`` (a key of :data:`STRUCTURES`).

    See Also
    --------
    structure
        Reads it.
    StructureInfo
        Where it came from.

    Examples
    --------
    >>> structure_path("1grm").name
    '1grm_single.pdb.gz'
    """
    if not isinstance(name, str):
        raise TypeError(f"name must be a str, got {type(name).__name__}")
    info = STRUCTURES.get(name.strip().lower())
    if info is None:
        raise ValueError(f"no shipped structure {name!r}; choose one of {sorted(STRUCTURES)}")
    return Path(str(resources.files("shapelab").joinpath("data", info.file)))


def structure(name: str, **kwargs):
    """Read a shipped real structure by name (Notes §23.1: a molecule as balls).

    Parameters
    ----------
    name : str
        A key of :data:`STRUCTURES`: ``"1hvr"``, ``"4ake"``, ``"1ake"``, ``"1grm"``,
        ``"t4l-l99a"``, ``"t4l-l99a-ligand"``, ``"1fmo"``, ``"1fmo-kvfinder"``, ``"3mht"``.
    **kwargs
        Passed to :func:`shapelab.io.read_pdb` (``probe``, ``chain``, ``hetatm``,
        ``water``, ``hydrogens``, ``radii``, ...), over the entry's own defaults
        (``STRUCTURES[name].read``; only ``"1fmo-kvfinder"`` has one, ``hydrogens=True``,
        since its points are written as hydrogens).

    Returns
    -------
    shapelab.io.PDBStructure
        By default heavy atoms only, without water, HETATM groups included.

    See Also
    --------
    read_pdb
        The reader used.
    structure_path
        The shipped file.

    Examples
    --------
    >>> s = structure("t4l-l99a", probe=1.4)
    >>> len(s), s.residue_label(0), float(s.balls.radii[0])
    (1290, ':MET1', 2.95)
    >>> STRUCTURES["1ake"].pdb_id, STRUCTURES["1ake"].source["package"]
    ('1AKE', 'MDAnalysisTests')
    """
    from .io import read_pdb

    path = structure_path(name)
    options = dict(STRUCTURES[name.strip().lower()].read)
    options.update(kwargs)
    return read_pdb(path, **options)


def trajectory_files(name: str = "adk-dims") -> tuple[Path, Path]:
    """The files of a shipped molecular-dynamics trajectory: (topology, trajectory) paths.

    One trajectory is shipped, ``"adk-dims"``: adenylate kinase of *E. coli* going from
    its closed to its open conformation along a DIMS transition path (dynamic importance
    sampling, a biased simulation that is pushed towards the target, not equilibrium
    dynamics; Beckstein et al. 2009).  It is every 4th of the 98 frames of
    ``adk_dims.dcd`` of MDAnalysisTests 2.11.0 (shipped frame *i* is source frame 4*i*),
    heavy atoms only (1656), coordinates as the source stores them: a gzipped PDB
    topology (elements added) and a DCD.  How it was made and the sha256 of the source
    and shipped files: ``STRUCTURES.json["trajectories"]`` (``course/fetch_trajectories.py``).
    Read it with :func:`shapelab.trajectory_measures` (Notes §23.1), which needs MDAnalysis.

    Parameters
    ----------
    name : str, default "adk-dims"
        The trajectory.

    Returns
    -------
    tuple of Path
        The topology (``.pdb.gz``) and the trajectory (``.dcd``).

    Raises
    ------
    TypeError
        ``name`` is not a str.
    ValueError
        No shipped trajectory has that name.

    See Also
    --------
    shapelab.trajectory_measures
        Measures it frame by frame.
    structure
        The shipped single structures (``"1ake"`` closed, ``"4ake"`` open).

    References
    ----------
    .. [1] O. Beckstein, E. J. Denning, J. R. Perilla, T. B. Woolf, "Zipping and unzipping of
       adenylate kinase: atomistic insights into the ensemble of open↔closed transitions",
       *J. Mol. Biol.* **394**, 160–176 (2009), doi:10.1016/j.jmb.2009.09.009.

    Examples
    --------
    >>> top, traj = trajectory_files("adk-dims")
    >>> top.name, traj.name
    ('adk_dims_heavy.pdb.gz', 'adk_dims_heavy.dcd')
    """
    if not isinstance(name, str):
        raise TypeError(f"name must be a str, got {type(name).__name__}")
    text = resources.files("shapelab").joinpath("data", "STRUCTURES.json").read_text(encoding="utf-8")
    found = {e["name"]: e for e in json.loads(text).get("trajectories", [])}
    entry = found.get(name.strip().lower())
    if entry is None:
        raise ValueError(f"no shipped trajectory {name!r}; choose one of {sorted(found)}")
    data = resources.files("shapelab").joinpath("data")
    return tuple(Path(str(data.joinpath(entry["files"][k]))) for k in ("topology", "trajectory"))


def noisy_sphere(n: int, *, noise: float = 0.01, center=(0.0, 0.0, 0.0), seed=0) -> np.ndarray:
    """``n`` points of the unit sphere (uniform directions) plus isotropic Gaussian
    noise of standard deviation ``noise``, moved to ``center``; deterministic in
    ``seed``.  The data of the benchmarks and of lesson 14.

    See Also
    --------
    shapelab.diagrams.bottleneck_distance
        Compare the diagrams of noisy samples.
    """
    n = as_positive_int(n, "n")
    noise = as_finite_scalar(noise, "noise", nonnegative=True)
    c = np.asarray(center, dtype=float)
    if c.shape != (3,) or not np.all(np.isfinite(c)):
        raise ValueError(f"center must be a finite 3-vector, got {center!r}")
    rng = np.random.default_rng(seed)
    x = rng.standard_normal((n, 3))
    x /= np.linalg.norm(x, axis=1, keepdims=True)
    return x + noise * rng.standard_normal((n, 3)) + c


# --------------------------------------------------------------------------- curves and meshes
# (critical points, lessons 13 and 14)
def ellipse_curve(a: float = 2.0, b: float = 1.0, center=(0.0, 0.0)) -> Callable:
    """The ellipse ``t -> center + (a cos t, b sin t)`` as a vectorised function.

    See Also
    --------
    shapelab.critical.polyline
        Samples it.
    critical_points
        Its critical points.
    """
    a = as_finite_scalar(a, "a", positive=True)
    b = as_finite_scalar(b, "b", positive=True)
    c = as_point(center, "center", dim=2)

    def fn(t):
        t = np.asarray(t, dtype=float)
        return np.array([c[0] + a * np.cos(t), c[1] + b * np.sin(t)])

    return fn


def blob_curve(t):
    """A smooth star-shaped closed curve like the one of Figure 23.3.

    ``r(t) = 1 + 0.25 cos 3t + 0.12 sin(2t + 0.6)`` in polar coordinates about
    the origin; vectorised: returns ``(x, y)``.  Seen from S = (0.1, 0.05) it has
    three minima and three maxima.

    See Also
    --------
    shapelab.critical.polyline
        Samples it.
    critical_points
        Its critical points.
    """
    t = np.asarray(t, dtype=float)
    r = 1.0 + 0.25 * np.cos(3 * t) + 0.12 * np.sin(2 * t + 0.6)
    return np.array([r * np.cos(t), r * np.sin(t)])


def icosphere(subdivisions: int = 2, radius: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """A triangulated sphere: the icosahedron, each triangle split in 4
    ``subdivisions`` times, vertices pushed to the sphere.

    Returns ``(vertices, faces)`` with ``10 * 4**s + 2`` vertices and
    ``20 * 4**s`` outward-oriented triangles.

    See Also
    --------
    bumpy_sphere
        A sphere with bumps.
    shapelab.critical.euler_characteristic
        χ = 2.
    """
    subdivisions = as_positive_int(subdivisions, "subdivisions", minimum=0)
    if subdivisions > 7:
        raise ValueError(f"subdivisions must be at most 7 (>{10 * 4**7} vertices), got {subdivisions}")
    radius = as_finite_scalar(radius, "radius", positive=True)
    p = (1.0 + np.sqrt(5.0)) / 2.0
    V = np.array(
        [
            [-1, p, 0],
            [1, p, 0],
            [-1, -p, 0],
            [1, -p, 0],
            [0, -1, p],
            [0, 1, p],
            [0, -1, -p],
            [0, 1, -p],
            [p, 0, -1],
            [p, 0, 1],
            [-p, 0, -1],
            [-p, 0, 1],
        ],
        dtype=float,
    )
    F = np.array(
        [
            [0, 11, 5],
            [0, 5, 1],
            [0, 1, 7],
            [0, 7, 10],
            [0, 10, 11],
            [1, 5, 9],
            [5, 11, 4],
            [11, 10, 2],
            [10, 7, 6],
            [7, 1, 8],
            [3, 9, 4],
            [3, 4, 2],
            [3, 2, 6],
            [3, 6, 8],
            [3, 8, 9],
            [4, 9, 5],
            [2, 4, 11],
            [6, 2, 10],
            [8, 6, 7],
            [9, 8, 1],
        ],
        dtype=np.intp,
    )
    V /= np.linalg.norm(V, axis=1, keepdims=True)
    for _ in range(subdivisions):
        e = np.concatenate([F[:, [0, 1]], F[:, [1, 2]], F[:, [2, 0]]])
        e.sort(axis=1)
        uniq, inv = np.unique(e, axis=0, return_inverse=True)
        inv = inv.ravel()
        mid = V[uniq[:, 0]] + V[uniq[:, 1]]
        mid /= np.linalg.norm(mid, axis=1, keepdims=True)
        m = V.shape[0] + inv.reshape(3, -1)  # midpoints of edges 01, 12, 20 of each face
        a, b, c = F[:, 0], F[:, 1], F[:, 2]
        F = np.concatenate(
            [
                np.stack([a, m[0], m[2]], 1),
                np.stack([b, m[1], m[0]], 1),
                np.stack([c, m[2], m[1]], 1),
                np.stack([m[0], m[1], m[2]], 1),
            ]
        )
        V = np.vstack([V, mid])
    return radius * V, F


def bumpy_sphere(
    subdivisions: int = 3, *, bumps: int = 6, amplitude: float = 0.3, seed=0
) -> tuple[np.ndarray, np.ndarray]:
    """An icosphere pushed radially by ``bumps`` random Gaussian bumps and dents:
    a closed star-shaped surface with several minima, maxima and saddles.

    Returns ``(vertices, faces)``; deterministic in ``seed``.

    See Also
    --------
    icosphere
        The smooth sphere.
    critical_points
        Its critical points.
    """
    bumps = as_positive_int(bumps, "bumps", minimum=0)
    amplitude = as_finite_scalar(amplitude, "amplitude", nonnegative=True)
    if amplitude >= 1:
        raise ValueError(f"amplitude must be below 1 (the surface must stay star-shaped), got {amplitude}")
    V, F = icosphere(subdivisions)
    rng = np.random.default_rng(seed)
    centers = rng.standard_normal((bumps, 3))
    centers /= np.linalg.norm(centers, axis=1, keepdims=True)
    heights = rng.uniform(-1.0, 1.0, bumps)
    widths = rng.uniform(0.25, 0.6, bumps)
    r = np.ones(V.shape[0])
    for c, h, w in zip(centers, heights, widths):
        r += amplitude * h * np.exp(-np.sum((V - c) ** 2, axis=1) / (2 * w * w))
    r = np.clip(r, 0.1, None)
    return V * r[:, None], F


def torus(n_major: int = 24, n_minor: int = 12, *, R: float = 1.0, r: float = 0.4) -> tuple[np.ndarray, np.ndarray]:
    """A triangulated torus (χ = 0) around the z axis: ``n_major * n_minor``
    vertices, ``2 * n_major * n_minor`` triangles.

    See Also
    --------
    icosphere
        A sphere.
    shapelab.critical.euler_characteristic
        χ = 0.
    """
    n_major = as_positive_int(n_major, "n_major", minimum=3)
    n_minor = as_positive_int(n_minor, "n_minor", minimum=3)
    R = as_finite_scalar(R, "R", positive=True)
    r = as_finite_scalar(r, "r", positive=True)
    if r >= R:
        raise ValueError(f"r must be smaller than R for an embedded torus, got r={r}, R={R}")
    u = np.arange(n_major) * (2.0 * np.pi / n_major)
    v = np.arange(n_minor) * (2.0 * np.pi / n_minor)
    U, W = np.meshgrid(u, v, indexing="ij")
    V = np.stack([(R + r * np.cos(W)) * np.cos(U), (R + r * np.cos(W)) * np.sin(U), r * np.sin(W)], -1).reshape(-1, 3)
    i, j = np.meshgrid(np.arange(n_major), np.arange(n_minor), indexing="ij")
    a = i * n_minor + j
    b = ((i + 1) % n_major) * n_minor + j
    c = ((i + 1) % n_major) * n_minor + (j + 1) % n_minor
    d = i * n_minor + (j + 1) % n_minor
    F = np.concatenate([np.stack([a, b, c], -1).reshape(-1, 3), np.stack([a, c, d], -1).reshape(-1, 3)])
    return V, F


# --------------------------------------------------------------------------- shapes for ICP (lesson 15)
def sample_shape(kind: str, n: int, *, seed: int = 0) -> np.ndarray:
    """Random points on a closed test surface, for ICP demos, tests and benchmarks.

    Parameters
    ----------
    kind : {"lumpy", "ellipsoid", "sphere", "cube", "torus"}
        ``"lumpy"``: an ellipsoid with semi-axes (1, 0.75, 0.55) carrying five bumps
        of different sizes in asymmetric directions — no symmetry at all, so ICP has
        a unique answer.  ``"ellipsoid"``: the same ellipsoid without bumps (three
        mirror planes, 4 rotational symmetries).  ``"sphere"``: the unit sphere (every
        rotation is a symmetry).  ``"cube"``: the surface of the cube [-1, 1]³
        (24 rotational symmetries), uniformly.  ``"torus"``: the torus of radii 1 and
        0.4 about the z axis, with both angles uniform (denser on the inner side).
    n : int
        Number of points.
    seed : int
        Seed of :func:`numpy.random.default_rng`; two different seeds give two
        independent samplings of the same surface.

    Returns
    -------
    ndarray, shape (n, 3)
        For the smooth shapes the direction from the origin is uniform on the sphere
        (not uniform in area); the cube is uniform in area.

    See Also
    --------
    icp
        Registers sampled shapes.
    shape_family
        Shapes in classes.
    """
    if not isinstance(kind, str):
        raise TypeError(f"kind must be a string, got {type(kind).__name__}")
    n = as_positive_int(n, "n")
    rng = np.random.default_rng(seed)
    if kind == "torus":
        u, v = rng.uniform(0.0, 2.0 * np.pi, (2, n))
        ring = 1.0 + 0.4 * np.cos(v)
        return np.column_stack([ring * np.cos(u), ring * np.sin(u), 0.4 * np.sin(v)])
    if kind == "cube":
        face = rng.integers(0, 6, n)
        p = rng.uniform(-1.0, 1.0, (n, 3))
        axis = face % 3
        p[np.arange(n), axis] = np.where(face < 3, 1.0, -1.0)
        return p
    u = rng.normal(size=(n, 3))
    u /= np.linalg.norm(u, axis=1, keepdims=True)
    if kind == "sphere":
        return u
    semi = np.array([1.0, 0.75, 0.55])
    if kind == "ellipsoid":
        return u * semi
    if kind == "lumpy":
        centres = np.array([[1, 0.3, 0.2], [-0.4, 1, 0.5], [0.2, -0.6, 1], [-1, -0.5, -0.3], [0.5, 0.4, -1]], float)
        centres /= np.linalg.norm(centres, axis=1, keepdims=True)
        height = np.array([0.35, 0.25, 0.3, 0.15, 0.2])
        width = np.array([0.15, 0.25, 0.1, 0.3, 0.2])
        rho = 1.0 + (height * np.exp((u @ centres.T - 1.0) / width)).sum(axis=1)
        return u * rho[:, None] * semi
    raise ValueError(f"kind must be one of 'lumpy', 'ellipsoid', 'sphere', 'cube', 'torus'; got {kind!r}")


def shape_family(
    kinds=("sphere", "ellipsoid", "cube", "torus"), per_class: int = 5, n: int = 400, *, noise=0.02, seed=0
):
    """A family of sampled shapes in classes, for shape classification (lesson 19).

    Each member is :func:`sample_shape` of its kind with its own sampling, turned by a
    random rotation, scaled by a factor in [0.95, 1.05] and moved by Gaussian noise of
    standard deviation ``noise``; deterministic in ``seed``.

    Returns
    -------
    shapes : list of ndarray, shape (n, 3)
    labels : list of str
        The kind of each shape; members of one class are contiguous.

    See Also
    --------
    sample_shape
        One shape.
    shapelab.diagrams.distance_matrix
        Compares the family's diagrams.
    """
    from .quaternion import Quaternion

    if isinstance(kinds, str) or not kinds:
        raise TypeError("kinds must be a non-empty sequence of shape kinds")
    per_class = as_positive_int(per_class, "per_class")
    n = as_positive_int(n, "n", minimum=4)
    noise = as_finite_scalar(noise, "noise", nonnegative=True)
    rng = _rng(seed)
    shapes, labels = [], []
    for kind in kinds:
        for _ in range(per_class):
            X = sample_shape(kind, n, seed=int(rng.integers(2**31)))
            q = Quaternion(*rng.normal(size=4))
            X = q.rotate(X) * rng.uniform(0.95, 1.05) + noise * rng.normal(size=X.shape)
            shapes.append(X)
            labels.append(str(kind))
    return shapes, labels
