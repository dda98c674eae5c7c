"""The student edition (course/student.py) and the instructor's solutions.

* The student edition of every lesson contains no solution text, no output, no
  execution count and no widget state; every code cell still parses.
* Unbalanced markers are refused, so a solution can never leak by accident.
* Every solution of the committed (executed) instructor edition passes its own
  self-check: each check it prints says "✓", none says "✗".
* The student edition of lesson 00, executed, says "not implemented yet" at the
  self-check instead of failing with an error.
"""

from __future__ import annotations

import ast
import os
import re
import textwrap
from pathlib import Path

import nbformat
import pytest

ROOT = Path(__file__).resolve().parents[2]
LESSONS = sorted((ROOT / "lessons").glob("[0-9][0-9]_*.ipynb"))
IDS = [p.stem for p in LESSONS]

# lines that may legitimately be in both editions: syntax, and the exercise's interface
TRIVIAL = {"", "return", "pass", "else:", "try:", "finally:", "continue", "break", ")", "]", "}", "):", "])"}
SIGNATURE = re.compile(r"^(async\s+)?(def|class)\s+\w+")


def _student_module():
    import course.student

    return course.student


se = _student_module()


def _solution_blocks(nb) -> tuple[list[str], list[str]]:
    """(solution lines, lines outside every solution) of an instructor notebook."""
    inside, outside = [], []
    for cell in nb.cells:
        tagged = "solution" in cell.metadata.get("tags", [])
        if cell.cell_type == "markdown":
            (inside if tagged else outside).extend(ln.strip() for ln in cell.source.splitlines())
            continue
        if cell.cell_type != "code":
            continue
        in_block = False
        for ln in cell.source.splitlines():
            if se.BEGIN.match(ln):
                in_block = True
            elif se.END.match(ln):
                in_block = False
            else:
                (inside if in_block else outside).append(ln.strip())
    return inside, outside


def _student_lines(nb) -> set[str]:
    return {ln.strip() for c in nb.cells for ln in c.source.splitlines()}


@pytest.fixture(params=LESSONS, ids=IDS)
def editions(request):
    instructor = nbformat.read(request.param, as_version=4)
    student, stats = se.student_notebook(instructor)
    return request.param, instructor, student, stats


def test_there_are_lessons():
    assert LESSONS and LESSONS[0].name == "00_start_here.ipynb"


def test_student_edition_has_no_solution_text(editions):
    path, instructor, student, stats = editions
    inside, outside = _solution_blocks(instructor)
    assert stats["exercises"] >= 1, f"{path.name}: no exercise found"
    public = set(outside)
    leaked = [
        ln
        for ln in inside
        if ln not in TRIVIAL and not SIGNATURE.match(ln) and ln not in public and ln in _student_lines(student)
    ]
    assert not leaked, f"{path.name}: solution lines in the student edition: {leaked[:5]}"
    assert not any("solution" in c.metadata.get("tags", []) for c in student.cells)


def test_student_edition_keeps_exercises_and_checks(editions):
    path, instructor, student, _ = editions
    sols = [c for c in instructor.cells if c.cell_type == "code" and "solution" in c.metadata.get("tags", [])]
    exercises = [c for c in student.cells if "exercise" in c.metadata.get("tags", [])]
    assert len(exercises) == len(sols), f"{path.name}: every exercise cell stays"
    for sol, ex in zip(sols, exercises):
        after = lambda src: src.split("# END SOLUTION", 1)[1]  # noqa: E731
        assert after(ex.source) == after(sol.source), "the self-check call after the markers is unchanged"
        assert "NotImplementedError" in ex.source, "the placeholder is there"
    n_md = sum(1 for c in instructor.cells if c.cell_type == "markdown")
    n_md_sol = sum(
        1 for c in instructor.cells if c.cell_type == "markdown" and "solution" in c.metadata.get("tags", [])
    )
    n_notes = sum(1 for c in instructor.cells if c.metadata.get("slideshow", {}).get("slide_type") == "notes")
    assert sum(1 for c in student.cells if c.cell_type == "markdown") == n_md - n_md_sol - n_notes


def test_student_edition_is_clean(editions):
    path, _, student, _ = editions
    nbformat.validate(student)
    assert "widgets" not in student.metadata, "widget state removed"
    assert not [
        c
        for c in student.cells
        if c.metadata.get("slideshow", {}).get("slide_type") == "notes" or "**Speaker notes.**" in c.source
    ], f"{path.name}: the instructor's speaker notes stay out"
    for i, cell in enumerate(student.cells):
        if cell.cell_type != "code":
            continue
        assert cell.outputs == [] and cell.execution_count is None, f"{path.name} cell {i} keeps outputs"
        assert "execution" not in cell.metadata
        if not cell.source.lstrip().startswith(("%", "!")):
            ast.parse(cell.source)  # the placeholder leaves valid Python


# ----------------------------------------------------------------- placeholders
def _strip(src: str) -> str:
    return se.strip_source(textwrap.dedent(src).strip("\n"))[0]


def test_a_function_solution_becomes_its_signature_and_a_raise():
    out = _strip('''
        # BEGIN SOLUTION
        import math
        @some_decorator
        def my_norm(v, *, p: int = 2):
            """Secret docstring."""
            return math.fsum(x ** p for x in v) ** (1 / p)
        # END SOLUTION
        check.norm(my_norm)
        ''')
    ns = {}
    exec(out.replace("check.norm(my_norm)", ""), ns)
    with pytest.raises(NotImplementedError):
        ns["my_norm"]([3, 4])
    assert "def my_norm(v, *, p: int=2):" in out
    for secret in ("fsum", "Secret", "import math", "some_decorator"):
        assert secret not in out
    assert out.endswith("check.norm(my_norm)")


def test_indented_markers_inside_a_function():
    out = _strip("""
        def my_norm(v):
            # BEGIN SOLUTION
            return sum(x * x for x in v) ** 0.5
            # END SOLUTION
        check.norm(my_norm)
        """)
    assert "sum(x * x" not in out
    ns = {}
    exec(out.replace("check.norm(my_norm)", ""), ns)
    with pytest.raises(NotImplementedError):
        ns["my_norm"]([1.0])


def test_a_value_solution_names_only_what_the_cell_uses():
    out = _strip("""
        # BEGIN SOLUTION
        helper = 2.0 * 3.0
        answer = helper + 1.0
        # END SOLUTION
        print(answer)
        """)
    assert "helper" not in out and "6.0" not in out
    with pytest.raises(NotImplementedError, match="answer"):
        exec(out, {})


def test_two_blocks_in_one_cell():
    out = _strip("""
        # BEGIN SOLUTION
        a = 1
        # END SOLUTION
        between = True
        # BEGIN SOLUTION
        def f():
            return 42
        # END SOLUTION
        """)
    assert "a = 1" not in out and "42" not in out and "between = True" in out
    assert out.count("# BEGIN SOLUTION") == 2


@pytest.mark.parametrize(
    "source",
    [
        "# BEGIN SOLUTION\nx = 1\n",  # BEGIN without END
        "x = 1\n# END SOLUTION\n",  # END without BEGIN
        "# BEGIN SOLUTION\n# BEGIN SOLUTION\nx = 1\n# END SOLUTION\n",  # nested
    ],
)
def test_unbalanced_markers_are_refused(source, tmp_path, capsys):
    nb = nbformat.v4.new_notebook(
        cells=[
            nbformat.v4.new_markdown_cell("# 99 · Bad"),
            nbformat.v4.new_code_cell(source, metadata={"tags": ["solution"]}),
        ]
    )
    bad = tmp_path / "99_bad.ipynb"
    nbformat.write(nb, bad)
    out = tmp_path / "student"
    assert se.main(["--out", str(out), str(bad)]) != 0
    assert not (out / bad.name).exists(), "nothing is written for a refused lesson"
    assert "99_bad.ipynb" in capsys.readouterr().err


def test_a_solution_cell_without_markers_is_refused():
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_code_cell("x = secret()", metadata={"tags": ["solution"]})])
    with pytest.raises(se.MarkerError, match="no '# BEGIN SOLUTION'"):
        se.student_notebook(nb)


def test_markdown_solutions_and_outputs_are_removed():
    code = nbformat.v4.new_code_cell(
        "# BEGIN SOLUTION\ny = 41 + 1\n# END SOLUTION\nprint(y)",
        metadata={"tags": ["solution"], "execution": {"iopub.execute_input": "2026-01-01T00:00:00Z"}},
        execution_count=3,
    )
    code.outputs = [nbformat.v4.new_output("stream", name="stdout", text="42\n")]
    nb = nbformat.v4.new_notebook(
        cells=[
            nbformat.v4.new_markdown_cell("Exercise: compute y."),
            nbformat.v4.new_markdown_cell("The answer is forty-two.", metadata={"tags": ["solution"]}),
            code,
        ],
        metadata={"widgets": {"state": {}}},
    )
    student, stats = se.student_notebook(nb)
    text = nbformat.writes(student)
    assert "forty-two" not in text and "41 + 1" not in text and '"42' not in text
    assert stats == {"exercises": 1, "markdown removed": 1}
    assert "widgets" not in student.metadata and student.cells[-1].execution_count is None


def test_the_sites_page_leaves_out_the_speaker_notes():
    """The site's pages keep every output but the solutions', and no speaker notes: the
    page's download button hands out its notebook (lesson 04's notes give an answer)."""
    notes = nbformat.v4.new_markdown_cell(
        "**Speaker notes.** Most answer 3, the answer is 5.25.",
        metadata={"slideshow": {"slide_type": "notes"}, "tags": ["remove-cell", "speaker-notes"]},
    )
    shown = nbformat.v4.new_code_cell("print(1)")
    shown.outputs = [nbformat.v4.new_output("stream", name="stdout", text="1\n")]
    nb = nbformat.v4.new_notebook(cells=[nbformat.v4.new_markdown_cell("# 99 · Notes"), notes, shown])
    page, _ = se.site_notebook(nb)
    assert "5.25" not in nbformat.writes(page)
    assert [c.cell_type for c in page.cells] == ["markdown", "code"] and page.cells[1].outputs


# ------------------------------------------------- the instructor's solutions pass
CHECK_LINE = re.compile(r"^(✓|✗|…)")


@pytest.mark.parametrize("path", LESSONS, ids=IDS)
def test_every_solution_passes_its_own_self_check(path):
    nb = nbformat.read(path, as_version=4)
    sols = [c for c in nb.cells if c.cell_type == "code" and "solution" in c.metadata.get("tags", [])]
    if any(c.execution_count is None for c in sols):
        pytest.skip(f"{path.name} is not executed yet (make lessons)")
    checked = 0
    for cell in sols:
        text = ""
        for out in cell.outputs:
            assert out.output_type != "error", f"{path.name}: a solution raised {out.get('ename')}"
            if out.output_type == "stream":
                text += out.text
            elif "data" in out:
                text += str(out.data.get("text/plain", ""))
        verdicts = [ln for ln in text.splitlines() if CHECK_LINE.match(ln)]
        assert not [v for v in verdicts if not v.startswith("✓")], f"{path.name}: {verdicts}"
        assert "passed=False" not in text
        assert re.search(r"\bcheck\.\w+\(", cell.source.split("# END SOLUTION")[-1]), (
            f"{path.name}: every exercise ends with a self-check call after its solution:\n{cell.source[-300:]}"
        )
        assert verdicts, f"{path.name}: a solution calls a check but no verdict was printed"
        checked += 1
    assert checked >= 1, f"{path.name}: no exercise has a self-check"


# ------------------------------------------- the student edition, executed, is kind
def test_student_edition_of_lesson_00_says_not_implemented(tmp_path, monkeypatch):
    pytest.importorskip("nbclient")
    pytest.importorskip("ipykernel")
    from nbclient import NotebookClient

    import shapelab.check as check

    try:
        check.power_distance  # noqa: B018
    except (AttributeError, ImportError) as exc:
        pytest.skip(f"shapelab.check.power_distance is not written yet ({exc})")
    student, _ = se.student_notebook(nbformat.read(LESSONS[0], as_version=4))
    monkeypatch.setenv("PYTHONPATH", str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    monkeypatch.setenv("MPLBACKEND", "Agg")
    NotebookClient(
        student, timeout=120, kernel_name="python3", allow_errors=True, resources={"metadata": {"path": str(tmp_path)}}
    ).execute()
    exercises = [c for c in student.cells if "exercise" in c.metadata.get("tags", [])]
    with_check = [c for c in exercises if "check." in c.source.split("# END SOLUTION")[-1]]
    assert with_check
    kinds = set()
    for cell in with_check:
        text = "".join(o.get("text", "") for o in cell.outputs if o.output_type == "stream")
        errors = [o for o in cell.outputs if o.output_type == "error"]
        if errors:  # a value exercise: its placeholder stops the cell before the check runs
            assert len(errors) == 1 and errors[0].ename == "NotImplementedError", errors
            assert errors[0].evalue.startswith("your code here"), errors[0].evalue
            kinds.add("value")
        else:  # a function exercise: the check runs the stub and reports, never raises
            assert "not implemented yet" in text, text
            kinds.add("function")
    assert kinds == {"value", "function"}, kinds  # lesson 00 shows students both kinds
    for i, cell in enumerate(student.cells):
        for o in cell.get("outputs", []):
            if o.output_type == "error":
                assert cell in exercises and o.ename == "NotImplementedError", (
                    f"cell {i} of the student edition fails with {o.ename}: {o.evalue}"
                )


# ------------------------------------------- the classroom image runs every lesson
def _binder_closure() -> set[str]:
    """Distributions installed by binder/requirements.txt, with their dependencies."""
    from importlib import metadata

    from packaging.requirements import Requirement

    todo = [
        Requirement(ln.split("#")[0].strip()).name
        for ln in (ROOT / "binder" / "requirements.txt").read_text().splitlines()
        if ln.split("#")[0].strip() and not ln.lstrip().startswith("-")
    ]
    # shapelab's own runtime dependencies (postBuild: pip install --no-deps -e .)
    todo += [Requirement(r).name for r in metadata.requires("shapelab") or [] if "extra ==" not in r]
    seen: set[str] = set()
    while todo:
        name = todo.pop().lower().replace("_", "-")
        if name in seen:
            continue
        seen.add(name)
        try:
            reqs = metadata.requires(name) or []
        except metadata.PackageNotFoundError:
            continue
        todo += [Requirement(r).name for r in reqs if "extra ==" not in r]
    return seen


def test_binder_environment_covers_every_lesson_import():
    import sys
    from importlib import metadata

    pytest.importorskip("packaging")
    try:
        metadata.distribution("shapelab")
    except metadata.PackageNotFoundError:
        pytest.skip("shapelab is not pip-installed here (make installs it)")
    have = _binder_closure()
    owners = metadata.packages_distributions()
    missing = set()
    for path in LESSONS:
        for cell in nbformat.read(path, as_version=4).cells:
            if cell.cell_type != "code" or cell.source.lstrip().startswith(("%", "!")):
                continue
            for node in ast.walk(ast.parse(cell.source)):
                mods = (
                    [a.name for a in node.names]
                    if isinstance(node, ast.Import)
                    else ([node.module] if isinstance(node, ast.ImportFrom) and node.module and not node.level else [])
                )
                for mod in mods:
                    top = mod.split(".")[0]
                    if top == "shapelab" or top in sys.stdlib_module_names:
                        continue
                    dists = {d.lower().replace("_", "-") for d in owners.get(top, [])}
                    if not dists & have:
                        missing.add(f"{path.name}: import {mod} ({', '.join(sorted(dists)) or 'not installed'})")
    assert not missing, "binder/requirements.txt lacks what these lessons import:\n" + "\n".join(sorted(missing))
