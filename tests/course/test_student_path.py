"""The student's path (issue 32): what a lesson imports is what the students' extras
install, the README's commands and example work as written, the make-free commands
(``python -m course``) need no shell and no ``make``, and the lab opens the student
edition without ever overwriting a student's work.

The environment itself is proven by ``.ci/run``, which builds the course and runs strict
nbval in an environment made from the ``lab`` and ``book`` extras alone; these tests
check the declarations that environment is made from.
"""

from __future__ import annotations

import ast
import importlib.metadata
import json
import os
import re
import subprocess
import sys
import time
from pathlib import Path

import yaml

import course.__main__ as cli
import course.lab as lab
from course import lesson_map

ROOT = Path(__file__).resolve().parents[2]
LESSONS = sorted(p for p in (ROOT / "lessons").glob("[0-9][0-9]_*.ipynb") if not p.name.endswith(".failed.ipynb"))
README = (ROOT / "README.md").read_text(encoding="utf-8")
#: peers without wheels on every platform students have: never a lesson's requirement
PEERS = {"gudhi", "freesasa", "voronotalt", "open3d", "zsasa", "fpocket-rs", "pykvfinder", "pocketeer"}


def _norm(name: str) -> str:
    return re.sub(r"[-_.]+", "-", name).lower()


def _students_closure() -> set[str]:
    """Every distribution that installing the lab and book extras installs, from the
    installed packages' own metadata (markers evaluated for this Python, no extras)."""
    from packaging.requirements import Requirement

    todo = [_norm(n) for n in cli.extra_requirements("lab") | cli.extra_requirements("book")]
    seen = set()
    while todo:
        name = todo.pop()
        if name in seen:
            continue
        seen.add(name)
        try:
            reqs = importlib.metadata.requires(name) or []
        except importlib.metadata.PackageNotFoundError:
            continue
        for r in reqs:
            req = Requirement(r)
            if req.marker is None or req.marker.evaluate({"extra": ""}):
                todo.append(_norm(req.name))
    return seen


def _lesson_imports(path: Path) -> set[str]:
    tree = ast.parse(lesson_map.code_of(path))
    out = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            out |= {a.name.split(".")[0] for a in node.names}
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            out.add(node.module.split(".")[0])
    return out


def test_every_lesson_imports_only_what_the_students_extras_install():
    closure = _students_closure()
    assert {"numpy", "jupyterlab", "jupyter-book", "mdanalysis"} <= closure  # the closure is real
    assert not closure & PEERS, f"a students' extra installs a peer without wheels everywhere: {closure & PEERS}"
    dists = importlib.metadata.packages_distributions()
    problems = []
    for path in LESSONS:
        for module in sorted(_lesson_imports(path)):
            if module in sys.stdlib_module_names or module == "shapelab":
                continue
            names = {_norm(d) for d in dists.get(module, [])}
            if not names:
                problems.append(f"{path.name}: imports {module!r}, which no installed distribution provides")
            elif not names & closure:
                problems.append(
                    f"{path.name}: imports {module!r} ({', '.join(sorted(names))}), not in the lab/book extras"
                )
    assert not problems, "\n".join(problems)


def test_a_lesson_importing_a_peer_is_caught(tmp_path):
    # the test above can fail: a notebook that imports GUDHI is reported
    nb = {"cells": [{"cell_type": "code", "source": ["%matplotlib inline\n", "import gudhi\n"]}]}
    path = tmp_path / "99_peer.ipynb"
    path.write_text(json.dumps(nb))
    assert "gudhi" in _lesson_imports(path)
    assert "gudhi" not in _students_closure()


def test_readme_lists_every_lesson():
    rows = re.findall(r"^\| (\d\d) \| \[[^]]+\]\((lessons/[^)]+\.ipynb)\) \|", README, re.M)
    assert [f"lessons/{p.name}" for p in LESSONS] == [link for _, link in rows]
    assert all(num == Path(link).name[:2] for num, link in rows)


def test_readme_is_for_students_and_instructors():
    lines = README.splitlines()
    assert len(lines) <= 150, f"README has {len(lines)} lines"
    for heading in ("## Lessons", "## Set up", "## For students", "## For instructors", "## The library in one screen"):
        assert heading in README
    for word in ("SLURM", "Kubernetes", "MALLOC_TRIM_THRESHOLD_", "dask-jobqueue"):
        assert word not in README, f"{word}: researchers' material belongs in book/researchers.md"
    assert "book/researchers.md" in README and (ROOT / "book" / "researchers.md").exists()
    assert "file: researchers" in (ROOT / "book" / "_toc.yml").read_text()
    assert "MALLOC_TRIM_THRESHOLD_" in (ROOT / "book" / "researchers.md").read_text()


def test_readme_commands_exist():
    targets = set(re.findall(r"^([\w-]+(?: [\w-]+)*):", (ROOT / "Makefile").read_text(), re.M))
    targets = {t for line in targets for t in line.split()}
    for target in re.findall(r"`make ([\w-]+)", README):
        assert target in targets, f"README names `make {target}`, which the Makefile lacks"
    for command in re.findall(r"python -m course ([\w-]+)", README):
        assert command in cli.NEEDS, f"README names `python -m course {command}`, which course/__main__.py lacks"
    assert "python -m course setup" in README and "python -m course lab" in README


def test_readme_example_runs_as_written(tmp_path):
    block = README.split("## The library in one screen", 1)[1].split("```python\n", 1)[1].split("```", 1)[0]
    script = tmp_path / "example.py"
    script.write_text(block, encoding="utf-8")
    env = dict(os.environ, PYTHONPATH=str(ROOT), MPLBACKEND="Agg")
    run = subprocess.run([sys.executable, str(script)], cwd=tmp_path, env=env, capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    lines = run.stdout.splitlines()
    betti = ast.literal_eval(lines[0].split(")")[0] + ")")
    assert len(betti) == 3 and betti[0] >= 1  # (β0, β1, β2) of 50 disks
    assert "## Cavities of structure" in run.stdout and "| kind | id |" in run.stdout


def test_course_commands_need_no_make_and_no_shell(tmp_path):
    # a `make` that fails, first on the PATH: the make-free path must never call it
    fake = tmp_path / "bin"
    fake.mkdir()
    (fake / "make").write_text("#!/bin/sh\necho make was called >&2\nexit 127\n")
    (fake / "make").chmod(0o755)
    env = dict(os.environ, PATH=f"{fake}{os.pathsep}{os.environ['PATH']}")
    run = subprocess.run([sys.executable, "-m", "course", "--help"], cwd=ROOT, env=env, capture_output=True, text=True)
    assert run.returncode == 0 and "python -m course lab" in run.stdout
    run = subprocess.run([sys.executable, "-m", "course", "nope"], cwd=ROOT, env=env, capture_output=True, text=True)
    assert run.returncode == 2 and "unknown command" in run.stderr
    for path in (ROOT / "course").glob("*.py"):
        text = path.read_text(encoding="utf-8")
        assert "shell=True" not in text, path.name
        assert not re.search(r"""["']make["']""", text), f"{path.name} calls make"
        assert ".venv/bin" not in text, f"{path.name} hard-codes .venv/bin (Scripts\\ on Windows)"


def test_venv_python_on_windows_and_posix(monkeypatch, tmp_path):
    monkeypatch.setattr(cli.os, "name", "nt")
    assert cli.venv_python(tmp_path) == tmp_path / "Scripts/python.exe"
    monkeypatch.setattr(cli.os, "name", "posix")
    assert cli.venv_python(tmp_path) == tmp_path / "bin/python"


def test_venv_dir_relative_to_the_root_and_never_empty(monkeypatch, tmp_path):
    # review of issue 32: SHAPELAB_VENV= (empty) named the current directory, so `python -m
    # course lab` made the repository itself a virtual environment; a relative path followed
    # the current directory, where the Makefile takes it from the root
    monkeypatch.chdir(tmp_path)
    for unset in ("", "  "):
        monkeypatch.setenv("SHAPELAB_VENV", unset)
        assert cli.venv_dir() == cli.ROOT / ".venv"
    monkeypatch.delenv("SHAPELAB_VENV")
    assert cli.venv_dir() == cli.ROOT / ".venv"
    monkeypatch.setenv("SHAPELAB_VENV", ".venv-student")
    assert cli.venv_dir() == cli.ROOT / ".venv-student"
    monkeypatch.setenv("SHAPELAB_VENV", str(tmp_path / "env"))
    assert cli.venv_dir() == tmp_path / "env"


def test_current_python_is_used_when_it_has_the_extras():
    # this test environment has the test extra (and shapelab from this repository)
    assert cli.current_python_has(("test",))
    assert "gudhi" in cli.extra_requirements("test") and "gudhi" not in cli.extra_requirements("lab")
    assert {"numpy", "ipykernel", "jupyterlab", "mdanalysis"} <= cli.extra_requirements("lab")


def test_extra_requirements_expand_self_references():
    assert cli.extra_requirements("lessons") < cli.extra_requirements("lab")
    assert "shapelab" not in cli.extra_requirements("test")


def test_lab_opens_the_student_edition(tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(lab, "STUDENT", tmp_path / "student")
    assert lab.main(["--dry-run", "--port", "8899"]) == 0
    out = capsys.readouterr().out
    assert "student edition" in out and "/lab/tree/00_start_here.ipynb?token=" in out
    written = sorted(p.name for p in (tmp_path / "student").glob("*.ipynb"))
    assert written == [p.name for p in LESSONS]
    from course.student import solution_blocks

    placeholder = re.compile(r"\s*(#.*|raise NotImplementedError\(.*\)|(def|class) .*:|)")
    for path in (tmp_path / "student").glob("*.ipynb"):
        nb = json.loads(path.read_text(encoding="utf-8"))
        assert "**Model answer.**" not in path.read_text(encoding="utf-8"), path.name
        for cell in nb["cells"]:
            lines = "".join(cell["source"]).splitlines()
            for begin, end in solution_blocks(lines) if cell["cell_type"] == "code" else []:
                body = lines[begin + 1 : end]
                assert all(placeholder.fullmatch(line) for line in body), (path.name, body)
    assert "check." in (tmp_path / "student" / "14_hausdorff.ipynb").read_text(encoding="utf-8")
    cmd = lab.build_command(
        "t0k", "8899", as_root=False, root_dir=tmp_path / "student", open_path="00_start_here.ipynb"
    )
    assert f"--ServerApp.root_dir={tmp_path / 'student'}" in cmd and "--ServerApp.ip=127.0.0.1" in cmd


def test_lab_never_overwrites_a_students_work(tmp_path):
    dest = tmp_path / "student"
    src = tmp_path / "lessons"
    src.mkdir()
    lesson = src / LESSONS[0].name
    lesson.write_bytes(LESSONS[0].read_bytes())
    written, stale = lab.student_copy(dest, [lesson])
    assert written == [lesson.name] and stale == []
    mine = dest / lesson.name
    mine.write_text(mine.read_text(encoding="utf-8").replace("Start here", "My notes"), encoding="utf-8")
    lesson.write_text(lesson.read_text(encoding="utf-8").replace("Start here", "Begin here"), encoding="utf-8")
    later = time.time() + 10
    os.utime(lesson, (later, later))  # the lesson changed upstream (a git pull)
    written, stale = lab.student_copy(dest, [lesson])
    assert written == [] and stale == [lesson.name]
    assert "My notes" in mine.read_text(encoding="utf-8")


def test_lab_names_a_changed_lesson_even_after_the_student_saved(tmp_path):
    # review of issue 32: staleness by mtime alone was lost as soon as the student saved
    # the copy after a git pull (JupyterLab autosaves); the copy records its lesson's digest
    dest, src = tmp_path / "student", tmp_path / "lessons"
    src.mkdir()
    lesson = src / LESSONS[0].name
    lesson.write_bytes(LESSONS[0].read_bytes())
    lab.student_copy(dest, [lesson])
    mine = dest / lesson.name
    assert json.loads(mine.read_text(encoding="utf-8"))["metadata"]["shapelab"]["lesson_sha256"]
    # the lesson is re-executed (outputs, later mtime): its cells are the same, not stale
    nb = json.loads(lesson.read_text(encoding="utf-8"))
    for cell in nb["cells"]:
        if cell["cell_type"] == "code":
            cell["outputs"], cell["execution_count"] = [], None
    lesson.write_text(json.dumps(nb), encoding="utf-8")
    later = time.time() + 10
    os.utime(lesson, (later, later))
    assert lab.student_copy(dest, [lesson]) == ([], [])
    # the lesson's text changes upstream, then the student saves the copy (newer than the lesson)
    nb["cells"][0]["source"] = "# Start here, revised\n"
    lesson.write_text(json.dumps(nb), encoding="utf-8")
    saved = json.loads(mine.read_text(encoding="utf-8"))
    saved["cells"][0]["source"] = "My notes"
    mine.write_text(json.dumps(saved), encoding="utf-8")
    os.utime(mine, (later + 60, later + 60))
    assert lab.student_copy(dest, [lesson]) == ([], [lesson.name])
    assert "My notes" in mine.read_text(encoding="utf-8")
    # a copy made before the digest was recorded: the lesson's mtime decides
    del saved["metadata"]["shapelab"]
    mine.write_text(json.dumps(saved), encoding="utf-8")
    os.utime(mine, (later + 60, later + 60))
    assert lab.student_copy(dest, [lesson]) == ([], [])
    os.utime(mine, (later - 60, later - 60))
    assert lab.student_copy(dest, [lesson]) == ([], [lesson.name])


def test_lab_check_stays_on_its_port(tmp_path, monkeypatch):
    # JupyterLab moves to the next port when one is taken; the check asks the given port
    # (review of issue 32), so the server must not move
    monkeypatch.setattr(lab, "STUDENT", tmp_path / "student")
    seen = {}
    monkeypatch.setattr(lab, "check_server", lambda cmd, *a: seen.setdefault("cmd", cmd) and 0)
    assert lab.main(["--check", "--port", "8897"]) == 0
    assert "--ServerApp.port_retries=0" in seen["cmd"] and "--ServerApp.port=8897" in seen["cmd"]


def test_lab_instructor_opens_the_lessons(capsys):
    assert lab.main(["--instructor", "--dry-run"]) == 0
    out = capsys.readouterr().out
    assert "INSTRUCTOR" in out and "/lab/tree/lessons/00_start_here.ipynb?token=" in out


def test_environment_yml_installs_the_students_extras():
    env = yaml.safe_load((ROOT / "environment.yml").read_text())
    deps = env["dependencies"]
    python = next(d for d in deps if isinstance(d, str) and d.startswith("python="))
    major, minor = map(int, python.split("=")[1].split(".")[:2])
    assert (3, 11) <= (major, minor) <= (3, 14)
    pip = next(d["pip"] for d in deps if isinstance(d, dict))
    assert "-c requirements/constraints.txt" in pip and (ROOT / "requirements" / "constraints.txt").exists()
    extras = re.fullmatch(r"-e \.\[([\w,]+)\]", next(p for p in pip if p.startswith("-e"))).group(1).split(",")
    assert {"lab", "book"} <= set(extras)


def test_contributing_has_the_first_hour_and_the_current_lesson_map():
    text = (ROOT / "CONTRIBUTING.md").read_text(encoding="utf-8")
    assert "## The first hour" in text.split("## Where things go")[0]
    assert lesson_map.table() in text, "run `python -m course.lesson_map` and paste its table into CONTRIBUTING.md"
    assert "`peers`" in lesson_map.table().splitlines()[-2]  # lesson 19 uses shapelab.peers


def test_nbval_keeps_each_notebook_on_one_worker():
    # with pytest-xdist, cells of one notebook on two workers run in two kernels: NameErrors
    for command in ("nbval", "test"):
        pytest_cmd = next(c for c in cli.command_line(command, "py", []) if c[1:3] == ["-m", "pytest"])
        i = pytest_cmd.index("--dist")
        assert pytest_cmd[i + 1] == "loadscope", command
        assert "--nbval-sanitize-with" in pytest_cmd and "--nbval-current-env" in pytest_cmd
