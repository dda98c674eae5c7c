"""shapelab.trajectory: per-frame measures of an MD trajectory and cavity tracking.

Oracles: each frame written to PDB by MDAnalysis and read back by shapelab.read_pdb
(radii from the PDB path, measured by union_measure), jobs=2 against jobs=1, a
synthetic bowl whose pocket closes into a void by construction, and hand-made
linings with known Jaccard indices.  Skips cleanly without MDAnalysis or the corpus.
"""

from __future__ import annotations

import tarfile
import warnings
from pathlib import Path

import numpy as np
import pytest

import shapelab
from shapelab.tools.trajectory import trajectory_measures
from shapelab.tracking import selection_radii, track_cavities

ROOT = Path(__file__).resolve().parents[2]
ARCHIVE = ROOT / ".cache" / "corpus" / "archives" / "mdanalysistests-2.11.0.tar.gz"
DATA = "mdanalysistests-2.11.0/MDAnalysisTests/data/"
ADK = ("adk.psf", "adk_dims.dcd")


# ---------------------------------------------------------------- tracking alone
def test_track_cavities_follows_the_largest_overlap():
    # frame 1: {2,3,4} has J = 2/4 = 0.5 with {1,2,3} (continues at the threshold),
    # {7,8} is new; frame 2: {7,8,9} has J = 2/3 with {7,8}; {1,2,3} came back but its
    # track ended (J with {2,3,4} = 0.5, so it continues track 0 instead).
    ids, ov = track_cavities([[[1, 2, 3]], [[2, 3, 4], [7, 8]], [[7, 8, 9], [1, 2, 3]]])
    assert ids == [[0], [0, 1], [1, 0]]
    assert ov[1][0] == 0.5 and np.isnan(ov[1][1]) and ov[2][0] == pytest.approx(2 / 3)


def test_track_cavities_threshold_and_one_to_one():
    # J({1,2,3}, {3,4,5}) = 1/5 < 0.5: a new track.
    assert track_cavities([[[1, 2, 3]], [[3, 4, 5]]])[0] == [[0], [1]]
    assert track_cavities([[[1, 2, 3]], [[3, 4, 5]]], min_overlap=0.2)[0] == [[0], [0]]
    # A split: both halves overlap the parent; the larger overlap continues it.
    ids, _ = track_cavities([[[1, 2, 3, 4, 5, 6]], [[1, 2], [3, 4, 5, 6]]], min_overlap=0.3)
    assert ids == [[0], [1, 0]]
    # An empty frame ends every track.
    assert track_cavities([[[1, 2]], [], [[1, 2]]])[0] == [[0], [], [1]]


@pytest.mark.parametrize("bad", [0, 1.5, -0.1, float("nan")])
def test_track_cavities_rejects_bad_threshold(bad):
    with pytest.raises(ValueError, match="min_overlap"):
        track_cavities([[[1]]], min_overlap=bad)


def test_without_mdanalysis_the_error_names_the_extra(monkeypatch):
    import sys

    monkeypatch.setitem(sys.modules, "MDAnalysis", None)  # import MDAnalysis now raises ImportError
    with pytest.raises(ImportError, match=r"shapelab\[md\]"):
        trajectory_measures("adk.psf", "adk.dcd", progress=False)


# ---------------------------------------------------------------- with MDAnalysis
try:
    import MDAnalysis as mda
except ImportError:  # the optional extra shapelab[md] is not installed
    mda = None


def _need_mdanalysis():
    if mda is None:
        pytest.skip('MDAnalysis is not installed (pip install "shapelab[md]")')


def bowl_coordinates(n=240, R=6.0, openings=(60, 30, 0, 60, 0)):
    """A spherical shell of ``n`` atoms squeezed into polar angles [a, 180°]: a bowl
    whose opening half-angle is ``a`` (0: the closed shell).  Grown, a bowl's mouth
    (a circle of radius R sin a) seals before its inside (radius R) fills: a pocket
    (Notes §23.1, Figure 23.2); the closed shell holds a void."""
    k = np.arange(n) + 0.5
    theta = np.arccos(1 - 2 * k / n)
    phi = np.pi * (1 + 5**0.5) * k
    frames = []
    for a in openings:
        t0 = np.radians(a)
        th = t0 + theta * (np.pi - t0) / np.pi
        frames.append(R * np.c_[np.sin(th) * np.cos(phi), np.sin(th) * np.sin(phi), np.cos(th)])
    return np.array(frames, dtype=np.float32)


def universe(coords, names="C", resname="BWL", element=None):
    from MDAnalysis.coordinates.memory import MemoryReader

    n = coords.shape[1]
    u = mda.Universe.empty(n, n_residues=1, atom_resindex=np.zeros(n, int), trajectory=True)
    u.add_TopologyAttr("names", [names] * n)
    u.add_TopologyAttr("resnames", [resname])
    if element is not None:
        u.add_TopologyAttr("elements", [element] * n)
    u.load_new(coords, format=MemoryReader)
    return u


@pytest.fixture(scope="module")
def bowl():
    _need_mdanalysis()
    u = universe(bowl_coordinates())
    return u, trajectory_measures(u, select="all", probe=0.0, progress=False)


def test_bowl_pocket_narrows_then_closes_into_a_void(bowl):
    _, r = bowl
    assert r.n_pockets.tolist() == [1, 1, 0, 1, 0]
    assert r.n_voids.tolist() == [0, 0, 1, 0, 1]
    # The closed shell's void holds the ball of radius R - r = 4.3 about the centre
    # (no atom reaches it) and lies in the ball of radius R = 6.
    assert 4 / 3 * np.pi * 4.3**3 < r.largest_void[2] < 4 / 3 * np.pi * 6.0**3
    assert r.largest_void[2] == r.largest_void[4]  # the same coordinates
    assert r.largest_void[[0, 1, 3]].tolist() == [0, 0, 0]
    # one cavity, lined by every atom, followed through closing and reopening
    assert len(r.tracks) == 1
    t = r.tracks[0]
    assert t.frames == (0, 1, 2, 3, 4)
    assert t.kinds == ("pocket", "pocket", "void", "pocket", "void")
    assert t.overlaps == (1.0, 1.0, 1.0, 1.0)
    assert all(c.lining.tolist() == list(range(240)) for cs in r.cavities for c in cs)
    # the pocket's free volume grows as its mouth narrows (the same atoms enclose more)
    assert t.volumes[0] < t.volumes[1]


def test_bowl_track_ends_when_the_cavity_is_gone():
    _need_mdanalysis()
    # frame 1 is the closed shell at a distance: lined by other atoms (a second shell)
    c = bowl_coordinates(openings=(0, 0))
    two = np.concatenate([c, c + np.float32(40.0)], axis=1)
    two[1, :240] = two[0, 240:] + np.float32(80.0)  # frame 1: the first shell moves away too
    r = trajectory_measures(universe(two), select="all", probe=0.0, progress=False)
    assert r.n_voids.tolist() == [2, 2]
    assert len(r.tracks) == 2 and [t.frames for t in r.tracks] == [(0, 1), (0, 1)]


def test_bowl_measures_equal_union_measure(bowl):
    u, r = bowl
    c = bowl_coordinates()
    for f in range(len(c)):
        m = shapelab.union_measure(shapelab.Balls(c[f].astype(np.float64), np.full(c.shape[1], 1.7)))
        assert r.volume[f] == pytest.approx(m.measure, rel=1e-12)
        assert r.area[f] == pytest.approx(m.boundary, rel=1e-12)
    assert r.frame.tolist() == [0, 1, 2, 3, 4] and r.n_atoms == c.shape[1]


def test_bowl_parallel_equals_serial(bowl):
    u, r = bowl
    r2 = trajectory_measures(u, select="all", probe=0.0, progress=False, jobs=2)
    assert r2.rows() == r.rows() and r2.tracks == r.tracks
    for a, b in zip(r.cavities, r2.cavities):
        assert [(c.kind, c.track, c.volume, c.lining.tolist()) for c in a] == [
            (c.kind, c.track, c.volume, c.lining.tolist()) for c in b
        ]


def test_progress_goes_to_stderr_only(bowl, capsys):
    u, r = bowl
    p = trajectory_measures(u, select="all", probe=0.0, stop=2)
    out, err = capsys.readouterr()
    assert out == "" and "2/2" in err
    assert p.volume.tolist() == r.volume[:2].tolist()


def test_step_and_stop_pick_frames(bowl):
    u, r = bowl
    s = trajectory_measures(u, select="all", probe=0.0, progress=False, start=1, stop=5, step=2)
    assert s.frame.tolist() == [1, 3]
    assert s.volume.tolist() == [r.volume[1], r.volume[3]]


@pytest.mark.parametrize(
    ("kwargs", "exc", "word"),
    [
        ({"probe": -1.0}, ValueError, "probe"),
        ({"probe": "1.4"}, TypeError, "probe"),
        ({"step": 0}, ValueError, "step"),
        ({"jobs": 0}, ValueError, "jobs"),
        ({"jobs": 1.5}, TypeError, "jobs"),
        ({"min_overlap": 0.0}, ValueError, "min_overlap"),
        ({"min_overlap": 2.0}, ValueError, "min_overlap"),
        ({"select": 3}, TypeError, "select"),
        ({"select": "index 0"}, ValueError, "select"),
        ({"progress": "yes"}, TypeError, "progress"),
        ({"trajectory": "x.dcd"}, TypeError, "trajectory"),
    ],
)
def test_bad_arguments_name_themselves(bowl, kwargs, exc, word):
    u, _ = bowl
    kw = {"select": "all", "progress": False} | kwargs
    with pytest.raises(exc, match=word):
        trajectory_measures(u, **kw)


def test_bad_topology_and_unknown_element(bowl):
    _need_mdanalysis()
    with pytest.raises(TypeError, match="topology"):
        trajectory_measures(42, progress=False)
    u = universe(bowl_coordinates()[:1], names="PM", resname="PM", element="Pm")  # no table lists Pm
    with pytest.raises(ValueError, match=r"element 'Pm'\) has no van der Waals.*Alvarez's \(2013\).*default_radius"):
        trajectory_measures(u, select="all", progress=False)
    r = trajectory_measures(u, select="all", progress=False, probe=0.0, default_radius=1.7)
    assert r.volume[0] == pytest.approx(bowl[1].volume[0], rel=1e-12)
    # iron, in neither Bondi's nor Mantina et al.'s table, takes Alvarez's (2013) 2.44 Å
    u = universe(bowl_coordinates()[:1], names="FE", resname="HEM", element="Fe")
    assert selection_radii(u.atoms, default_radius=1.7).tolist() == [2.44] * 240
    # without elements, a name is read as a PDB reader reads it: " OG1" is oxygen (1.52 Å)
    u = universe(bowl_coordinates()[:1], names="OG1", resname="SER")
    r = trajectory_measures(u, select="all", progress=False, probe=0.0)
    m = shapelab.union_measure(shapelab.Balls(bowl_coordinates()[0].astype(np.float64), np.full(240, 1.52)))
    assert r.volume[0] == pytest.approx(m.measure, rel=1e-12)


# ---------------------------------------------------------------- adenylate kinase
@pytest.fixture(scope="module")
def adk(tmp_path_factory):
    _need_mdanalysis()
    if not ARCHIVE.exists():
        pytest.skip(f"the corpus archive {ARCHIVE.name} is not fetched (python -m course.fetch_corpus)")
    d = tmp_path_factory.mktemp("adk")
    with tarfile.open(ARCHIVE) as tar:
        for name in ADK:
            member = tar.getmember(DATA + name)
            (d / name).write_bytes(tar.extractfile(member).read())
    return tuple(str(d / n) for n in ADK)


def _quiet():
    # MDAnalysis' DCD reader announces a change of behaviour in 3.0 (DeprecationWarning);
    # its PDB writer warns that the PSF has no elements (read_pdb reads them from names)
    warnings.simplefilter("ignore", DeprecationWarning)
    warnings.simplefilter("ignore", UserWarning)


@pytest.fixture(scope="module")
def adk_measures(adk):
    with warnings.catch_warnings():
        _quiet()
        return trajectory_measures(*adk, stop=60, step=30, progress=False)


def test_adk_frames_equal_a_pdb_round_trip(adk, adk_measures, tmp_path):
    r = adk_measures
    assert r.frame.tolist() == [0, 30]
    with warnings.catch_warnings():
        _quiet()
        u = mda.Universe(*adk)
        atoms = u.select_atoms("protein and not name H*")
        for i, f in enumerate(r.frame):
            u.trajectory[int(f)]
            path = tmp_path / f"adk_{f}.pdb"
            atoms.write(str(path))
            s = shapelab.read_pdb(path, probe=1.4)
            x = atoms.positions.astype(np.float64)
            assert len(s) == len(atoms) == r.n_atoms
            assert s.atom_names.tolist() == [n.strip() for n in atoms.names]
            assert set(s.elements.tolist()) == {"C", "N", "O", "S"}
            # the radii of the PDB path, at the trajectory's own coordinates: exact
            m = shapelab.union_measure(shapelab.Balls(x, s.balls.radii))
            assert r.volume[i] == pytest.approx(m.measure, rel=1e-12)
            assert r.area[i] == pytest.approx(m.boundary, rel=1e-12)
            # the PDB's own balls (coordinates rounded to 0.001 Å)
            m = shapelab.union_measure(s.balls)
            assert r.volume[i] == pytest.approx(m.measure, rel=1e-4)
            assert r.area[i] == pytest.approx(m.boundary, rel=1e-4)
            assert r.n_voids[i] == len(shapelab.voids(shapelab.Balls(x, s.balls.radii)))
    assert r.time[1] - r.time[0] == pytest.approx(30 * u.trajectory.dt, rel=1e-6)


def test_adk_parallel_equals_serial(adk, adk_measures):
    with warnings.catch_warnings():
        _quiet()
        r2 = trajectory_measures(*adk, stop=60, step=30, progress=False, jobs=2)
    assert r2.rows() == adk_measures.rows() and r2.tracks == adk_measures.tracks
