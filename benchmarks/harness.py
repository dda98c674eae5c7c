"""Benchmark harness: our code against a peer library, on the same data, in one run.

A *case* names three module-level functions:

* ``setup(seed) -> data``: builds the input (not timed), deterministic in ``seed``;
* ``ours(data) -> result`` and ``peer(data) -> result``: the two timed calls;
* optionally ``check(ours_result, peer_result) -> str``: a one-line accuracy note; a
  note that starts with ``MISMATCH`` (the two sides disagree beyond the case's
  tolerance) marks the case as not met, however fast it is.

Every repetition runs in a fresh Python process, so neither side profits from the
other's caches or allocator.  In it, after ``setup`` (and the case's optional
``prepare_ours``/``prepare_peer(data)``, untimed), the *first* call is timed as a
student meets it: cold, imports of the side's modules included (case functions
import lazily) together with first-use caches; then the *warm* call is timed.
Each side's wall times are medians of ``repeats`` (at least 5) processes, run
interleaved ours/peer so that drifts of the machine's load hit both alike; peak
memory is the growth of the resident set size during the timed call: the peak
(VmHWM, reset just before the call through ``/proc/self/clear_refs``, so neither the
setup nor the warm-up counts) minus the resident size just before it, median over
the runs.  Memory the warm-up freed is handed back to the system first
(``malloc_trim``), so that it is not silently reused by the timed call.

A case may declare an N ladder (``ladder``, values of the ``setup`` keyword
``ladder_param``): then one more fresh process per side and rung measures cold
and warm time and peak memory, and :mod:`benchmarks.scaling` draws time and
peak memory against N on log-log axes, ours and the peer's, with the fitted
exponent of each (``benchmarks/results/<case>_scaling.png``).

``python -m benchmarks`` runs every case; ``python -m benchmarks NAME`` one case;
``--no-scaling`` skips the ladders.  It prints a markdown table with the ratios
ours/peer (warm and cold), headed by the machine (CPU model and flags, BLAS kernel),
and writes JSON to ``benchmarks/results/``.
"""

from __future__ import annotations

import argparse
import ctypes
import ctypes.util
import gc
import importlib
import json
import os
import pkgutil
import platform
import resource
import statistics
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

__all__ = ["Case", "all_cases", "main"]

RESULTS = Path(__file__).resolve().parent / "results"


@dataclass(frozen=True)
class Case:
    """One comparison.

    Parameters
    ----------
    name : str
        Short unique name, used by ``make bench CASE=name``.
    module : str
        Module (under ``benchmarks.cases``) holding setup/ours/peer/check.
    peer_name : str
        What the peer is, e.g. ``"scipy Rotation.align_vectors"``.
    target : float or None
        The largest acceptable ratio ours/peer of median times (from the issue).
    memory_target : float or None
        The largest acceptable ratio of peak memory, where the issue sets one.
    repeats : int
        Processes per side (>= 5).
    params : dict
        Keyword arguments passed to ``setup`` besides the seed.
    ours, peer, setup, check : str
        Names of the functions in ``module``.
    prepare_ours, prepare_peer : str or None
        Functions ``f(data)`` run untimed before the cold call of that side (e.g.
        building a filtration whose topology is timed).
    ladder : tuple of int
        Values of ``params[ladder_param]`` for the scaling curves, small to large
        (empty: no curve).
    ladder_param : str
        The ``setup`` keyword the ladder varies.
    """

    name: str
    module: str
    peer_name: str
    target: float | None = None
    memory_target: float | None = None
    repeats: int = 5
    params: dict = field(default_factory=dict)
    setup: str = "setup"
    ours: str = "ours"
    peer: str = "peer"
    check: str | None = None
    description: str = ""
    prepare_ours: str | None = None
    prepare_peer: str | None = None
    ladder: tuple = ()
    ladder_param: str = "n"


def all_cases() -> list[Case]:
    """Collect ``CASES`` from every module in :mod:`benchmarks.cases`."""
    import benchmarks.cases as pkg

    cases: list[Case] = []
    modules = [f"benchmarks.cases.{m.name}" for m in sorted(pkgutil.iter_modules(pkg.__path__), key=lambda m: m.name)]
    # extra case modules (used by the harness's own test), comma-separated dotted names
    modules += [m for m in os.environ.get("SHAPELAB_BENCH_MODULES", "").split(",") if m]
    for name in modules:
        mod = importlib.import_module(name)
        cases.extend(getattr(mod, "CASES", []))
    names = [c.name for c in cases]
    dup = {n for n in names if names.count(n) > 1}
    if dup:
        raise ValueError(f"duplicate benchmark case names: {sorted(dup)}")
    return cases


def _rss_now() -> int:
    """Current resident set size in KiB (Linux)."""
    try:
        with open("/proc/self/statm") as fh:
            pages = int(fh.read().split()[1])
        return pages * os.sysconf("SC_PAGE_SIZE") // 1024
    except OSError:
        return 0


#: A check's note starting with this says that ours and the peer disagree.
MISMATCH = "MISMATCH"


def _release_freed() -> bool:
    """Hand memory that is freed but still resident back to the system: Python's
    garbage, then glibc's free heap pages (``malloc_trim(0)``).  Without it the timed
    call silently reuses what the warm-up freed, and a peer that allocates on the
    heap (C++ nodes, as GUDHI's simplex tree) looks several times smaller than it is,
    while NumPy's large arrays, which are returned to the system at once, do not
    profit.  Returns False where there is no glibc (the peak may then be too low)."""
    gc.collect()
    try:
        libc = ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6")
        libc.malloc_trim(ctypes.c_size_t(0))
        return True
    except (OSError, AttributeError):
        return False


def _reset_peak() -> bool:
    """Reset the kernel's record of this process's peak RSS (VmHWM), so the next peak read
    belongs to the timed call alone, not to the setup or the warm-up (Linux >= 4.0)."""
    try:
        with open("/proc/self/clear_refs", "w") as fh:
            fh.write("5")
        return True
    except OSError:
        return False


def _peak_rss() -> int:
    """Peak resident set size in KiB: VmHWM where the kernel reports it, else ru_maxrss."""
    try:
        with open("/proc/self/status") as fh:
            for line in fh:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1])
    except OSError:
        pass
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss


def _module_name(module: str) -> str:
    return module if "." in module else f"benchmarks.cases.{module}"


def _worker(case_name: str, side: str, seed: int, params: str | None = None) -> None:
    case = {c.name: c for c in all_cases()}[case_name]
    mod = importlib.import_module(_module_name(case.module))
    kwargs = dict(case.params, **(json.loads(params) if params else {}))
    data = getattr(mod, case.setup)(seed=seed, **kwargs)
    prep = case.prepare_ours if side == "ours" else case.prepare_peer
    if prep:
        getattr(mod, prep)(data)
    fn = getattr(mod, getattr(case, side))
    _release_freed()
    t0 = time.perf_counter()
    fn(data)  # cold: the first call, imports and first-use caches included
    cold = time.perf_counter() - t0
    _release_freed()
    before = _rss_now()
    _reset_peak()  # where it fails, the peak is the process's, and may include setup's
    t0 = time.perf_counter()
    result = fn(data)
    elapsed = time.perf_counter() - t0
    peak = _peak_rss()
    note = None
    if case.check and side == "ours" and not params:
        peer_result = getattr(mod, case.peer)(data)
        note = getattr(mod, case.check)(result, peer_result)
    print(json.dumps({"seconds": elapsed, "cold_seconds": cold, "peak_kib": max(peak - before, 0), "note": note}))


def _run_side(case: Case, side: str, rep: int, params: dict | None = None) -> dict:
    cmd = [sys.executable, "-m", "benchmarks.harness", "--worker", case.name, side, str(rep)]
    if params:
        cmd += ["--params", json.dumps(params)]
    root = Path(__file__).resolve().parent.parent
    env = dict(os.environ, PYTHONPATH=str(root) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    # one thread against the peers' one thread (freesasa, zsasa, Voronota-LT are run single-threaded):
    # shapelab's free-space slices would otherwise use every CPU; SHAPELAB_THREADS=2 make bench gives 2-core figures
    env.setdefault("SHAPELAB_THREADS", "1")
    out = subprocess.run(cmd, capture_output=True, text=True, cwd=root, env=env)
    if out.returncode != 0:
        raise RuntimeError(f"benchmark {case.name} ({side}) failed:\n{out.stderr[-2000:]}")
    return json.loads(out.stdout.strip().splitlines()[-1])


def run_case(case: Case, repeats: int | None = None) -> dict:
    n = max(5, repeats or case.repeats)
    runs = {"ours": [], "peer": []}
    for rep in range(n):
        for side in ("ours", "peer"):  # interleaved, so drifts hit both sides alike
            runs[side].append(_run_side(case, side, 0))
            print(f"  {case.name}: {side} run {rep + 1}/{n}: {runs[side][-1]['seconds']:.3f} s", file=sys.stderr)
    med = {s: statistics.median(r["seconds"] for r in runs[s]) for s in runs}
    cold = {s: statistics.median(r["cold_seconds"] for r in runs[s]) for s in runs}
    mem = {s: statistics.median(r["peak_kib"] for r in runs[s]) for s in runs}
    ratio = med["ours"] / med["peer"] if med["peer"] > 0 else float("inf")
    cold_ratio = cold["ours"] / cold["peer"] if cold["peer"] > 0 else float("inf")
    mem_ratio = mem["ours"] / mem["peer"] if mem["peer"] > 0 else None
    notes = sorted({r["note"] for r in runs["ours"] if r.get("note")})
    agree = not any(note.startswith(MISMATCH) for note in notes)
    ok = (
        agree
        and (case.target is None or max(ratio, cold_ratio) <= case.target)
        and (case.memory_target is None or (mem_ratio is not None and mem_ratio <= case.memory_target))
    )
    return {
        "case": case.name,
        "description": case.description,
        "peer": case.peer_name,
        "repeats": n,
        "ours_s": med["ours"],
        "peer_s": med["peer"],
        "ratio": ratio,
        "ours_cold_s": cold["ours"],
        "peer_cold_s": cold["peer"],
        "cold_ratio": cold_ratio,
        "target": case.target,
        "ours_peak_mib": mem["ours"] / 1024,
        "peer_peak_mib": mem["peer"] / 1024,
        "memory_ratio": mem_ratio,
        "memory_target": case.memory_target,
        "met": ok,
        "notes": notes,
        "runs": runs,
    }


def _table(rows: list[dict]) -> str:
    head = (
        "| case | peer | warm ours (s) | warm peer (s) | warm ours/peer | cold ours (s) | cold peer (s) "
        "| cold ours/peer | target | peak MiB ours/peer | met | note |\n"
    )
    head += "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|:-:|---|\n"
    for r in rows:
        tgt = "—" if r["target"] is None else f"≤ {r['target']:g}"
        mr = "—" if r["memory_ratio"] is None else f"{r['memory_ratio']:.2f}"
        head += (
            f"| {r['case']} | {r['peer']} | {r['ours_s']:.3f} | {r['peer_s']:.3f} | {r['ratio']:.2f} "
            f"| {r['ours_cold_s']:.3f} | {r['peer_cold_s']:.3f} | {r['cold_ratio']:.2f} | {tgt} "
            f"| {r['ours_peak_mib']:.0f}/{r['peer_peak_mib']:.0f} ({mr}) | {'yes' if r['met'] else 'NO'} "
            f"| {'; '.join(r['notes'])} |\n"
        )
    return head


def machine() -> dict:
    """What the ratios depend on: CPU model, its vector extensions, cores, memory,
    the BLAS library and kernel NumPy dispatches to (threadpoolctl), NumPy's SIMD."""
    info = {"python": sys.version.split()[0], "platform": platform.platform(), "cpus": os.cpu_count()}
    try:
        with open("/proc/cpuinfo") as fh:
            text = fh.read()
        for line in text.splitlines():
            if line.startswith("model name") and "cpu" not in info.get("cpu", "x"):
                info["cpu"] = line.split(":", 1)[1].strip()
            if line.startswith("flags"):
                flags = set(line.split(":", 1)[1].split())
                simd = [
                    "sse4_2",
                    "avx",
                    "avx2",
                    "fma",
                    "avx512f",
                    "avx512dq",
                    "avx512bw",
                    "avx512vl",
                    "avx512_vnni",
                    "avx512_bf16",
                    "amx_tile",
                ]
                info["cpu_flags"] = " ".join(f for f in simd if f in flags) or "none of AVX/AVX-512"
                info["avx512"] = "avx512f" in flags
                break
    except OSError:
        info["cpu"] = platform.processor() or "unknown"
    try:
        with open("/proc/meminfo") as fh:
            info["memory_gib"] = round(int(fh.readline().split()[1]) / 2**20, 1)
    except (OSError, ValueError, IndexError):
        pass
    try:
        import numpy as np

        info["numpy"] = np.__version__
        from numpy._core._multiarray_umath import __cpu_features__ as feats  # NumPy's dispatch

        info["numpy_simd"] = " ".join(f for f in ("AVX2", "FMA3", "AVX512F", "AVX512_SKX") if feats.get(f))
    except Exception:  # pragma: no cover - older NumPy
        pass
    try:
        import numpy as np
        from threadpoolctl import threadpool_info

        np.ones((2, 2)) @ np.ones((2, 2))  # load the BLAS
        blas = [p for p in threadpool_info() if p.get("user_api") == "blas"]
        info["blas"] = (
            "; ".join(
                f"{p.get('internal_api')} {p.get('version')} ({p.get('architecture')} kernel, {p.get('num_threads')} threads)"
                for p in blas
            )
            or "none found"
        )
    except ImportError:
        info["blas"] = "unknown (install threadpoolctl: pip install -e '.[bench]')"
    return info


def machine_line(info: dict) -> str:
    return (
        f"Machine: {info.get('cpu', '?')}, {info.get('cpus')} logical CPUs, {info.get('memory_gib', '?')} GiB; "
        f"CPU flags: {info.get('cpu_flags', '?')}; BLAS: {info.get('blas', '?')}; "
        f"NumPy {info.get('numpy', '?')} dispatches {info.get('numpy_simd', '?')}; "
        f"Python {info['python']} on {info['platform']}."
    )


def run_ladder(case: Case) -> list[dict]:
    """One fresh process per side and rung of ``case.ladder``: cold and warm time, peak."""
    points = []
    for value in case.ladder:
        for side in ("ours", "peer"):
            r = _run_side(case, side, 0, {case.ladder_param: value})
            points.append({"n": value, "side": side, **{k: r[k] for k in ("seconds", "cold_seconds", "peak_kib")}})
            print(f"  {case.name} scaling: {case.ladder_param} = {value} {side}: {r['seconds']:.3f} s", file=sys.stderr)
    return points


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m benchmarks", description=__doc__.split("\n\n")[0])
    ap.add_argument("case", nargs="*", help="case names (default: all)")
    ap.add_argument("--repeats", type=int, default=None, help="processes per side (at least 5)")
    ap.add_argument("--list", action="store_true", help="list the cases and exit")
    ap.add_argument("--no-scaling", action="store_true", help="skip the N ladders and their figures")
    ap.add_argument("--worker", nargs=3, help=argparse.SUPPRESS)
    ap.add_argument("--params", default=None, help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.worker:
        _worker(args.worker[0], args.worker[1], int(args.worker[2]), args.params)
        return 0
    cases = all_cases()
    if args.list:
        for c in cases:
            print(f"{c.name:32s} vs {c.peer_name}  {c.description}")
        return 0
    if args.case:
        known = {c.name for c in cases}
        unknown = [n for n in args.case if n not in known]
        if unknown:
            print(f"unknown case(s): {', '.join(unknown)}; known: {', '.join(sorted(known))}", file=sys.stderr)
            return 2
        cases = [c for c in cases if c.name in args.case]
    rows = []
    info = machine()
    print(machine_line(info), file=sys.stderr)
    RESULTS.mkdir(parents=True, exist_ok=True)
    stamp = time.strftime("%Y%m%d-%H%M%S")
    for i, case in enumerate(cases, 1):
        print(f"[{i}/{len(cases)}] {case.name} vs {case.peer_name}", file=sys.stderr)
        try:
            row = run_case(case, args.repeats)
            if case.ladder and not args.no_scaling:
                from benchmarks import scaling

                row["scaling"] = run_ladder(case)
                row["exponents"], row["figure"] = scaling.draw(case, row["scaling"], RESULTS)
        except RuntimeError as err:  # a side that cannot run here (a peer that will not import)
            row = _failed_row(case, err)
            print(f"  {case.name}: not run: {row['notes'][0]}", file=sys.stderr)
        rows.append(row)
        _write(rows, info, stamp, partial=i < len(cases))  # a later failure keeps what was measured
    table = _table(rows)
    fits = [r for r in rows if r.get("exponents")]
    if fits:
        table += "\nScaling (fitted exponent of time and peak memory against N, warm, log-log least squares):\n\n"
        table += "| case | N | time ours | time peer | memory ours | memory peer | figure |\n|---|---|---:|---:|---:|---:|---|\n"
        for r in fits:
            e = r["exponents"]
            ladder = [p["n"] for p in r["scaling"] if p["side"] == "ours"]

            def fmt(x):
                return "—" if x is None else f"{x:.2f}"

            table += (
                f"| {r['case']} | {ladder[0]:g}–{ladder[-1]:g} | {fmt(e['ours_time'])} | {fmt(e['peer_time'])} "
                f"| {fmt(e['ours_memory'])} | {fmt(e['peer_memory'])} | [{r['figure']}]({r['figure']}) |\n"
            )
    print(_header(info) + table)
    _write(rows, info, stamp, partial=False, table=table)
    return 0 if not any(r.get("failed") for r in rows) else 1


def _failed_row(case: Case, err: Exception) -> dict:
    """A case that could not run: its row says why (the last line of the error)."""
    lines = [ln.strip() for ln in str(err).splitlines() if ln.strip()]
    why = lines[-1] if lines else type(err).__name__
    nan = float("nan")
    return {
        "case": case.name,
        "description": case.description,
        "peer": case.peer_name,
        "failed": True,
        "ours_s": nan,
        "peer_s": nan,
        "ratio": nan,
        "ours_cold_s": nan,
        "peer_cold_s": nan,
        "cold_ratio": nan,
        "target": case.target,
        "ours_peak_mib": nan,
        "peer_peak_mib": nan,
        "memory_ratio": None,
        "memory_target": case.memory_target,
        "met": False,
        "notes": [f"NOT RUN: {why[:200]}"],
    }


def _header(info) -> str:
    return (
        f"{machine_line(info)}\nMedians of fresh processes, ours and the peer interleaved "
        f"(other work on the machine hits both alike).\n\n"
    )


def _write(rows, info, stamp, *, partial, table=None) -> None:
    """Per-case JSON and ``latest.md``; after each case while the run goes on, marked
    as partial, so that an interrupted run keeps what it measured."""
    header = _header(info)
    payload = {"machine": info, "results": rows}
    for r in rows:
        (RESULTS / f"{r['case']}.json").write_text(json.dumps(dict(payload, results=[r]), indent=1))
    what = "partial: the run goes on" if partial else "complete"
    (RESULTS / "latest.md").write_text(f"Benchmarks run {stamp} ({what})\n\n{header}{table or _table(rows)}")


if __name__ == "__main__":
    sys.exit(main())
