"""Execute lessons top to bottom in a fresh kernel, with progress and timings.

Used by ``make lessons`` (refresh the committed outputs in place, see
CONTRIBUTING.md) and by ``make course`` (execute into the book's build tree).

    python -m course.execute                      # all lessons, in place
    python -m course.execute lessons/03_*.ipynb   # some, in place
    python -m course.execute --out book/lessons   # copies, for the book

A lesson fails if any cell raises or writes to stderr.  The course's budget is 60 s per
lesson on 2 cores (``BUDGET``): a lesson over it is named with a warning, and fails
only with ``--limit SECONDS`` (maintainers' runs), so that a student's slower laptop
still builds the course.
Widget state is stored in the committed lessons; the book's copies (``--out``) carry the
explorers' static players instead (shapelab.widgets.static) and no widget state.
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

import nbformat
from nbclient import NotebookClient

ROOT = Path(__file__).resolve().parent.parent


def problems(nb) -> list[str]:
    """Error outputs and stderr streams of an executed notebook, as messages."""
    out = []
    for i, cell in enumerate(nb.cells):
        if cell.cell_type != "code":
            continue
        for o in cell.get("outputs", []):
            if o.get("output_type") == "error":
                out.append(f"cell {i}: {o.get('ename')}: {o.get('evalue')}")
            elif o.get("output_type") == "stream" and o.get("name") == "stderr":
                out.append(f"cell {i}: wrote to stderr: {''.join(o.get('text', ''))[:300]!r}")
    return out


LOG = ROOT / "book" / "_build" / "logs" / "kernels.log"
#: the course's time budget per lesson, in seconds on 2 cores (a warning past it)
BUDGET = 60.0


#: the inline backend's figure formats of every executed lesson, committed or copied for the
#: site and the decks: ``retina`` (PNG at twice the pixels, shown at the same size, so sharp
#: on a projector and a high-resolution screen) unless ``$SHAPELAB_FIGURE_FORMATS`` names
#: others (``svg``).  nbval does not compare image data, so a student's kernel (plain PNG)
#: reproduces the committed outputs all the same.
FIGURE_FORMATS_ENV = "SHAPELAB_FIGURE_FORMATS"
COPIES_FIGURE_FORMATS = "retina"


def kernel_arguments(out_dir: Path | None = None) -> list[str]:
    """The kernel's command-line configuration: figures drawn as ``$SHAPELAB_FIGURE_FORMATS``
    (default ``retina``), for the lessons in place and for copies (``--out``) alike."""
    formats = [f.strip() for f in os.environ.get(FIGURE_FORMATS_ENV, COPIES_FIGURE_FORMATS).split(",") if f.strip()]
    return [f"--InlineBackend.figure_formats={f}" for f in formats]


def execute(path: Path, out_dir: Path | None, timeout: int, limit: float | None, log=None) -> float:
    nb = nbformat.read(path, as_version=4)
    env_cwd = path.parent
    keep_widgets = os.environ.get("SHAPELAB_STATIC_EXPLORERS") != "1"
    if not keep_widgets:
        nb.metadata.pop("widgets", None)  # the committed lesson's state, stale and unused here
    client = NotebookClient(
        nb,
        timeout=timeout,
        kernel_name="python3",
        resources={"metadata": {"path": str(env_cwd)}},
        # the committed lessons keep the widget state (JupyterLab, the decks); the book's
        # copies show the explorers' static players and need none
        store_widget_state=keep_widgets,
        record_timing=False,
        allow_errors=True,
        extra_arguments=kernel_arguments(out_dir),
    )
    t0 = time.perf_counter()
    # the kernel's own messages (e.g. jupyter_client's note that a local kernel talks over
    # TCP without encryption) go to the log file, not between the progress lines
    client.execute(**({"stderr": log} if log is not None else {}))
    elapsed = time.perf_counter() - t0
    found = problems(nb)
    if limit is not None and elapsed > limit:
        found.append(f"took {elapsed:.1f} s, over the {limit:.0f} s limit")
    target = (out_dir / path.name) if out_dir else path
    target.parent.mkdir(parents=True, exist_ok=True)
    if found and out_dir is None:
        # never overwrite a good committed lesson with a broken run
        bad = target.with_suffix(".failed.ipynb")
        nbformat.write(nb, bad)
        raise RuntimeError(f"{path.name}: " + "; ".join(found) + f" (executed copy in {bad})")
    if found:
        raise RuntimeError(f"{path.name}: " + "; ".join(found))
    nbformat.write(nb, target)
    return elapsed


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("notebooks", nargs="*", type=Path, help="default: lessons/*.ipynb")
    ap.add_argument("--out", type=Path, default=None, help="write executed copies here instead of in place")
    ap.add_argument("--timeout", type=int, default=120, help="per-cell timeout in seconds")
    ap.add_argument(
        "--limit", type=float, default=None, help=f"fail a lesson that takes longer (default: warn past {BUDGET:.0f} s)"
    )
    ap.add_argument(
        "--static-explorers",
        action=argparse.BooleanOptionalAction,
        default=None,
        help="precompute every explorer's frames for a page without a kernel "
        "(default: on with --out, i.e. for the book; off for the committed lessons)",
    )
    args = ap.parse_args(argv)
    static = args.out is not None if args.static_explorers is None else args.static_explorers
    # read by shapelab.widgets.static in the kernels started below
    os.environ["SHAPELAB_STATIC_EXPLORERS"] = "1" if static else "0"
    os.environ.setdefault("PYTHONHASHSEED", "0")
    os.environ.setdefault("PYDEVD_DISABLE_FILE_VALIDATION", "1")
    os.environ["PYTHONPATH"] = str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", "")
    paths = args.notebooks or sorted((ROOT / "lessons").glob("[0-9][0-9]_*.ipynb"))
    paths = [p for p in paths if not p.name.endswith(".failed.ipynb")]
    if not paths:
        print("no lessons found", file=sys.stderr)
        return 1
    failures, total = [], 0.0
    LOG.parent.mkdir(parents=True, exist_ok=True)
    log = open(LOG, "a", encoding="utf-8")
    for i, path in enumerate(paths, 1):
        print(f"[{i}/{len(paths)}] executing {path.name} ...", end="", flush=True)
        log.write(f"--- {time.strftime('%Y-%m-%d %H:%M:%S')} {path.name}\n")
        log.flush()
        try:
            dt = execute(path, args.out, args.timeout, args.limit, log)
        except Exception as exc:  # keep going, report all at the end
            print(" FAILED")
            failures.append(str(exc))
            continue
        total += dt
        over = f"  (over the course's {BUDGET:.0f} s budget on 2 cores)" if dt > BUDGET else ""
        print(f" {dt:.1f} s{over}")
    log.close()
    print(
        f"executed {len(paths) - len(failures)}/{len(paths)} lessons in {total:.1f} s "
        f"(the kernels' messages: {LOG.relative_to(ROOT)})"
    )
    for f in failures:
        print("  " + f, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
