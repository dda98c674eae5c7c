"""``alpha_filtration`` with the triangulation's candidate in blocks (threads)
against one thread and against GUDHI (issue 25, item 1: the 2-core figure).

``python -m benchmarks.blocks_alpha [--inputs 6fpj ...] [--threads 2] [--repeats 5]``

Inputs are those of :mod:`benchmarks.cases.degenerate` (``6fpj``: the rounded MD
system, heavy atoms with water, 30,041 balls; ``grid15``; the corpus files).  Each
call is one fresh process (imports and a warm-up on 1hvr untimed), the sides
interleaved round by round: ours with ``SHAPELAB_THREADS=1``, ours with
``SHAPELAB_THREADS=N`` and GUDHI's weighted ``AlphaComplex(...).create_simplex_tree()``
(one thread; BLAS and OpenMP pinned to one thread everywhere).  Reported: the median
wall and CPU time of the call, the road (``triangulation_report``) and the
simplex counts (ours with 1 and N threads must be equal; GUDHI's beside them).
Writes ``benchmarks/results/blocks_alpha.md``.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
ONE = {"OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1"}


def _worker(side: str, name: str) -> None:
    from shapelab.power import triangulation_report

    from benchmarks.cases.degenerate import balls_of
    from shapelab import alpha_filtration
    from shapelab.datasets import structure

    b = balls_of(name)
    warm = structure("1hvr").balls
    if side == "gudhi":
        import gudhi

        gudhi.AlphaComplex(points=warm.centers, weights=warm.radii**2).create_simplex_tree()
        t0, c0 = time.perf_counter(), time.process_time()
        st = gudhi.AlphaComplex(points=b.centers, weights=b.radii**2).create_simplex_tree()
        wall, cpu = time.perf_counter() - t0, time.process_time() - c0
        counts = [0] * 4
        for s, _ in st.get_simplices():
            counts[len(s) - 1] += 1
        road = "gudhi"
    else:
        alpha_filtration(warm)
        t0, c0 = time.perf_counter(), time.process_time()
        F = alpha_filtration(b)
        wall, cpu = time.perf_counter() - t0, time.process_time() - c0
        counts = list(F.counts())
        rep = triangulation_report(b)
        road = f"{rep.method}, blocks={rep.blocks}" + (f" ({rep.blocks_reason})" if rep.blocks_reason else "")
    print(json.dumps({"wall": wall, "cpu": cpu, "counts": counts, "road": road, "n": len(b)}))


def _run(side: str, name: str, threads: int) -> dict:
    env = dict(os.environ, PYTHONPATH=str(ROOT), **ONE)
    env["SHAPELAB_THREADS"] = str(threads if side == "ours_mt" else 1)
    cmd = [sys.executable, "-m", "benchmarks.blocks_alpha", "--worker", side, name]
    out = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT, env=env)
    if out.returncode != 0:
        raise RuntimeError(f"{side} {name} failed:\n{out.stderr[-2000:]}")
    return json.loads(out.stdout.strip().splitlines()[-1])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--inputs", nargs="*", default=["6fpj"])
    ap.add_argument("--threads", type=int, default=2)
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--out", type=Path, default=ROOT / "benchmarks" / "results" / "blocks_alpha.md")
    ap.add_argument("--worker", nargs=2, help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.worker:
        _worker(*args.worker)
        return 0
    from benchmarks.harness import machine, machine_line

    sides = ("ours", "ours_mt", "gudhi")
    lines = [
        machine_line(machine()),
        "",
        f"`alpha_filtration`, one thread and SHAPELAB_THREADS={args.threads}, against GUDHI (one thread); "
        f"median of {args.repeats} fresh processes per side, interleaved; seconds: wall (CPU)",
        "",
        f"| input | balls | ours, 1 thread | ours, {args.threads} threads | GUDHI | ours 1 / {args.threads} threads (wall) "
        f"| ours {args.threads} threads / GUDHI (wall) | road with {args.threads} threads | counts equal | load |",
        "|---|---:|---:|---:|---:|---:|---:|---|---|---|",
    ]
    for name in args.inputs:
        load0 = os.getloadavg()[0]
        runs = {s: [] for s in sides}
        for _ in range(args.repeats):
            for s in sides:
                runs[s].append(_run(s, name, args.threads))
        med = {
            s: (statistics.median(r["wall"] for r in runs[s]), statistics.median(r["cpu"] for r in runs[s]))
            for s in sides
        }
        same = runs["ours"][0]["counts"] == runs["ours_mt"][0]["counts"]
        gud = runs["ours"][0]["counts"] == runs["gudhi"][0]["counts"]
        lines.append(
            f"| {name} | {runs['ours'][0]['n']:,} | "
            + " | ".join(f"{med[s][0]:.2f} ({med[s][1]:.2f})" for s in sides)
            + f" | {med['ours'][0] / med['ours_mt'][0]:.2f} | {med['ours_mt'][0] / med['gudhi'][0]:.2f} "
            + f"| {runs['ours_mt'][0]['road']} | 1 vs {args.threads} threads {same}, vs GUDHI {gud} "
            + f"| {load0:.1f} / {os.getloadavg()[0]:.1f} |"
        )
        print(lines[-1], file=sys.stderr, flush=True)
    text = "\n".join(lines) + "\n"
    args.out.write_text(text, encoding="utf-8")
    print(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
