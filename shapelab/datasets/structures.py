"""The shipped structures: real proteins from the PDB, the example molecule's file, an MD
trajectory (Notes §23.1).

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

:func:`example_pdb` is the shipped file of the generated globule
(:func:`~shapelab.datasets.globule_structure`), :func:`trajectory_files` the files of
the shipped trajectory (lesson 12).
"""

from __future__ import annotations

import json
import types
from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from ..io import PDBStructure

__all__ = ["STRUCTURES", "StructureInfo", "structure", "structure_path", "trajectory_files", "example_pdb"]


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


def structure(name: str, **kwargs: Any) -> PDBStructure:
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
    from ..io import read_pdb

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

    Examples
    --------
    >>> example_pdb().name
    'globule.pdb'
    """
    return Path(str(resources.files("shapelab").joinpath("data", "globule.pdb")))
