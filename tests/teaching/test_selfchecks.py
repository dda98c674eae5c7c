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

Those three only show that a check refuses an *empty* answer.  Each exercise's answers are
then replaced by wrong answers of the right type and shape, made from the solution's own
value by ``tests/_mutants.py`` (a number 10 % off, one array entry changed, random values
of the same shape, a label replaced by another residue, a quiz answer changed, a function
wrong on one input only, ...): the cell runs up to its solution, then the rest of the cell
(the self-check) runs once per wrong answer, and each run must print "✗" (a cell with two checks refuses when one of
them does), and must not show the right value.  The answers are the names the solution block defines that
the cell's ``check.*`` call reads (or, for a solution inside a function, that function).
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

ROOT = Path(__file__).resolve().parents[2]
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


def _check_args(tree) -> set:
    """Names read by the arguments of the ``check.*(...)`` calls in ``tree``."""
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute):
            base = node.func.value
            if isinstance(base, ast.Name) and base.id == "check":
                for arg in [*node.args, *(k.value for k in node.keywords)]:
                    out |= {n.id for n in ast.walk(arg) if isinstance(n, ast.Name)}
    return out


def _split(source: str):
    """``(head, rest, answers)``: the cell up to and including its solution, the rest (the
    self-check), and the names that hold the answer.  A solution inside a function (an
    indented block) makes the function the answer, and the head ends with its ``def``."""
    lines = source.splitlines()
    ((begin, end),) = _blocks(lines)
    tree = ast.parse(source)
    holder = [n for n in tree.body if n.lineno - 1 < begin] if BEGIN.match(lines[begin]).group(1) else []
    if holder:
        split = max(holder[-1].end_lineno, end + 1)
        answers = [holder[-1].name] if isinstance(holder[-1], (ast.FunctionDef, ast.AsyncFunctionDef)) else []
    else:
        split = end + 1
        defined = []
        for node in tree.body:
            if begin < node.lineno - 1 < end:
                if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
                    defined.append(node.name)
                defined += [n.id for n in ast.walk(node) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store)]
        defined = list(dict.fromkeys(defined))
        rest_tree = ast.parse(textwrap.dedent("\n".join(lines[split:])) or "pass")
        read = _check_args(rest_tree)
        answers = [n for n in defined if n in read] or [n for n in defined if n in _used_after(source, end)]
    return "\n".join(lines[:split]), "\n".join(lines[split:]), answers


def _mutant_source(head: str, rest: str, name: str, key: str) -> str:
    """The cell's head, then its rest once per wrong answer for ``name`` (see tests/_mutants.py),
    each run's output after a line ``@@mutant <label>``; the solution's value is put back."""
    return "\n".join(
        [
            head,
            "import tests._mutants as _m_",
            f"_m_solution_ = {name}",
            f"for _m_label_, _m_wrong_ in _m_.mutants(_m_solution_, {key!r}, globals()):",
            f"    {name} = _m_wrong_",
            "    print('@@mutant ' + _m_label_, flush=True)",
            "    try:",
            f"        exec(compile({rest!r}, '<the self-check>', 'exec'), globals())",
            "    except Exception as _m_exc_:",
            "        print(f'@@raised {type(_m_exc_).__name__}: {_m_exc_}', flush=True)",
            f"{name} = _m_solution_",
        ]
    )


def _runs(out: str) -> list:
    """``[(label, output)]`` of a mutant cell's runs."""
    runs = []
    for line in out.splitlines():
        if line.startswith("@@mutant "):
            runs.append([line[len("@@mutant ") :], ""])
        elif runs:
            runs[-1][1] += line + "\n"
    return [tuple(r) for r in runs]


@pytest.mark.parametrize("path", LESSONS, ids=[p.stem for p in LESSONS])
def test_self_checks_fail_on_wrong_answers_and_pass_on_the_solution(path):
    strip = _student_edition().strip_source
    nb = nbformat.read(path, as_version=4)
    kernel = Kernel(path.parent)
    problems, n_exercises, n_mutants = [], 0, 0
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
            head, rest, names = _split(source)
            if not names:
                problems.append(f"cell {i}: no answer found to replace with wrong ones")
            mutated = []  # (answer name, what, output)
            for name in names:
                out, err, _ = kernel.run(_mutant_source(head, rest, name, f"{path.stem}:{name}"))
                runs = _runs(out)
                if err is not None or not runs:
                    problems.append(f"cell {i}: no wrong answer of the right type for {name} (error {err}):\n{out}")
                for label, text in runs:
                    what = f"{name} = {label}"
                    mutated.append((name, what, text))
                    if "✗" not in text:  # a cell with two checks refuses when one of them does
                        problems.append(f"cell {i}: the check does not refuse {what}:\n{text}")
                    if "@@raised" in text or "@@unsupported" in text:
                        problems.append(f"cell {i}: with {what}, the cell broke instead of checking:\n{text}")
                n_mutants += len(runs)
            # the solution last, so that the later cells see its values
            out, err, shown = kernel.run(source)
            if err is not None or "✓" not in out or "✗" in out:
                problems.append(f"cell {i}: the solution does not pass (error {err}):\n{out}")
            if any("CheckResult(" in s for s in shown):
                problems.append(f"cell {i}: the solution's result is shown twice")
            answers = _values(kernel, {n for _, _, names in variants for n in names} | set(names))
            # a wrong answer's output shows the student's (wrong) value, never the right one
            shows = [(n, label, text) for n in answers for label, text in outputs]
            shows += [(n, what, text) for n, what, text in mutated]
            for name, label, text in shows:
                v = answers.get(name)
                if v is None or abs(v) < 0.01 or float(v).is_integer():
                    continue  # too common a number to tell a leak from chance
                if f"{v:.4f}" in text or f"{v:.6g}" in text:
                    problems.append(f"cell {i}: with {label}, the output shows the answer {name} = {v:.6g}")
    finally:
        kernel.close()
    assert not problems, f"{path.name}:\n" + "\n\n".join(problems)
    assert n_mutants >= n_exercises, f"{path.name}: {n_mutants} wrong answers for {n_exercises} exercises"
