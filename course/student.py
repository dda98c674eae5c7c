#!/usr/bin/env python
"""Write the student edition of the lessons: no solutions, no outputs.

    python -m course.student                    # every lesson -> dist/student/
    python -m course.student --out DIR lessons/14_hausdorff.ipynb

For every lesson:

* markdown cells tagged ``solution`` are dropped, and so are the instructor's speaker
  notes (``slideshow.slide_type`` ``notes``);
* in every code cell, what lies between ``# BEGIN SOLUTION`` and ``# END SOLUTION`` is
  replaced by a placeholder, and the code after ``# END SOLUTION`` (the self-check
  call) stays.  The placeholder keeps that call meaningful:

  - a solution that defines functions becomes the same signatures with the body
    ``raise NotImplementedError("your code here")``, so that
    ``check.hausdorff(my_hausdorff)`` runs and says "not implemented yet";
  - markers indented inside a function body become that ``raise`` line;
  - a solution that only computes values becomes a comment naming them and a
    ``raise NotImplementedError``: the cell stops, kindly, until the student writes it;

* every output, execution count and the stored widget state are removed.

A lesson with unbalanced markers (an END without a BEGIN, a BEGIN without an END,
nested BEGINs) or a code cell tagged ``solution`` without markers is refused: nothing
is written for it and the command exits non-zero, so a solution never leaks.
"""

from __future__ import annotations

import argparse
import ast
import copy
import re
import sys
import textwrap
import time
from pathlib import Path

import nbformat

from course.notebooks import BEGIN, END, SOLUTION_TAG, slide_type

ROOT = Path(__file__).resolve().parent.parent
DEFAULT_OUT = ROOT / "dist" / "student"

PLACEHOLDER = 'raise NotImplementedError("your code here")'
TAG = SOLUTION_TAG
STUDENT_TAG = "exercise"

README = """# shapelab: student edition

These are the course's lessons without solutions and without outputs.

1. Open `00_start_here.ipynb` and run its cells from the top (*Run → Run All Cells*).
2. Each exercise has a cell with a placeholder, `raise NotImplementedError("your code here")`.
   Replace it with your code and run the cell: the self-check below it (for example
   `check.hausdorff(my_hausdorff)`) tries your function on many cases and says
   "correct", or shows the first input where your answer differs from the library's.
3. Stuck? Re-read the lesson's sections above the exercise; every formula you need is there.

The notebooks need the `shapelab` package (`pip install -e .` in the course repository,
or the course's JupyterHub / Binder image, see `binder/`).
"""


class MarkerError(ValueError):
    """Unbalanced or missing solution markers."""


def solution_blocks(lines: list[str]) -> list[tuple[int, int]]:
    """(begin, end) line indices of each marked block; raises MarkerError if unbalanced."""
    blocks, start = [], None
    for i, line in enumerate(lines):
        if BEGIN.match(line):
            if start is not None:
                raise MarkerError(f"line {i + 1}: '# BEGIN SOLUTION' inside another solution (missing END?)")
            start = i
        elif END.match(line):
            if start is None:
                raise MarkerError(f"line {i + 1}: '# END SOLUTION' without a '# BEGIN SOLUTION'")
            blocks.append((start, i))
            start = None
    if start is not None:
        raise MarkerError(f"line {start + 1}: '# BEGIN SOLUTION' without an '# END SOLUTION'")
    return blocks


def _assigned_names(node: ast.AST) -> list[str]:
    names = []
    for sub in ast.walk(node):
        if isinstance(sub, ast.Name) and isinstance(sub.ctx, ast.Store):
            names.append(sub.id)
    return names


def _stub(node: ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef, indent: str) -> list[str]:
    if isinstance(node, ast.ClassDef):
        head = f"class {node.name}:"
        body = ["def __init__(self, *args, **kwargs):", f"    {PLACEHOLDER}"]
    else:
        stub = copy.copy(node)
        stub.decorator_list = []
        stub.body = [ast.Pass()]
        head = ast.unparse(stub).splitlines()[0]
        body = ["# your code here", PLACEHOLDER]
    return [indent + head] + [indent + "    " + b for b in body]


def _loaded_names(source: str) -> set[str]:
    try:
        tree = ast.parse(textwrap.dedent(source))
    except SyntaxError:
        return set()
    return {n.id for n in ast.walk(tree) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)}


def placeholder(solution: list[str], indent: str, after: str = "") -> list[str]:
    """The lines that replace a solution block whose markers are indented by ``indent``.

    ``after`` is the code that follows the block in the cell: a value solution's
    placeholder names only the values that code uses (not the solution's helpers).
    """
    if indent:  # markers inside a function body: the body becomes the raise
        return [indent + "# your code here", indent + PLACEHOLDER]
    try:
        tree = ast.parse(textwrap.dedent("\n".join(solution)))
    except SyntaxError:  # e.g. IPython magics: nothing to learn from the code's shape
        return ["# your code here", PLACEHOLDER]
    defs = [n for n in tree.body if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef))]
    rest = [n for n in tree.body if n not in defs and not isinstance(n, (ast.Import, ast.ImportFrom))]
    out: list[str] = []
    for d in defs:
        if out:
            out.append("")
        out += _stub(d, "")
    if rest or not defs:
        names = list(dict.fromkeys(n for node in rest for n in _assigned_names(node)))
        used = _loaded_names(after)
        names = [n for n in names if n in used] or names[-1:]
        what = f"compute {', '.join(names)}" if names else "your code here"
        if out:
            out.append("")
        out += [f"# your code here: {what}", f'raise NotImplementedError("your code here: {what}")']
    return out


def strip_source(source: str) -> tuple[str, int]:
    """``source`` with each solution block replaced; returns (text, number of blocks)."""
    lines = source.splitlines()
    blocks = solution_blocks(lines)
    if not blocks:
        return source, 0
    out, pos = [], 0
    for begin, end in blocks:
        out += lines[pos:begin]
        indent = re.match(r"\s*", lines[begin]).group(0)
        after = "\n".join(lines[end + 1 :])
        out += [lines[begin]] + placeholder(lines[begin + 1 : end], indent, after) + [lines[end]]
        pos = end + 1
    out += lines[pos:]
    return "\n".join(out), len(blocks)


def _strip_code_cell(cell, i: int, tags: list[str]) -> int:
    """Replace the solutions of code cell ``i`` by their placeholders; how many there were.
    A cell tagged ``solution`` without markers is refused (its solution would leak)."""
    try:
        cell.source, n = strip_source(cell.source)
    except MarkerError as exc:
        raise MarkerError(f"cell {i}: {exc}") from None
    if TAG in tags and n == 0:
        raise MarkerError(f"cell {i} is tagged 'solution' but has no '# BEGIN SOLUTION' / '# END SOLUTION' markers")
    return n


def student_notebook(nb) -> tuple[nbformat.NotebookNode, dict]:
    """The student edition of an instructor notebook, and counts of what changed."""
    nb = copy.deepcopy(nb)
    stats = {"exercises": 0, "markdown removed": 0}
    cells = []
    for i, cell in enumerate(nb.cells):
        tags = list(cell.get("metadata", {}).get("tags", []))
        speaker_notes = cell.get("metadata", {}).get("slideshow", {}).get("slide_type") == "notes"
        if cell.cell_type == "markdown" and (TAG in tags or speaker_notes):
            stats["markdown removed"] += 1
            continue
        if cell.cell_type == "code":
            n = _strip_code_cell(cell, i, tags)
            stats["exercises"] += n
            cell.outputs = []
            cell.execution_count = None
            for key in ("execution", "collapsed", "scrolled"):
                cell.metadata.pop(key, None)
        if TAG in tags:
            cell.metadata["tags"] = [STUDENT_TAG if t == TAG else t for t in tags]
        if "attachments" in cell and not cell.attachments:
            del cell["attachments"]
        cells.append(cell)
    nb.cells = cells
    nb.metadata.pop("widgets", None)
    nbformat.validate(nb)
    return nb, stats


def site_notebook(nb) -> tuple[nbformat.NotebookNode, dict]:
    """The course site's page of an executed lesson: as the student edition, no solution
    (markdown solutions dropped, code between the markers replaced by the placeholder,
    that cell's outputs removed, since they are the solution's results), but every other
    cell keeps its outputs: the site shows the lesson as it ran.

    The speaker notes (``slideshow.slide_type`` ``notes``) are dropped too: tagged
    ``remove-cell`` they are off the page, but the page's "download .ipynb" button
    (``_sources/``) would still hand them out, and they can tell an exercise's answer."""
    nb = copy.deepcopy(nb)
    stats = {"exercises": 0, "markdown removed": 0}
    cells = []
    for i, cell in enumerate(nb.cells):
        tags = list(cell.get("metadata", {}).get("tags", []))
        if cell.cell_type == "markdown" and TAG in tags:
            stats["markdown removed"] += 1
            continue
        if cell.cell_type == "markdown" and slide_type(cell) == "notes":
            continue
        if cell.cell_type == "code":
            n = _strip_code_cell(cell, i, tags)
            if n:
                stats["exercises"] += n
                cell.outputs = []
                cell.execution_count = None
        if TAG in tags:
            cell.metadata["tags"] = [STUDENT_TAG if t == TAG else t for t in tags]
        cells.append(cell)
    nb.cells = cells
    return nb, stats


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("lessons", nargs="*", type=Path, help="default: lessons/NN_*.ipynb")
    ap.add_argument("--out", type=Path, default=DEFAULT_OUT, help=f"default {DEFAULT_OUT.relative_to(ROOT)}")
    args = ap.parse_args(argv)
    paths = args.lessons or sorted((ROOT / "lessons").glob("[0-9][0-9]_*.ipynb"))
    paths = [p for p in paths if not p.name.endswith(".failed.ipynb")]
    if not paths:
        print("no lessons found", file=sys.stderr)
        return 1
    t0 = time.perf_counter()
    out = args.out
    out.mkdir(parents=True, exist_ok=True)
    if not args.lessons:  # a full edition: no stale lessons from an earlier run
        for old in out.glob("*.ipynb"):
            old.unlink()
    failures, written, size = [], 0, 0
    for i, path in enumerate(paths, 1):
        print(f"[{i}/{len(paths)}] {path.name} ...", end="", flush=True)
        try:
            nb, stats = student_notebook(nbformat.read(path, as_version=4))
        except Exception as exc:
            print(" REFUSED")
            failures.append(f"{path.name}: {exc}")
            (out / path.name).unlink(missing_ok=True)
            continue
        target = out / path.name
        nbformat.write(nb, target)
        written += 1
        size += target.stat().st_size
        extra = f", {stats['markdown removed']} markdown solutions removed" if stats["markdown removed"] else ""
        print(f" {stats['exercises']} exercises with placeholders{extra}")
    (out / "README.md").write_text(README, encoding="utf-8")
    print(
        f"student edition: {written}/{len(paths)} lessons, {size / 1024:.0f} KiB, "
        f"in {time.perf_counter() - t0:.1f} s -> {out}"
    )
    for f in failures:
        print("  refused " + f, file=sys.stderr)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
