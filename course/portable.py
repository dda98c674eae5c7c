"""Check that lesson outputs survive a change of floating-point environment.

A local diagnostic, never run in CI (see CONTRIBUTING.md, *Portable outputs*).
It re-executes lessons with ``course/execute.py`` under a named
variant of the environment (another OpenBLAS kernel, NumPy's SIMD dispatch
switched off, ...) into a temporary directory, never into ``lessons/``, and
prints, cell by cell, how the text outputs differ from the committed ones after
the sanitizing regexes of ``tests/nbval_sanitize.cfg``, as strict nbval would
see them.

    python -m course.portable --list                         # the variants
    python -m course.portable --variant blas-sandybridge     # all lessons
    python -m course.portable --variant npy-simd lessons/15_icp.ipynb
    python -m course.portable --variant current --keep /tmp/base   # this machine, as is
    python -m course.portable --variant blas-prescott --against /tmp/base

Cells are numbered as nbval numbers them (``Cell N`` counts code cells only).
Exit status: 0 if no cell differs, 1 if some cell differs or a lesson failed.
"""

from __future__ import annotations

import argparse
import copy
import difflib
import json
import os
import re
import subprocess
import sys
import tempfile
from pathlib import Path

import nbformat
from nbval.plugin import coalesce_streams, get_sanitize_patterns

from course import execute as execute_lessons  # the same execution as `make lessons`

ROOT = execute_lessons.ROOT
SANITIZE = ROOT / "tests" / "nbval_sanitize.cfg"

# What strict nbval leaves out of the comparison (nbval.plugin.IPyNbFile.skip_compare).
SKIP = {
    "metadata",
    "traceback",
    "prompt_number",
    "output_type",
    "name",
    "execution_count",
    "application/vnd.jupyter.widget-view+json",
    "image/png",
    "image/jpeg",
}

_BLAS = ("OPENBLAS_CORETYPE", "OPENBLAS_L2_SIZE")


def _simd_features() -> str:
    """NumPy's dispatched SIMD features that this CPU has (what ``npy-simd`` turns off)."""
    from numpy._core._multiarray_umath import __cpu_dispatch__, __cpu_features__

    return " ".join(f for f in __cpu_dispatch__ if __cpu_features__.get(f))


# name -> (description, variables to set, variables to remove)
VARIANTS = {
    "current": ("this machine's environment unchanged (is the lesson deterministic here?)", {}, ()),
    "blas-unset": ("OPENBLAS_CORETYPE and OPENBLAS_L2_SIZE removed: OpenBLAS picks its kernel itself", {}, _BLAS),
    "blas-haswell": ("OpenBLAS Haswell kernels (AVX2/FMA)", {"OPENBLAS_CORETYPE": "Haswell"}, _BLAS[1:]),
    "blas-sandybridge": ("OpenBLAS Sandybridge kernels (AVX, no FMA)", {"OPENBLAS_CORETYPE": "Sandybridge"}, _BLAS[1:]),
    "blas-prescott": ("OpenBLAS Prescott kernels (SSE3 only)", {"OPENBLAS_CORETYPE": "Prescott"}, _BLAS[1:]),
    "blas-1thread": ("OpenBLAS on one thread", {"OPENBLAS_NUM_THREADS": "1"}, ()),
    "npy-simd": (
        "NumPy's dispatched SIMD paths off (NPY_DISABLE_CPU_FEATURES = those this CPU has, "
        "AVX-512 or AVX2/FMA3): the baseline loops run instead",
        {"NPY_DISABLE_CPU_FEATURES": None},
        (),
    ),
}


def variant_env(name: str, base: dict | None = None) -> dict:
    """The environment of variant ``name``: a copy of ``base`` (default ``os.environ``)."""
    _, set_, unset = VARIANTS[name]
    env = dict(os.environ if base is None else base)
    for key in unset:
        env.pop(key, None)
    for key, value in set_.items():
        env[key] = _simd_features() if value is None else value
    return env


def describe_runtime(env: dict) -> str:
    """Which BLAS kernel and SIMD features a Python started in ``env`` uses."""
    code = (
        "import json, numpy\n"
        "from numpy._core._multiarray_umath import __cpu_features__ as f, __cpu_dispatch__ as d\n"
        "out = {'simd': [k for k in d if f.get(k)]}\n"
        "try:\n"
        "    import scipy.linalg, threadpoolctl\n"
        "    out['blas'] = sorted({f\"{i['internal_api']} {i.get('architecture')} x{i['num_threads']}\"\n"
        "                          for i in threadpoolctl.threadpool_info() if i['user_api'] == 'blas'})\n"
        "except ImportError:\n"
        "    out['blas'] = ['(install threadpoolctl to see the kernel)']\n"
        "print(json.dumps(out))\n"
    )
    res = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True)
    if res.returncode:
        return "python fails in this environment: " + res.stderr.strip()[-300:]
    info = json.loads(res.stdout)
    return f"BLAS: {', '.join(info['blas'])}; NumPy SIMD dispatch: {' '.join(info['simd']) or 'none'}"


def _texts(outputs, patterns) -> dict[str, list[str]]:
    """Outputs flattened as nbval compares them: mime type or stream name -> sanitized texts."""
    outs: dict[str, list[str]] = {}
    for o in coalesce_streams(copy.deepcopy(list(outputs))):
        if o.get("output_type") == "stream":
            items = [(o["name"], o.get("text", ""))]
        elif o.get("output_type") == "error":
            items = [("error", f"{o.get('ename')}: {o.get('evalue')}")]
        else:
            items = [(k, v) for k, v in o.get("data", {}).items() if k not in SKIP]
        for key, value in items:
            text = "".join(value) if isinstance(value, list) else value
            if not isinstance(text, str):
                text = json.dumps(text, sort_keys=True, indent=1)
            for regex, replace in patterns:
                text = re.sub(regex, replace, text)
            outs.setdefault(key, []).append(text)
    return outs


def compare(ref, new, patterns) -> list[tuple[int, int, str]]:
    """Code cells of two notebooks whose sanitized outputs differ.

    Returns ``(nbval_cell, cell_index, diff)`` for each: nbval's ``Cell N`` counts
    code cells, ``cell_index`` counts all cells, ``diff`` is a unified diff of
    the texts (committed ``-``, fresh ``+``).
    """
    ref_code = [c for c in ref.cells if c.cell_type == "code"]
    new_code = [c for c in new.cells if c.cell_type == "code"]
    index = [i for i, c in enumerate(ref.cells) if c.cell_type == "code"]
    if len(ref_code) != len(new_code):
        return [(-1, -1, f"different notebooks: {len(ref_code)} and {len(new_code)} code cells")]
    found = []
    for n, (a, b) in enumerate(zip(ref_code, new_code)):
        ta, tb = _texts(a.get("outputs", []), patterns), _texts(b.get("outputs", []), patterns)
        if ta == tb:
            continue
        lines = []
        for key in sorted(set(ta) | set(tb)):
            va, vb = "\n".join(ta.get(key, [])), "\n".join(tb.get(key, []))
            if va != vb:
                lines.extend(
                    difflib.unified_diff(
                        va.splitlines(), vb.splitlines(), f"committed {key}", f"fresh {key}", n=0, lineterm=""
                    )
                )
        found.append((n, index[n], "\n".join(lines)))
    return found


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("notebooks", nargs="*", type=Path, help="default: lessons/*.ipynb")
    ap.add_argument("--variant", default="blas-unset", choices=sorted(VARIANTS))
    ap.add_argument("--list", action="store_true", help="list the variants and exit")
    ap.add_argument(
        "--against",
        type=Path,
        default=None,
        help="compare with the notebooks of this directory (e.g. an earlier --keep), not with the committed lessons",
    )
    ap.add_argument("--keep", type=Path, default=None, help="write the executed copies here (kept)")
    ap.add_argument(
        "--limit",
        type=float,
        default=600.0,
        help="whole-notebook budget in seconds (generous: slow kernels are not the point)",
    )
    args = ap.parse_args(argv)
    if args.list:
        for name, (what, *_) in VARIANTS.items():
            print(f"{name:17s} {what}")
        return 0
    paths = args.notebooks or sorted((ROOT / "lessons").glob("[0-9][0-9]_*.ipynb"))
    paths = [p.resolve() for p in paths if not p.name.endswith(".failed.ipynb")]
    patterns = get_sanitize_patterns(SANITIZE.read_text())
    env = variant_env(args.variant)
    changed = {k: env.get(k, "(unset)") for k in (*_BLAS, *VARIANTS[args.variant][1])}
    print(f"variant {args.variant}: {VARIANTS[args.variant][0]}")
    print("  " + ", ".join(f"{k}={v}" for k, v in changed.items()))
    print("  " + describe_runtime(env))

    with tempfile.TemporaryDirectory(prefix="portable-") as tmp:
        out = args.keep or Path(tmp)
        saved = dict(os.environ)
        os.environ.clear()
        os.environ.update(env)  # the kernels inherit it
        try:
            execute_lessons.main(
                [*map(str, paths), "--out", str(out), "--limit", str(args.limit), "--no-static-explorers"]
            )
        finally:
            os.environ.clear()
            os.environ.update(saved)
        differ = failed = 0
        for path in paths:
            fresh = out / path.name
            if not fresh.exists():
                print(f"{path.name}: FAILED to execute (see above)")
                failed += 1
                continue
            ref = nbformat.read((args.against / path.name) if args.against else path, as_version=4)
            cells = compare(ref, nbformat.read(fresh, as_version=4), patterns)
            if not cells:
                print(f"{path.name}: identical")
            for n, i, diff in cells:
                differ += 1
                print(
                    f"{path.name}: Cell {n} (cell index {i}) differs\n"
                    + "\n".join("    " + line for line in diff.splitlines())
                )
    print(f"variant {args.variant}: {differ} cell(s) differ, {failed} lesson(s) failed, {len(paths)} lesson(s) checked")
    return 1 if differ or failed else 0


if __name__ == "__main__":
    sys.exit(main())
