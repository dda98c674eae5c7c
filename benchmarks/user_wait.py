"""What a user waits for (issue 25, item 3): a lesson's first cells, one CLI report, a batch.

    python -m benchmarks.user_wait                 # all -> benchmarks/results/user_wait.md (+ .json)
    python -m benchmarks.user_wait --only lessons  # lessons, cli, batch, importtime (any of them)

Every figure but the batch's is the median of ``--repeats`` (at least 5) FRESH processes,
timed from outside (the wall time of the whole process: interpreter start, imports, work,
exit), because that is what a user waits for:

* **lessons**: the first two code cells of each lesson (the imports cell, then the first
  cell that computes: "import plus first call"), run by a fresh ``python`` (not a
  Jupyter kernel: kernel start-up is Jupyter's, not ours, and is the same for every
  lesson) in the lessons folder, with IPython's line magics (``%matplotlib inline``)
  dropped, the Agg backend, ``display`` from IPython, and every open figure rendered to
  PNG at the end of each cell as the inline backend does.  Inside the process the
  imports cell (matplotlib, ipywidgets, numpy, scipy included: the cell imports them)
  and the first call are timed apart, and one more run under ``-X importtime`` splits
  each cell's import time by package (:func:`_by_package`).
* **cli**: ``python -m shapelab report shapelab/data/1FMO.pdb.gz`` into a temporary folder.
* **batch**: :func:`shapelab.report_batch` over 100 real structures (:func:`batch_files`:
  the 86 complexes of ``benchmarks/data/pockets``, the other real proteins shipped in
  ``shapelab/data`` and ``tests/data``, then chains of the verification corpus),
  ``hetatm=False``, ``jobs=1`` and ``jobs=2``, ``--batch-repeats`` fresh processes each
  (default 3; each is 100 reports): the wall time, per structure (wall / 100), when the
  first report was written (import and warm-up included), each structure's own time
  (first, and the median of the other 99) and the peak memory; then the peer in one
  process on the same balls: freesasa Lee–Richards (100 slices) beside our
  ``union_measure``, per structure, one thread each.
* **importtime**: ``python -X importtime`` of ``import shapelab`` and of the first geometry
  call (``sl.union_measure`` on 1hvr): the 10 entries with the largest cumulative time,
  the 10 with the largest own time, and the time by package (one run: a profile, not a
  benchmark).

The machine is named as in the other results (:func:`benchmarks.harness.machine`) with
the 1-minute load average before and after each part (the 2 cores are shared).
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
DATA = ROOT / "shapelab" / "data"
PARTS = ("lessons", "cli", "batch", "importtime")
BATCH_SIZE = 100
POCKETS = ROOT / "benchmarks" / "data" / "pockets"
TESTS_DATA = ROOT / "tests" / "data"
CORPUS = ROOT / ".cache" / "corpus" / "files"
#: the real proteins of shapelab/data that the pocket set does not hold already (by PDB id); the
#: KVFinder output, the ligand alone, the synthetic globule and the DCD's topology are left out
SHIPPED = (
    "1FMO.pdb.gz",
    "1grm_single.pdb.gz",
    "adk_closed.pdb.gz",
    "adk_open.pdb.gz",
    "t4l_l99a_receptor.pdb.gz",
)
#: tests/data structures the pocket set does not hold (1fbl and 2W83 are in it)
TESTS = ("3ny7A.pdb.gz", "cobrotoxin.pdb.gz")
#: fill-ins from the verification corpus (``python -m course.fetch_corpus``): MDAnalysisTests' DSSP
#: chains, in name order, but the two test fixtures and what is already in the list
CORPUS_SKIP = ("1mr1D_failing", "wrong_hydrogens", "3ny7A")
PROBE = 1.4

#: run by the fresh python of a lesson: cells as JSON in argv[1]; prints the in-process times
_CELLS = r"""
import json, sys, time
t_start = time.perf_counter()
from IPython.display import display  # a kernel has IPython; matplotlib comes with the cells (MPLBACKEND=Agg)
ns = {"display": display, "__name__": "__main__"}
times = []
for k, src in enumerate(json.loads(sys.argv[1])):
    print(f"@@cell {k}", file=sys.stderr, flush=True)  # splits a -X importtime profile by cell
    code = "\n".join(ln for ln in src.splitlines() if not ln.lstrip().startswith(("%", "!")))
    t = time.perf_counter()
    exec(compile(code, "<cell>", "exec"), ns)
    if "matplotlib.pyplot" in sys.modules:  # the inline backend renders each figure
        import io
        import matplotlib.pyplot as plt
        for num in plt.get_fignums():
            plt.figure(num).savefig(io.BytesIO(), format="png")
        plt.close("all")
    times.append(time.perf_counter() - t)
print(json.dumps({"cells": times, "in_process": time.perf_counter() - t_start}))
"""


def _env() -> dict:
    return dict(os.environ, PYTHONPATH=str(ROOT), MPLBACKEND="Agg", PYTHONHASHSEED="0")


def _timed(cmd, *, cwd=None, extra=None) -> tuple[float, str]:
    """Wall time of one fresh process (and its stdout); a failure raises with its stderr."""
    t = time.perf_counter()
    r = subprocess.run(cmd, cwd=cwd, env=dict(_env(), **(extra or {})), capture_output=True, text=True)
    wall = time.perf_counter() - t
    if r.returncode != 0:
        raise RuntimeError(f"{' '.join(map(str, cmd[:4]))} failed:\n{r.stderr[-1500:]}")
    return wall, r.stdout


def _first_cells(path: Path, n: int = 2) -> list[str]:
    import nbformat

    nb = nbformat.read(path, as_version=4)
    return [c.source for c in nb.cells if c.cell_type == "code"][:n]


#: the packages a lesson's imports are split into (each with what it pulled in itself)
GROUPS = ("matplotlib", "ipywidgets", "numpy", "scipy", "shapelab")


def _import_tree(lines: list[str]) -> list[tuple[int, int, str]]:
    """``-X importtime`` lines -> (self µs, depth, module) in the order Python printed them
    (post-order: a module after everything it imported)."""
    entries = []
    for ln in lines:
        if not ln.startswith("import time:") or "cumulative" in ln:
            continue
        _, self_us, _cum, name = (x for x in ln.replace("import time:", "|").split("|"))
        entries.append((int(self_us), (len(name) - len(name.lstrip(" "))) // 2, name.strip()))
    return entries


def _by_package(entries) -> dict[str, float]:
    """Import time (ms) by package: each module's own time goes to the top-level package
    of its outermost ancestor (itself included) outside shapelab, or to ``shapelab`` when
    every ancestor is shapelab's; so ``from shapelab import plot`` counts matplotlib and
    everything matplotlib imports as matplotlib, and the groups add up to the total."""
    out: dict[str, float] = {}
    stack: list[str] = []
    for self_us, depth, name in reversed(entries):  # reversed post-order: parents first
        del stack[depth:]
        stack.append(name)
        outside = [m.split(".")[0] for m in stack if m.split(".")[0] != "shapelab"]
        group = outside[0] if outside else "shapelab"
        out[group] = out.get(group, 0.0) + self_us / 1000
    return out


def _lesson_profile(cells: str, cwd: Path) -> list[dict[str, float]]:
    """One ``-X importtime`` run of a lesson's cells: the import time (ms) of each cell by package."""
    r = subprocess.run(
        [sys.executable, "-X", "importtime", "-c", _CELLS, cells], cwd=cwd, env=_env(), capture_output=True, text=True
    )
    if r.returncode != 0:
        return []
    per_cell: list[list[str]] = []
    for ln in r.stderr.splitlines():
        if ln.startswith("@@cell "):
            per_cell.append([])
        elif per_cell:
            per_cell[-1].append(ln)
    return [_by_package(_import_tree(lines)) for lines in per_cell]


def lessons(repeats: int, only=None) -> list[dict]:
    rows = []
    for path in sorted((ROOT / "lessons").glob("[0-9][0-9]_*.ipynb")):
        if only and path.name[:2] not in only:
            continue
        cells = json.dumps(_first_cells(path))
        walls, imports, calls = [], [], []
        error = None
        for _ in range(repeats):
            try:
                wall, out = _timed([sys.executable, "-c", _CELLS, cells], cwd=path.parent)
            except RuntimeError as err:
                error = str(err).splitlines()[-1][:200]
                break
            inner = json.loads(out.strip().splitlines()[-1])
            walls.append(wall)
            imports.append(inner["cells"][0])
            calls.append(inner["cells"][1] if len(inner["cells"]) > 1 else 0.0)
        row = {"lesson": path.stem, "runs": len(walls), "error": error}
        if walls:
            row |= {
                "wall_s": statistics.median(walls),
                "import_cell_s": statistics.median(imports),
                "first_call_s": statistics.median(calls),
                "import_ms_by_package": _lesson_profile(cells, path.parent),
            }
        rows.append(row)
        print(f"  {path.stem}: {row.get('wall_s', float('nan')):.2f} s {error or ''}", file=sys.stderr)
    return rows


def cli(repeats: int) -> dict:
    walls = []
    for _ in range(repeats):
        with tempfile.TemporaryDirectory() as tmp:
            wall, _ = _timed([sys.executable, "-m", "shapelab", "report", str(DATA / "1FMO.pdb.gz")], cwd=tmp)
            walls.append(wall)
    return {
        "command": "python -m shapelab report shapelab/data/1FMO.pdb.gz",
        "runs": repeats,
        "wall_s": statistics.median(walls),
        "all_s": walls,
    }


def batch_files() -> list[tuple[str, Path]]:
    """The 100 structures of the batch, in a fixed order, as (source, path): the 86
    complexes of ``benchmarks/data/pockets`` (manifest order, i.e. by id), the real
    proteins of ``shapelab/data`` and ``tests/data`` they do not hold (:data:`SHIPPED`,
    :data:`TESTS`), then MDAnalysisTests' DSSP chains from the verification corpus in
    name order (:data:`CORPUS_SKIP` left out) up to :data:`BATCH_SIZE`.  Without the
    corpus on disk the list is filled by taking the pocket set again from its start,
    under other names (the table says so)."""
    manifest = json.loads((POCKETS / "manifest.json").read_text(encoding="utf-8"))
    files = [("pockets", POCKETS / e["file"]) for e in manifest["structures"]]
    files += [("shapelab/data", DATA / name) for name in SHIPPED]
    files += [("tests/data", TESTS_DATA / name) for name in TESTS]
    dssp = CORPUS / "mdanalysistests" / "dssp"
    if dssp.is_dir():
        for f in sorted(dssp.glob("*.pdb")):
            if len(files) >= BATCH_SIZE:
                break
            if f.name.split(".")[0] not in CORPUS_SKIP:
                files.append(("corpus", f))
    k = 0
    while len(files) < BATCH_SIZE:  # no corpus: the pocket set again (copied under new names)
        files.append(("pockets (again)", files[k][1]))
        k += 1
    return files[:BATCH_SIZE]


#: the batch in one fresh process: report_batch with the progress lines timestamped
#: (they come as each structure is done), then the rows' seconds and the peak memory
_BATCH = r"""
import json, resource, sys, time
t0 = time.perf_counter()
done = []

class Stamp:
    def write(self, text):
        done.extend(time.perf_counter() - t0 for ln in text.splitlines() if "/" in ln and "  " in ln)
        return len(text)
    def flush(self):
        pass
    def isatty(self):
        return False

paths, out, jobs = json.loads(sys.argv[1]), sys.argv[2], int(sys.argv[3])
import shapelab
t_import = time.perf_counter() - t0
err, sys.stderr = sys.stderr, Stamp()
try:
    s = shapelab.report_batch(paths, out=out, jobs=jobs, progress=True, hetatm=False)
finally:
    sys.stderr = err
kib = 1024 if sys.platform == "darwin" else 1  # ru_maxrss: bytes on macOS, KiB on Linux
print(json.dumps({
    "elapsed": time.perf_counter() - t0,
    "import_shapelab": t_import,
    "done_at": done,
    "seconds": list(s["seconds"]),
    "status": list(s["status"]),
    "atoms": list(s["atoms"]),
    "error": list(s["error"]),
    "peak_main_mib": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / kib / 1024,
    "peak_worker_mib": resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / kib / 1024,
}))
"""

#: the peer on the same structures in one fresh process: each file read by shapelab (the
#: same SA balls: Bondi radii + probe), then freesasa Lee-Richards (100 slices, one thread,
#: vdW radii and the probe) and our union_measure on those balls, interleaved
_PEER = r"""
import json, resource, sys, time
t0 = time.perf_counter()
import freesasa
t_import_peer = time.perf_counter() - t0
import numpy as np
from shapelab import union_measure
from shapelab.io import read_structure
t_import_ours = time.perf_counter() - t0 - t_import_peer
freesasa.setVerbosity(freesasa.silent)
probe = float(sys.argv[2])
params = freesasa.Parameters({"algorithm": freesasa.LeeRichards, "n-slices": 100, "probe-radius": probe, "n-threads": 1})
rows = []
for path in json.loads(sys.argv[1]):
    t = time.perf_counter()
    s = read_structure(path, hetatm=False)
    t_read = time.perf_counter() - t
    centers = np.ascontiguousarray(s.balls.centers, dtype=np.float64)
    vdw = s.balls.radii - probe
    t = time.perf_counter()
    peer = freesasa.calcCoord(centers.ravel(), vdw, params).totalArea()
    t_peer = time.perf_counter() - t
    t = time.perf_counter()
    ours = union_measure(s.balls).surface_area
    t_ours = time.perf_counter() - t
    rows.append({"atoms": len(s.balls), "read": t_read, "peer": t_peer, "ours": t_ours,
                 "rel_err": abs(peer - ours) / ours})
print(json.dumps({"elapsed": time.perf_counter() - t0, "import_peer": t_import_peer,
                  "import_ours": t_import_ours, "rows": rows,
                  "peak_mib": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024}))
"""


#: the first structure's report twice in one fresh process (in a temporary folder): the
#: first call pays the imports and first-use caches (the warm-up), the second does not
_WARMUP = r"""
import json, sys, time
import shapelab  # the lazy export map alone: what the batch's caller has imported too
times = []
for _ in range(2):
    t = time.perf_counter()
    rep = shapelab.report(shapelab.read_structure(sys.argv[1], hetatm=False), float(sys.argv[2]))
    rep.write(".", "first")
    times.append(time.perf_counter() - t)
print(json.dumps({"cold": times[0], "warm": times[1]}))
"""


def warmup(path: str, repeats: int) -> dict:
    """The first structure's report, cold (imports and warm-up included) and warm, in
    ``repeats`` fresh processes (medians): what the first row of a batch pays extra."""
    cold, warm, load0 = [], [], os.getloadavg()[0]
    for _ in range(repeats):
        with tempfile.TemporaryDirectory() as tmp:
            _, out = _timed([sys.executable, "-c", _WARMUP, path, str(PROBE)], cwd=tmp)
        r = json.loads(out.strip().splitlines()[-1])
        cold.append(r["cold"])
        warm.append(r["warm"])
    return {
        "file": str(Path(path).relative_to(ROOT)),
        "runs": repeats,
        "cold_s": statistics.median(cold),
        "warm_s": statistics.median(warm),
        "load": f"{load0:.2f} / {os.getloadavg()[0]:.2f}",
    }


def _stats(xs: list[float]) -> dict:
    return {"first_s": xs[0], "median_rest_s": statistics.median(xs[1:]), "sum_s": sum(xs)}


def batch(repeats: int, jobs=(1, 2)) -> dict:
    """``report_batch`` over :func:`batch_files`, ``jobs`` 1 and 2, each ``repeats``
    fresh processes (interleaved), then the peer's process on the same files."""
    files = batch_files()
    paths = [str(p) for _, p in files]
    runs = {j: [] for j in jobs}
    loads = [os.getloadavg()[0]]
    with tempfile.TemporaryDirectory() as tmp:
        src = Path(tmp) / "in"  # the inputs under unique names: report_batch refuses two stems alike
        src.mkdir()
        inputs = []
        for k, p in enumerate(paths):
            q = src / f"{k:03d}_{Path(p).name}"
            os.symlink(p, q)
            inputs.append(str(q))
        arg = json.dumps(inputs)
        for _ in range(repeats):
            for j in jobs:
                out = Path(tmp) / "out"
                shutil.rmtree(out, ignore_errors=True)
                out.mkdir()
                wall, stdout = _timed([sys.executable, "-c", _BATCH, arg, str(out), str(j)], cwd=tmp)
                inner = json.loads(stdout.strip().splitlines()[-1])
                ok = inner["status"].count("ok")
                if ok != BATCH_SIZE:
                    bad = [(p, e) for p, st, e in zip(paths, inner["status"], inner["error"]) if st != "ok"]
                    raise RuntimeError(f"batch jobs={j}: {ok} of {BATCH_SIZE} structures ok; {bad[:3]}")
                startup = wall - inner["elapsed"]  # interpreter start before the script's first line
                runs[j].append(
                    {
                        "wall_s": wall,
                        "first_done_s": startup + inner["done_at"][0],
                        "import_shapelab_s": startup + inner["import_shapelab"],
                        "row_seconds": inner["seconds"],
                        "peak_main_mib": inner["peak_main_mib"],
                        "peak_worker_mib": inner["peak_worker_mib"] if j > 1 else None,
                    }
                )
                loads.append(os.getloadavg()[0])
                print(
                    f"  batch jobs={j}: {wall:.1f} s, first done at {runs[j][-1]['first_done_s']:.2f} s, "
                    f"load {loads[-1]:.1f}",
                    file=sys.stderr,
                )
        atoms = inner["atoms"]
        first = warmup(paths[0], max(repeats, 3))
        one = {"SHAPELAB_THREADS": "1", "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}
        wall, stdout = _timed([sys.executable, "-c", _PEER, json.dumps(paths), str(PROBE)], cwd=tmp, extra=one)
        peer = json.loads(stdout.strip().splitlines()[-1])
        loads.append(os.getloadavg()[0])
    rows = []
    for j in jobs:
        rs = runs[j]
        w = statistics.median(r["wall_s"] for r in rs)
        # per structure inside the batch: the rows' own seconds (read, compute, write), medians over the runs
        per = [statistics.median(r["row_seconds"][i] for r in rs) for i in range(BATCH_SIZE)]
        rows.append(
            {
                "jobs": j,
                "runs": len(rs),
                "wall_s": w,
                "all_s": [r["wall_s"] for r in rs],
                "per_structure_s": w / BATCH_SIZE,
                "first_done_s": statistics.median(r["first_done_s"] for r in rs),
                "import_shapelab_s": statistics.median(r["import_shapelab_s"] for r in rs),
                "rows": _stats(per),
                "peak_main_mib": max(r["peak_main_mib"] for r in rs),
                "peak_worker_mib": max(r["peak_worker_mib"] for r in rs) if j > 1 else None,
            }
        )
    pr = peer["rows"]
    return {
        "files": [{"source": src, "file": str(p.relative_to(ROOT)), "atoms": n} for (src, p), n in zip(files, atoms)],
        "atoms_total": sum(atoms),
        "atoms_median": statistics.median(atoms),
        "probe": PROBE,
        "first_structure": first,
        "jobs": rows,
        "peer": {
            "wall_s": wall,
            "import_peer_s": peer["import_peer"],
            "import_ours_s": peer["import_ours"],
            "read": _stats([r["read"] for r in pr]),
            "freesasa": _stats([r["peer"] for r in pr]),
            "ours_union_measure": _stats([r["ours"] for r in pr]),
            "ratio_median": statistics.median(r["ours"] / r["peer"] for r in pr),
            "ratio_sum": sum(r["ours"] for r in pr) / sum(r["peer"] for r in pr),
            "rel_err_max": max(r["rel_err"] for r in pr),
            "peak_mib": peer["peak_mib"],
        },
        "loads": [round(x, 2) for x in loads],
    }


_FIRST_CALL = "import shapelab as sl; sl.union_measure(sl.datasets.structure('1hvr').balls)"


def importtime(top: int = 10) -> dict:
    """``-X importtime`` of ``import shapelab`` and of the first geometry call: the
    modules with the largest cumulative time (top level of each import chain, i.e. what
    the statement itself pulled in), and which heavy packages were imported at all."""
    out = {}
    for label, code in (("import shapelab", "import shapelab"), ("first geometry call", _FIRST_CALL)):
        code += "; import sys, json; print(json.dumps(sorted(m for m in sys.modules if '.' not in m)))"
        t = time.perf_counter()
        r = subprocess.run([sys.executable, "-X", "importtime", "-c", code], env=_env(), capture_output=True, text=True)
        wall = time.perf_counter() - t
        entries = []
        for ln in r.stderr.splitlines():
            if not ln.startswith("import time:") or "cumulative" in ln:
                continue
            _, self_us, cum_us, name = (x for x in ln.replace("import time:", "|").split("|"))
            depth = (len(name) - len(name.lstrip(" "))) // 2
            entries.append((int(cum_us), int(self_us), depth, name.strip()))
        roots = sorted((e for e in entries if e[2] <= 1), reverse=True)[:top]
        selfs = sorted(entries, key=lambda e: -e[1])[:top]
        mods = json.loads(r.stdout.strip().splitlines()[-1])
        heavy = [
            m
            for m in (
                "numpy",
                "scipy",
                "matplotlib",
                "gemmi",
                "ipywidgets",
                "tqdm",
                "MDAnalysis",
                "dask",
                "gudhi",
                "freesasa",
                "pandas",
                "pyarrow",
            )
            if m in mods
        ]
        out[label] = {
            "wall_s": wall,
            "total_ms": sum(e[0] for e in entries if e[2] == 0) / 1000,
            "top": [{"module": n, "cumulative_ms": c / 1000, "self_ms": s / 1000, "depth": d} for c, s, d, n in roots],
            "top_self": [
                {"module": n, "cumulative_ms": c / 1000, "self_ms": s / 1000, "depth": d} for c, s, d, n in selfs
            ],
            "heavy_imported": heavy,
            "ms_by_package": _by_package([(s_, d, n) for _, s_, d, n in entries]),
        }
    return out


def _batch_markdown(b: dict, load: str) -> list[str]:
    from collections import Counter

    by_source = Counter(f["source"] for f in b["files"])
    names = {}
    for f in b["files"]:
        names.setdefault(f["source"], []).append(Path(f["file"]).name.split(".")[0])
    n = len(b["files"])
    L = [
        f"## A batch of {n} structures (load {load}; sampled {', '.join(map(str, b['loads']))})",
        "",
        f"`shapelab.report_batch(paths, out=tmp, jobs=J, hetatm=False)` (the polymer alone, as "
        "`benchmarks/pocket_sites.py` reads these complexes: with their HETATM records six of them stop at a "
        f"metal ion without a Bondi radius; otherwise the defaults: probe {b['probe']} Å, ranked pockets, every "
        "file written) over "
        + ", ".join(f"{n} from {src}" for src, n in by_source.items())
        + f": {b['atoms_total']:,} atoms read (median {b['atoms_median']:,.0f} per structure).  "
        f"One fresh process per run (jobs 1 and 2 interleaved); *per structure* is the batch's wall time / {n}; "
        "*first done* is when the first structure's report was written, counted from the process start "
        "(interpreter, `import shapelab`, the imports of the first report and its warm-up); *row* times are "
        "each structure's own `seconds` in the summary (read, compute, write; medians over the runs).  Peak "
        "memory: the largest resident set of the calling process and of any worker (`getrusage`).",
        "",
        f"| jobs | runs | batch (s) | per structure (s) | first done (s) | first row (s) | median of the other {n - 1} rows (s) "
        "| peak main (MiB) | peak worker (MiB) |",
        "|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
    ]
    for r in b["jobs"]:
        worker = f"{r['peak_worker_mib']:.0f}" if r["peak_worker_mib"] else "–"
        L.append(
            f"| {r['jobs']} | {r['runs']} | {r['wall_s']:.1f} | {r['per_structure_s']:.3f} | {r['first_done_s']:.2f} "
            f"| {r['rows']['first_s']:.2f} | {r['rows']['median_rest_s']:.3f} | {r['peak_main_mib']:.0f} | {worker} |"
        )
    if b.get("first_structure"):
        f = b["first_structure"]
        L += [
            "",
            f"**The first structure's warm-up**: `shapelab.report` of {Path(f['file']).name.split('.')[0]} (and "
            f"its files written) twice in one fresh process: {f['cold_s']:.2f} s the first time (the lazy imports "
            f"of numpy, scipy and the report's modules, and first-use caches), {f['warm_s']:.2f} s the second "
            f"(median of {f['runs']} processes): the import and warm-up cost "
            f"{f['cold_s'] - f['warm_s']:.2f} s once per process (once per worker with jobs > 1)"
            + (f"; load {f['load']}." if f.get("load") else "."),
        ]
    p = b["peer"]
    L += [
        "",
        "**The peer on the same structures**, one fresh process, in order: each file read by "
        "`shapelab.io.read_structure(path, hetatm=False)` (the same SA balls: Bondi radii, probe 1.4 Å), then freesasa's "
        "Lee–Richards (100 slices, one thread, `calcCoord` with the vdW radii and the probe) and our "
        f"`union_measure` on the same balls (exact area and volume); one thread each (`SHAPELAB_THREADS=1`, `OMP_NUM_THREADS=1`).  Process "
        f"{p['wall_s']:.1f} s; `import freesasa` {p['import_peer_s'] * 1000:.0f} ms, then numpy + "
        f"`shapelab.union_measure` + `shapelab.io` {p['import_ours_s'] * 1000:.0f} ms; peak {p['peak_mib']:.0f} MiB.",
        "",
        f"| per structure | first (s) | median of the other {n - 1} (s) | sum of {n} (s) |",
        "|---|---:|---:|---:|",
    ]
    for key, label in (
        ("read", "read the file (`shapelab.io.read_structure`)"),
        ("freesasa", "freesasa LR-100 area"),
        ("ours_union_measure", "shapelab `union_measure` (exact)"),
    ):
        x = p[key]
        L.append(f"| {label} | {x['first_s']:.3f} | {x['median_rest_s']:.4f} | {x['sum_s']:.2f} |")
    L += [
        "",
        f"Ours / freesasa: median over the structures {p['ratio_median']:.2f}, sum over sum {p['ratio_sum']:.2f}; "
        f"largest relative difference of the areas {p['rel_err_max']:.1e} (LR-100's error).  The whole report "
        f"per structure (the batch's rows above) is what a user of `report_batch` waits for; freesasa computes "
        "the area alone.",
        "",
        f"<details><summary>The {n} structures</summary>",
        "",
    ]
    L += [f"- {src} ({len(ns)}): {', '.join(ns)}" for src, ns in names.items()]
    L += ["", "</details>", ""]
    return L


def _markdown(doc) -> str:
    L = [
        "# What a user waits for (issue 25, item 3)",
        "",
        "`python -m benchmarks.user_wait` (run "
        + "; ".join(f"{part} {r['when']} UTC at shapelab commit {r['commit']}" for part, r in doc["runs"].items())
        + "; raw numbers in `user_wait.json`).  Every time is the median of fresh processes, timed from outside "
        "(interpreter start to exit), but the import profiles (one run each).  The 1-minute load average is "
        "given before / after each part: the machine's 2 cores are shared, so read the ratios of figures "
        "taken in the same part.",
        "",
        doc["machine"],
        "",
    ]
    if "lessons" in doc:
        L += [
            f"## The first cells of each lesson (load {doc['load']['lessons']})",
            "",
            "The lesson's first two code cells (the imports, then the first cell that computes) in a fresh "
            "`python` started in `lessons/` (not a Jupyter kernel; IPython magics dropped, Agg backend, each "
            "open figure rendered to PNG after its cell as the inline backend does).  *import cell* and "
            "*first call* are timed inside the process; *total* is the whole process.",
            "",
            "The *import cell* includes everything the cell imports: numpy, matplotlib (through `from shapelab "
            "import plot` or directly), ipywidgets (through `shapelab.widgets`), scipy.  Its split by package "
            "comes from one more run of the same cells under `python -X importtime` (which adds its own "
            "overhead: read the shares, not the sums): each module's own time is counted under the "
            "outermost package outside shapelab that imported it, so *matplotlib* holds what matplotlib "
            "pulled in (PIL, kiwisolver, ...) and *shapelab* only shapelab's own modules.  *imports in first "
            "call* is the import time of the second cell (what the first call imported lazily).",
            "",
            "| lesson | runs | total (s) | import cell (s) | matplotlib (ms) | ipywidgets (ms) | numpy (ms) "
            "| scipy (ms) | shapelab (ms) | other (ms) | first call (s) | imports in first call (ms) |",
            "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|",
        ]
        for r in doc["lessons"]:
            if r.get("error"):
                L.append(f"| {r['lesson']} | {r['runs']} | failed: {r['error']} |" + " |" * 9)
                continue
            prof = r.get("import_ms_by_package") or []
            cell0 = prof[0] if prof else {}
            groups = [f"{cell0.get(g, 0.0):.0f}" if prof else "?" for g in GROUPS]
            rest = {k: v for k, v in cell0.items() if k not in GROUPS}
            other = f"{sum(rest.values()):.0f}" if prof else "?"
            big = max(rest.items(), key=lambda kv: kv[1], default=None)
            if big and big[1] >= 100:
                other += f" ({big[0]} {big[1]:.0f})"
            later = f"{sum(prof[1].values()):.0f}" if len(prof) > 1 else "?"
            L.append(
                f"| {r['lesson']} | {r['runs']} | {r['wall_s']:.2f} | {r['import_cell_s']:.2f} | "
                + " | ".join(groups)
                + f" | {other} | {r['first_call_s']:.2f} | {later} |"
            )
        L.append("")
    if "cli" in doc:
        c = doc["cli"]
        L += [
            f"## One report from the command line (load {doc['load']['cli']})",
            "",
            f"`{c['command']}` in a temporary folder: **{c['wall_s']:.2f} s** (median of {c['runs']}; "
            f"all: {', '.join(f'{x:.2f}' for x in c['all_s'])}).",
            "",
        ]
    if "batch" in doc and "jobs" in doc["batch"]:
        L += _batch_markdown(doc["batch"], doc["load"]["batch"])
    if "importtime" in doc:
        L += ["## Import profile (`python -X importtime`, one run)", ""]
        for label, p in doc["importtime"].items():
            L += [
                f"**{label}**: process {p['wall_s']:.2f} s, imports {p['total_ms']:.0f} ms; heavy packages imported: "
                f"{', '.join(p['heavy_imported']) or 'none'}."
                + (
                    "  By package (as in the lessons' split): "
                    + ", ".join(
                        f"{k} {v:.0f} ms" for k, v in sorted(p["ms_by_package"].items(), key=lambda kv: -kv[1])[:6]
                    )
                    + "."
                    if p.get("ms_by_package")
                    else ""
                ),
                "",
                "| module (top two levels; the 10 largest cumulative) | cumulative (ms) | self (ms) |",
                "|---|---:|---:|",
            ]
            L += [
                f"| {'&nbsp;&nbsp;' * e['depth']}{e['module']} | {e['cumulative_ms']:.1f} | {e['self_ms']:.1f} |"
                for e in p["top"]
            ]
            L.append("")
            if p.get("top_self"):
                L += [
                    f"The {len(p['top_self'])} most expensive imports by their own time (without what they import):",
                    "",
                    "| module | self (ms) | cumulative (ms) |",
                    "|---|---:|---:|",
                ]
                L += [f"| {e['module']} | {e['self_ms']:.1f} | {e['cumulative_ms']:.1f} |" for e in p["top_self"]]
                L.append("")
    return "\n".join(L) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--only", nargs="*", choices=PARTS, default=list(PARTS))
    ap.add_argument("--lessons", nargs="*", default=None, help="lesson numbers (default: all)")
    ap.add_argument("--repeats", type=int, default=5, help="fresh processes per figure (at least 5)")
    ap.add_argument(
        "--batch-repeats",
        type=int,
        default=3,
        help="fresh batch processes per jobs value (default 3: each is 100 reports; the per-structure "
        "figures are medians over the structures)",
    )
    ap.add_argument("--out", type=Path, default=ROOT / "benchmarks" / "results" / "user_wait.md")
    args = ap.parse_args(argv)
    if args.repeats < 5:
        ap.error("--repeats must be at least 5 (medians of at least 5 fresh processes)")
    from benchmarks.harness import machine, machine_line

    commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True, text=True)
    doc = {
        "machine": machine_line(machine()),
        "when": time.strftime("%Y-%m-%d %H:%M", time.gmtime()),
        "commit": commit.stdout.strip() or "?",
        "repeats": args.repeats,
        "load": {},
        "runs": {},
    }
    notes = ""
    if set(args.only) != set(PARTS):  # a partial run updates its parts and keeps the others (and the notes)
        doc, notes = _previous(args.out, doc, args.only)
    steps = {
        "lessons": lambda: lessons(args.repeats, {n.zfill(2) for n in args.lessons} if args.lessons else None),
        "cli": lambda: cli(args.repeats),
        "batch": lambda: batch(args.batch_repeats),
        "importtime": importtime,
    }
    for part in PARTS:
        if part in args.only:
            print(f"[user_wait] {part}", file=sys.stderr)
            load0 = os.getloadavg()[0]
            doc[part] = steps[part]()
            doc["load"][part] = f"{load0:.2f} / {os.getloadavg()[0]:.2f}"
            doc["runs"][part] = {"when": time.strftime("%Y-%m-%d %H:%M", time.gmtime()), "commit": doc["commit"]}
            _save(doc, args.out, notes)  # after each part: an interrupted run keeps what it measured
    print(_markdown(doc))
    return 0


#: where the hand-written notes of a results file begin (kept by a partial run)
NOTES = "\n## Notes"


def _previous(out: Path, doc: dict, only) -> tuple[dict, str]:
    """``doc`` with the parts of the previous results that this run does not measure
    (their load and when/commit kept), and the previous file's hand-written notes."""
    old_json, notes = out.with_suffix(".json"), ""
    if old_json.exists():
        old = json.loads(old_json.read_text(encoding="utf-8"))
        for part in PARTS:
            if part in old and part not in only:
                doc[part] = old[part]
                doc["load"][part] = old.get("load", {}).get(part, "?")
                doc["runs"][part] = old.get("runs", {}).get(part) or {
                    "when": old.get("when", "?"),
                    "commit": old.get("commit", "?"),
                }
    if out.exists():
        text = out.read_text(encoding="utf-8")
        if NOTES in text:
            notes = text[text.index(NOTES) :]
    return doc, notes


def _save(doc, out: Path, notes: str = "") -> None:
    out.parent.mkdir(parents=True, exist_ok=True)
    out.with_suffix(".json").write_text(json.dumps(doc, indent=1) + "\n", encoding="utf-8")
    out.write_text(_markdown(doc) + notes, encoding="utf-8")


if __name__ == "__main__":
    sys.exit(main())
