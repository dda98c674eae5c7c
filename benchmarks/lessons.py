"""The lessons' time budget: every lesson executed top to bottom in a fresh kernel.

    python -m benchmarks.lessons            # all lessons -> benchmarks/results/lessons.md
    python -m benchmarks.lessons 08 14      # some (by number)

The course promises that a lesson runs in under 60 s on 2 cores (students on a laptop or
a shared JupyterHub).  That is a performance figure, so it is measured here, with the
machine it ran on, and not asserted by a timed test: ``make bench`` runs it after the
benchmark cases.  Each lesson runs once as the committed notebook (no static explorer
frames) in a temporary copy; the median of ``--repeats`` runs is reported.
"""

from __future__ import annotations

import argparse
import statistics
import sys
import tempfile
import time
from pathlib import Path

from benchmarks.harness import RESULTS, machine, machine_line

ROOT = Path(__file__).resolve().parent.parent
BUDGET_S = 60.0


def _execute_lessons():
    import course.execute

    return course.execute


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("numbers", nargs="*", help="lesson numbers (default: all)")
    ap.add_argument("--repeats", type=int, default=1, help="runs per lesson (median reported)")
    args = ap.parse_args(argv)
    ex = _execute_lessons()
    paths = sorted((ROOT / "lessons").glob("[0-9][0-9]_*.ipynb"))
    if args.numbers:
        paths = [p for p in paths if p.name[:2] in {n.zfill(2) for n in args.numbers}]
    rows = []
    with tempfile.TemporaryDirectory() as tmp, open(Path(tmp) / "kernels.log", "w") as log:
        for i, path in enumerate(paths, 1):
            print(f"[{i}/{len(paths)}] {path.name} ...", end="", flush=True)
            times = []
            for _ in range(max(1, args.repeats)):
                times.append(ex.execute(path, Path(tmp), timeout=300, limit=float("inf"), log=log))
            t = statistics.median(times)
            rows.append((path.stem, t))
            print(f" {t:.1f} s")
    info = machine()
    over = [name for name, t in rows if t > BUDGET_S]
    lines = [
        f"Lessons executed {time.strftime('%Y-%m-%d %H:%M')} (median of {max(1, args.repeats)} run(s) each, "
        f"fresh kernel, committed outputs replaced)",
        "",
        machine_line(info),
        "",
        f"| lesson | seconds | within the {BUDGET_S:.0f} s budget |",
        "|---|---:|---|",
    ]
    lines += [f"| {name} | {t:.1f} | {'yes' if t <= BUDGET_S else '**no**'} |" for name, t in rows]
    lines += ["", f"total {sum(t for _, t in rows):.1f} s; over budget: {', '.join(over) or 'none'}"]
    RESULTS.mkdir(parents=True, exist_ok=True)
    (RESULTS / "lessons.md").write_text("\n".join(lines) + "\n", encoding="utf-8")
    print(f"wrote {RESULTS / 'lessons.md'}; over budget: {', '.join(over) or 'none'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
