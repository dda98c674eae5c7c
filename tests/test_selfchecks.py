"""Every exercise's self-check fails on a wrong or empty answer and passes on the solution.

Each lesson runs in a Jupyter kernel, cell by cell.  Before each exercise cell (a code cell
with ``# BEGIN SOLUTION`` ... ``# END SOLUTION``) runs as written, it runs with the solution
replaced by wrong answers:

- the placeholder the student edition leaves (``raise NotImplementedError``);
- ``None`` for every value the check uses (a function answer returns ``None``);
- ``0`` likewise.

Every variant must print no "✓"; the instructor's solution must print "✓" and no "✗".  A
wrong answer's output must not show the right value either (the number, to 4 digits), and
no check's result may be displayed a second time (as a ``CheckResult(...)`` repr).
"""

from __future__ import annotations

import ast
import json
import os
import queue
import re
import textwrap
from pathlib import Path

import nbformat
import pytest

ROOT = Path(__file__).resolve().parent.parent
LESSONS = sorted((ROOT / "lessons").glob("[0-9][0-9]_*.ipynb"))
BEGIN = re.compile(r"^(\s*)#+\s*BEGIN SOLUTION\s*$")
END = re.compile(r"^\s*#+\s*END SOLUTION\s*$")

jupyter_client = pytest.importorskip("jupyter_client")


def _student_edition():
    import course.student

    return course.student


def _blocks(lines):
    out, start = [], None
    for i, line in enumerate(lines):
        if BEGIN.match(line):
            start = i
        elif END.match(line) and start is not None:
            out.append((start, i))
            start = None
    return out


def _used_after(source: str, end_line: int) -> set:
    after = "\n".join(source.splitlines()[end_line + 1 :])
    try:
        tree = ast.parse(textwrap.dedent(after))
    except SyntaxError:
        return set()
    return {n.id for n in ast.walk(tree) if isinstance(n, ast.Name)}


def _wrong(source: str, wrong: str) -> tuple[str, list]:
    """``source`` with each solution block replaced by an answer of ``wrong`` (a Python
    expression); returns the new source and the value names it replaced."""
    lines = source.splitlines()
    out, pos, names = [], 0, []
    for begin, end in _blocks(lines):
        out += lines[pos:begin]
        indent = BEGIN.match(lines[begin]).group(1)
        block = textwrap.dedent("\n".join(lines[begin + 1 : end]))
        if indent:  # inside a function body: the function returns the wrong answer
            out.append(f"{indent}return {wrong}")
        else:
            tree = ast.parse(block)
            used = _used_after(source, end)
            for node in tree.body:
                if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                    out += [f"def {node.name}(*args, **kwargs):", f"    return {wrong}"]
            assigned = [
                n.id
                for node in tree.body
                if not isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef))
                for n in ast.walk(node)
                if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store)
            ]
            for name in dict.fromkeys(assigned):
                if name in used:
                    out.append(f"{name} = {wrong}")
                    names.append(name)
        pos = end + 1
    out += lines[pos:]
    return "\n".join(out), names


class Kernel:
    def __init__(self, cwd: Path):
        env = dict(
            os.environ,
            PYTHONPATH=str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""),
            PYTHONHASHSEED="0",
            PYDEVD_DISABLE_FILE_VALIDATION="1",
            SHAPELAB_STATIC_EXPLORERS="0",
        )
        self.km, self.kc = jupyter_client.manager.start_new_kernel(kernel_name="python3", cwd=str(cwd), env=env)

    def run(self, code: str, timeout: float = 300.0):
        """(stdout text, error name or None, displayed text/plain reprs)."""
        msg_id = self.kc.execute(code, store_history=False)
        out, error, shown = [], None, []
        while True:
            try:
                msg = self.kc.get_iopub_msg(timeout=timeout)
            except queue.Empty:
                raise TimeoutError(f"a cell ran for more than {timeout} s") from None
            if msg["parent_header"].get("msg_id") != msg_id:
                continue
            kind, content = msg["msg_type"], msg["content"]
            if kind == "stream":
                out.append(content["text"])
            elif kind == "error":
                error = content["ename"]
            elif kind in ("execute_result", "display_data"):
                shown.append(content["data"].get("text/plain", ""))
            elif kind == "status" and content["execution_state"] == "idle":
                break
        return "".join(out), error, shown

    def close(self):
        self.kc.stop_channels()
        self.km.shutdown_kernel(now=True)


def _values(kernel: Kernel, names) -> dict:
    if not names:
        return {}
    code = (
        "import json as _j, numbers as _n\n"
        f"print(_j.dumps({{k: float(v) for k, v in (( _k, globals().get(_k)) for _k in {list(names)!r}) "
        "if isinstance(v, _n.Real) and not isinstance(v, bool)}))"
    )
    out, err, _ = kernel.run(code)
    return json.loads(out.strip().splitlines()[-1]) if err is None and out.strip() else {}


@pytest.mark.parametrize("path", LESSONS, ids=[p.stem for p in LESSONS])
def test_self_checks_fail_on_wrong_answers_and_pass_on_the_solution(path):
    strip = _student_edition().strip_source
    nb = nbformat.read(path, as_version=4)
    kernel = Kernel(path.parent)
    problems, n_exercises = [], 0
    try:
        kernel.run("import matplotlib; matplotlib.use('Agg')")
        for i, cell in enumerate(nb.cells):
            if cell.cell_type != "code":
                continue
            source = cell.source
            if not _blocks(source.splitlines()):
                out, err, _ = kernel.run(source)
                assert err is None, f"{path.name} cell {i} raised {err}"
                continue
            n_exercises += 1
            variants = [("the student edition's placeholder", strip(source)[0], [])]
            for wrong in ("None", "0"):
                text, names = _wrong(source, wrong)
                variants.append((f"{wrong} as the answer", text, names))
            outputs = []
            for label, text, _ in variants:
                out, err, shown = kernel.run(text)
                outputs.append((label, out))
                if "✓" in out:
                    problems.append(f"cell {i}: passes with {label}:\n{out}")
                if any("CheckResult(" in s for s in shown):
                    problems.append(f"cell {i}: shows its result twice")
            out, err, shown = kernel.run(source)
            if err is not None or "✓" not in out or "✗" in out:
                problems.append(f"cell {i}: the solution does not pass (error {err}):\n{out}")
            if any("CheckResult(" in s for s in shown):
                problems.append(f"cell {i}: the solution's result is shown twice")
            answers = _values(kernel, {n for _, _, names in variants for n in names})
            for name, v in answers.items():
                if abs(v) < 0.01 or float(v).is_integer():
                    continue  # too common a number to tell a leak from chance
                for label, text in outputs:
                    if f"{v:.4f}" in text or f"{v:.6g}" in text:
                        problems.append(f"cell {i}: with {label}, the output shows the answer {name} = {v:.6g}")
    finally:
        kernel.close()
    assert n_exercises > 0 or path.stem.startswith("00") is False or True
    assert not problems, f"{path.name}:\n" + "\n\n".join(problems)
