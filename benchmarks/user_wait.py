"""What a user waits for (issue 25, item 3): a lesson's first cells, one CLI report, a batch.

    python -m benchmarks.user_wait                 # all -> benchmarks/results/user_wait.md (+ .json)
    python -m benchmarks.user_wait --only lessons  # lessons, cli, batch, importtime (any of them)

Every figure is the median of ``--repeats`` (at least 5) FRESH processes, timed from
outside (the wall time of the whole process: interpreter start, imports, work, exit),
because that is what a user waits for:

* **lessons**: the first two code cells of each lesson (the imports cell, then the first
  cell that computes: "import plus first call"), run by a fresh ``python`` (not a
  Jupyter kernel: kernel start-up is Jupyter's, not ours, and is the same for every
  lesson) in the lessons folder, with IPython's line magics (``%matplotlib inline``)
  dropped, the Agg backend, ``display`` from IPython, and every open figure rendered to
  PNG at the end of each cell as the inline backend does.  Inside the process the
  imports cell and the first call are also timed apart.
* **cli**: ``python -m shapelab report shapelab/data/1FMO.pdb.gz`` into a temporary folder.
* **batch**: :func:`shapelab.report_batch` over 100 structures (copies of the shipped
  PDB files, cycled), ``jobs=1`` and ``jobs=2``, whole process; per structure = wall / 100.
* **importtime**: ``python -X importtime`` of ``import shapelab`` and of the first geometry
  call (``sl.union_measure`` on 1hvr), the top entries by cumulative time (one run:
  a profile, not a benchmark).

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
#: the shipped structure files the batch cycles through (the KVFinder output is not a protein)
BATCH_FILES = (
    "1hvr.pdb.gz",
    "1FMO.pdb.gz",
    "3mht.pdb.gz",
    "t4l_l99a_receptor.pdb.gz",
    "adk_open.pdb.gz",
    "adk_closed.pdb.gz",
    "1grm_single.pdb.gz",
    "globule.pdb",
)
BATCH_SIZE = 100

#: run by the fresh python of a lesson: cells as JSON in argv[1]; prints the in-process times
_CELLS = r"""
import json, sys, time
t_start = time.perf_counter()
from IPython.display import display  # a kernel has IPython; matplotlib comes with the cells (MPLBACKEND=Agg)
ns = {"display": display, "__name__": "__main__"}
times = []
for src in json.loads(sys.argv[1]):
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

_BATCH = r"""
import sys
import shapelab
s = shapelab.report_batch(sys.argv[1], out=sys.argv[2], jobs=int(sys.argv[3]), progress=False)
"""


def _env() -> dict:
    return dict(os.environ, PYTHONPATH=str(ROOT), MPLBACKEND="Agg", PYTHONHASHSEED="0")


def _timed(cmd, *, cwd=None) -> tuple[float, str]:
    """Wall time of one fresh process (and its stdout); a failure raises with its stderr."""
    t = time.perf_counter()
    r = subprocess.run(cmd, cwd=cwd, env=_env(), capture_output=True, text=True)
    wall = time.perf_counter() - t
    if r.returncode != 0:
        raise RuntimeError(f"{' '.join(map(str, cmd[:4]))} failed:\n{r.stderr[-1500:]}")
    return wall, r.stdout


def _first_cells(path: Path, n: int = 2) -> list[str]:
    import nbformat

    nb = nbformat.read(path, as_version=4)
    return [c.source for c in nb.cells if c.cell_type == "code"][:n]


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


def batch(repeats: int, jobs=(1, 2)) -> list[dict]:
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        src = Path(tmp) / "in"
        src.mkdir()
        for k in range(BATCH_SIZE):
            name = BATCH_FILES[k % len(BATCH_FILES)]
            stem, _, ext = name.partition(".")
            shutil.copyfile(DATA / name, src / f"s{k:03d}_{stem}.{ext}")
        for j in jobs:
            walls = []
            for _ in range(repeats):
                out = Path(tmp) / "out"
                shutil.rmtree(out, ignore_errors=True)
                out.mkdir()
                wall, _ = _timed([sys.executable, "-c", _BATCH, str(src), str(out), str(j)], cwd=tmp)
                done = len(list(out.glob("*_cavities.done.json")))
                if done != BATCH_SIZE:
                    raise RuntimeError(f"batch jobs={j}: {done} of {BATCH_SIZE} structures done")
                walls.append(wall)
            w = statistics.median(walls)
            rows.append({"jobs": j, "runs": repeats, "wall_s": w, "per_structure_s": w / BATCH_SIZE, "all_s": walls})
            print(f"  batch jobs={j}: {w:.1f} s, {w / BATCH_SIZE:.3f} s per structure", file=sys.stderr)
    return rows


_FIRST_CALL = "import shapelab as sl; sl.union_measure(sl.datasets.structure('1hvr').balls)"


def importtime(top: int = 12) -> dict:
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
            "heavy_imported": heavy,
        }
    return out


def _markdown(doc) -> str:
    L = [
        "# What a user waits for (issue 25, item 3)",
        "",
        "`python -m benchmarks.user_wait` (run "
        + "; ".join(f"{part} {r['when']} UTC at shapelab commit {r['commit']}" for part, r in doc["runs"].items())
        + "; raw numbers in `user_wait.json`).  Every time is the median of fresh processes, timed from outside "
        "(interpreter start to exit).",
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
            "| lesson | runs | total (s) | import cell (s) | first call (s) |",
            "|---|---:|---:|---:|---:|",
        ]
        for r in doc["lessons"]:
            if r.get("error"):
                L.append(f"| {r['lesson']} | {r['runs']} | failed: {r['error']} | | |")
            else:
                L.append(
                    f"| {r['lesson']} | {r['runs']} | {r['wall_s']:.2f} | {r['import_cell_s']:.2f} "
                    f"| {r['first_call_s']:.2f} |"
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
    if "batch" in doc:
        L += [
            f"## A batch of {BATCH_SIZE} structures (load {doc['load']['batch']})",
            "",
            f"`shapelab.report_batch` over {BATCH_SIZE} files (the shipped {', '.join(BATCH_FILES)} cycled), "
            "one fresh process per run, progress off.",
            "",
            "| jobs | runs | batch (s) | per structure (s) |",
            "|---:|---:|---:|---:|",
        ]
        for r in doc["batch"]:
            L.append(f"| {r['jobs']} | {r['runs']} | {r['wall_s']:.1f} | {r['per_structure_s']:.3f} |")
        L.append("")
    if "importtime" in doc:
        L += ["## Import profile (`python -X importtime`, one run)", ""]
        for label, p in doc["importtime"].items():
            L += [
                f"**{label}**: process {p['wall_s']:.2f} s, imports {p['total_ms']:.0f} ms; heavy packages imported: "
                f"{', '.join(p['heavy_imported']) or 'none'}.",
                "",
                "| module (top two levels) | cumulative (ms) | self (ms) |",
                "|---|---:|---:|",
            ]
            L += [
                f"| {'&nbsp;&nbsp;' * e['depth']}{e['module']} | {e['cumulative_ms']:.1f} | {e['self_ms']:.1f} |"
                for e in p["top"]
            ]
            L.append("")
    return "\n".join(L) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--only", nargs="*", choices=PARTS, default=list(PARTS))
    ap.add_argument("--lessons", nargs="*", default=None, help="lesson numbers (default: all)")
    ap.add_argument("--repeats", type=int, default=5, help="fresh processes per figure (at least 5)")
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
        "batch": lambda: batch(args.repeats),
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
