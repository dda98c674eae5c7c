"""Benchmark harness: our code against a peer library, on the same data, in one run.

A *case* names three module-level functions:

* ``setup(seed) -> data``: builds the input (not timed), deterministic in ``seed``;
* ``ours(data) -> result`` and ``peer(data) -> result``: the two timed calls;
* optionally ``check(ours_result, peer_result) -> str``: a one-line accuracy note; a
  note that starts with ``MISMATCH`` (the two sides disagree beyond the case's
  tolerance) marks the case as not met, however fast it is.

Every repetition runs in a fresh Python process, after one untimed warm-up call
in that process, so neither side profits from the other's caches or allocator.
Each side's wall time is the median of ``repeats`` (at least 5) processes; peak
memory is the growth of the resident set size during the timed call: the peak
(VmHWM, reset just before the call through ``/proc/self/clear_refs``, so neither the
setup nor the warm-up counts) minus the resident size just before it, median over
the runs.  Memory the warm-up freed is handed back to the system first
(``malloc_trim``), so that it is not silently reused by the timed call.

``python -m benchmarks`` runs every case; ``python -m benchmarks NAME`` one case.
It prints a markdown table with the ratio ours/peer and writes JSON to
``benchmarks/results/``.
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
from dataclasses import asdict, dataclass, field
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


def _worker(case_name: str, side: str, seed: int) -> None:
    case = {c.name: c for c in all_cases()}[case_name]
    mod = importlib.import_module(_module_name(case.module))
    data = getattr(mod, case.setup)(seed=seed, **case.params)
    fn = getattr(mod, getattr(case, side))
    fn(data)  # warm-up: imports, JIT-free caches, page faults of the input
    _release_freed()
    before = _rss_now()
    _reset_peak()  # where it fails, the peak is the process's, and may include setup's
    t0 = time.perf_counter()
    result = fn(data)
    elapsed = time.perf_counter() - t0
    peak = _peak_rss()
    note = None
    if case.check and side == "ours":
        peer_result = getattr(mod, case.peer)(data)
        note = getattr(mod, case.check)(result, peer_result)
    print(json.dumps({"seconds": elapsed, "peak_kib": max(peak - before, 0), "note": note}))


def _run_side(case: Case, side: str, rep: int) -> dict:
    cmd = [sys.executable, "-m", "benchmarks.harness", "--worker", case.name, side, str(rep)]
    root = Path(__file__).resolve().parent.parent
    env = dict(os.environ, PYTHONPATH=str(root) + os.pathsep + os.environ.get("PYTHONPATH", ""))
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
    mem = {s: statistics.median(r["peak_kib"] for r in runs[s]) for s in runs}
    ratio = med["ours"] / med["peer"] if med["peer"] > 0 else float("inf")
    mem_ratio = mem["ours"] / mem["peer"] if mem["peer"] > 0 else None
    notes = sorted({r["note"] for r in runs["ours"] if r.get("note")})
    agree = not any(note.startswith(MISMATCH) for note in notes)
    ok = agree and (case.target is None or ratio <= case.target) and (
        case.memory_target is None or (mem_ratio is not None and mem_ratio <= case.memory_target)
    )
    return {
        "case": case.name,
        "description": case.description,
        "peer": case.peer_name,
        "repeats": n,
        "ours_s": med["ours"],
        "peer_s": med["peer"],
        "ratio": ratio,
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
    head = "| case | peer | ours (s) | peer (s) | ours/peer | target | peak MiB ours/peer | met | note |\n"
    head += "|---|---|---:|---:|---:|---:|---:|:-:|---|\n"
    for r in rows:
        tgt = "—" if r["target"] is None else f"≤ {r['target']:g}"
        mr = "—" if r["memory_ratio"] is None else f"{r['memory_ratio']:.2f}"
        head += (
            f"| {r['case']} | {r['peer']} | {r['ours_s']:.3f} | {r['peer_s']:.3f} | {r['ratio']:.2f} | {tgt} "
            f"| {r['ours_peak_mib']:.0f}/{r['peer_peak_mib']:.0f} ({mr}) | {'yes' if r['met'] else 'NO'} "
            f"| {'; '.join(r['notes'])} |\n"
        )
    return head


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m benchmarks", description=__doc__.split("\n\n")[0])
    ap.add_argument("case", nargs="*", help="case names (default: all)")
    ap.add_argument("--repeats", type=int, default=None, help="processes per side (at least 5)")
    ap.add_argument("--list", action="store_true", help="list the cases and exit")
    ap.add_argument("--worker", nargs=3, help=argparse.SUPPRESS)
    args = ap.parse_args(argv)
    if args.worker:
        _worker(args.worker[0], args.worker[1], int(args.worker[2]))
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
    for i, case in enumerate(cases, 1):
        print(f"[{i}/{len(cases)}] {case.name} vs {case.peer_name}", file=sys.stderr)
        rows.append(run_case(case, args.repeats))
    table = _table(rows)
    print(table)
    RESULTS.mkdir(parents=True, exist_ok=True)
    stamp = time.strftime("%Y%m%d-%H%M%S")
    payload = {"machine": {"python": sys.version.split()[0], "platform": platform.platform(), "cpus": os.cpu_count()}, "results": rows}
    for r in rows:
        (RESULTS / f"{r['case']}.json").write_text(json.dumps(dict(payload, results=[r]), indent=1))
    (RESULTS / "latest.md").write_text(f"Benchmarks run {stamp} on {payload['machine']['platform']}\n\n{table}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
