"""The course's commands, on Windows, macOS and Linux alike, with or without ``make``.

    python -m course setup        once: .venv with the course's pinned packages (the lab extra)
    python -m course lab          JupyterLab on 127.0.0.1 with the student edition (--instructor: solutions)
    python -m course build        execute every lesson; build the site, slides, figures, student edition
    python -m course lessons      re-execute the lessons in place (maintainers)
    python -m course test         what CI runs: lint, library tests, strict nbval on every lesson
    python -m course test-lib     the library's and the teaching layer's tests and doctests
    python -m course lint         ruff: lint and format check (part of test)
    python -m course nbval        strict nbval on every lesson, in the course's environment (no test extra)

Each command runs in the environment it needs:

* the Python running this command, when it already has this repository's ``shapelab``
  and the packages of the extra the command needs (a conda environment made from
  ``environment.yml``, a hub's image, an activated virtual environment);
* otherwise ``.venv`` at the repository's root (``SHAPELAB_VENV`` names another, relative
  to the root),
  made with this Python and filled from ``requirements/constraints.txt`` on first use,
  and again when ``pyproject.toml`` or the pins change.

Only the standard library is used here, so any Python 3.11 or later can run it.  The
``make`` targets are the short forms of these commands (see the Makefile).
"""

from __future__ import annotations

import importlib.metadata
import importlib.util
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

if sys.version_info < (3, 11):  # noqa: UP036 (any Python may run this: say why it cannot)
    raise SystemExit(f"the course needs Python 3.11 or later; this is {sys.version.split()[0]}")

import tomllib  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
PYPROJECT = ROOT / "pyproject.toml"
CONSTRAINTS = ROOT / "requirements" / "constraints.txt"
BOOK = ROOT / "book"
NODE_STAMP = BOOK / "node_modules" / ".installed"

#: command -> (extras it needs, whether it needs the book's JavaScript from npm)
NEEDS = {
    "setup": (("lab",), False),
    "lab": (("lab",), False),
    "build": (("book",), True),
    "lessons": (("book",), False),
    "student": (("book",), False),
    "figures": (("book",), False),
    "book": (("book",), True),
    "slides": (("book",), True),
    "nbval": (("lab", "book"), False),
    "test": (("test", "book"), True),
    "test-lib": (("test",), False),
    "lint": (("test",), False),
}
#: what `nbval` adds to the students' packages: the test runner only (pinned)
NBVAL_TOOLS = ("pytest", "nbval", "pytest-xdist")


def venv_dir() -> Path:
    """``SHAPELAB_VENV`` or ``.venv``; a relative path is taken from the repository's root, as
    the Makefile takes it, whatever the current directory.  An empty ``SHAPELAB_VENV`` is
    unset (as the Makefile's ``$(or ...)``): it would otherwise name the current directory,
    and the repository itself would be made a virtual environment."""
    return (ROOT / (os.environ.get("SHAPELAB_VENV", "").strip() or ".venv")).resolve()


def venv_python(venv: Path) -> Path:
    """The virtual environment's interpreter: ``Scripts\\python.exe`` on Windows."""
    return venv / ("Scripts/python.exe" if os.name == "nt" else "bin/python")


def _name(req: str) -> str:
    return re.split(r"[\s\[<>=!~;(]", req.strip(), maxsplit=1)[0].lower().replace("_", "-")


def extra_requirements(extra: str, _seen=None) -> set[str]:
    """The distribution names an extra of ``pyproject.toml`` asks for, with the core
    dependencies and the extras it names (``shapelab[lessons]``) expanded."""
    project = tomllib.loads(PYPROJECT.read_text(encoding="utf-8"))["project"]
    seen = set() if _seen is None else _seen
    if extra in seen:
        return set()
    seen.add(extra)
    out = {_name(r) for r in project["dependencies"]}
    for req in project["optional-dependencies"][extra]:
        m = re.match(r"shapelab\[([\w,\s-]+)\]", req.strip())
        if m:
            for sub in m.group(1).split(","):
                out |= extra_requirements(sub.strip(), seen)
        else:
            out.add(_name(req))
    return out


def current_python_has(extras) -> bool:
    """Whether the running Python has this repository's shapelab and every package of ``extras``."""
    spec = importlib.util.find_spec("shapelab")
    if spec is None or spec.origin is None or Path(spec.origin).resolve().parent != ROOT / "shapelab":
        return False
    for extra in extras:
        for name in extra_requirements(extra):
            try:
                importlib.metadata.version(name)
            except importlib.metadata.PackageNotFoundError:
                return False
    return True


def _newer(stamp: Path, *sources: Path) -> bool:
    return stamp.exists() and all(stamp.stat().st_mtime >= s.stat().st_mtime for s in sources)


def _run(cmd, **kw) -> None:
    rc = subprocess.call([str(c) for c in cmd], **kw)
    if rc:
        raise SystemExit(f"failed ({rc}): {' '.join(map(str, cmd))}")


def ensure_venv(extras) -> Path:
    """``.venv`` with ``extras`` installed (pinned); returns its interpreter."""
    venv = venv_dir()
    py = venv_python(venv)
    if not py.exists():
        print(f"creating {venv} with {sys.executable} (Python {sys.version.split()[0]}) ...", flush=True)
        _run([sys.executable, "-m", "venv", venv])
        _run([py, "-m", "pip", "install", "-q", "--upgrade", "pip"])
    for extra in extras:
        stamp = venv / f".installed-{extra}"
        if _newer(stamp, PYPROJECT, CONSTRAINTS):
            continue
        print(f"installing shapelab[{extra}] into {venv} (pinned by requirements/constraints.txt) ...", flush=True)
        _run([py, "-m", "pip", "install", "-q", "-c", CONSTRAINTS, "-e", f".[{extra}]"], cwd=ROOT)
        stamp.touch()
    return py


def ensure_node(required: bool) -> bool:
    """The book's JavaScript (MathJax, reveal.js, widgets, 3Dmol.js) from the npm registry."""
    if _newer(NODE_STAMP, BOOK / "package.json", BOOK / "package-lock.json"):
        return True
    npm = shutil.which("npm")
    if npm is None:
        if required:
            raise SystemExit("this command needs Node.js and npm (https://nodejs.org) for the book's JavaScript")
        print("npm unavailable: shapelab.plot.view3d will not draw in JupyterLab (everything else works)")
        return False
    print("installing the book's JavaScript from the npm registry (book/package-lock.json) ...", flush=True)
    _run([npm, "ci", "--no-audit", "--no-fund", "--loglevel=error"], cwd=BOOK)
    NODE_STAMP.touch()
    return True


def _pytest(py, *args) -> list:
    """pytest on 2 workers (``JOBS``), every test module or notebook on one worker: the
    cells of a notebook run in order in one kernel."""
    return [py, "-m", "pytest", "-n", os.environ.get("JOBS", "2"), "--dist", "loadscope", *args]


#: strict nbval, as CI runs it: the committed outputs, sanitized, against a fresh run
NBVAL = [
    "--nbval",
    "--nbval-current-env",
    "--nbval-sanitize-with",
    "tests/nbval_sanitize.cfg",
    "--nbval-cell-timeout",
    "120",
]


def command_line(command: str, py, args: list[str]) -> list[list]:
    """The commands that carry out ``command`` with interpreter ``py``."""
    simple = {
        "setup": [],
        "lab": [[py, "-m", "course.lab", *args]],
        "build": [[py, "-m", "course.build", *args]],
        "figures": [[py, "-m", "course.figures", "--out", "book/_build/figures", "--format", "svg", *args]],
        "lessons": [[py, "-m", "course.execute", *args]],
    }
    if command in simple:
        return simple[command]
    if command in ("book", "slides", "student"):
        return [[py, "-m", "course.build", "--only", command, *args]]
    if command == "nbval":
        tools = [py, "-m", "pip", "install", "-q", "-c", CONSTRAINTS, *NBVAL_TOOLS]
        return [tools, _pytest(py, *NBVAL, *(args or ["lessons"]))]
    lint = [[py, "-m", "ruff", "check", "."], [py, "-m", "ruff", "format", "--check", "."]]
    if command == "lint":
        return lint
    if command == "test":
        return [*lint, _pytest(py, *NBVAL, "--doctest-modules", *(args or ["tests", "lessons", "shapelab"]))]
    if command == "test-lib":
        return [
            _pytest(
                py, "--doctest-modules", "-p", "no:nbval", *(args or ["tests/library", "tests/teaching", "shapelab"])
            )
        ]
    raise SystemExit(f"unknown command {command!r}")


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if not argv or argv[0] in ("-h", "--help", "help"):
        print(__doc__)
        return 0
    command, args = argv[0], argv[1:]
    if command not in NEEDS:
        print(f"unknown command {command!r}\n{__doc__}", file=sys.stderr)
        return 2
    extras, node = NEEDS[command]
    here = command != "setup" and current_python_has(extras)
    py = Path(sys.executable) if here else ensure_venv(extras)
    if command in ("lab", "setup"):
        ensure_node(required=False)
    elif node:
        ensure_node(required=True)
    if command == "setup":
        print(f"ready: {py}\nnext: python -m course lab")
        return 0
    env = dict(os.environ, PYTHONPATH=str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    for cmd in command_line(command, py, args):
        rc = subprocess.call([str(c) for c in cmd], cwd=ROOT, env=env)
        if rc:
            return rc
    return 0


if __name__ == "__main__":
    sys.exit(main())
