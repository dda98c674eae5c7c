"""Which public ``shapelab`` functions and classes the lessons call, read from their code cells.

    python -m course.lesson_calls            # one line per name: module, name, lessons
    python -m course.lesson_calls --names    # the dotted names only

A name counts when a code cell reaches it: ``sl.icp``, ``sl.datasets.structure``,
``check.hausdorff``, ``plot_matching.hausdorff`` (``from shapelab.plot import matching as
plot_matching``), or imports it (``from shapelab import register``, ``from shapelab.datasets
import structure``).  A name a package re-exports (the ``_EXPORTS`` tables of ``shapelab``,
``shapelab.plot``, ``shapelab.check``, ``shapelab.widgets``, and the names a package's
``__init__`` imports from its own modules) counts as the module that defines it; a module that
moved (``shapelab._MOVED``) counts under its new name.  Everything is read with ``ast``: nothing
is imported.  ``tests/library/test_examples.py`` imports each name and holds its docstring to an
``Examples`` section and its signature to full type annotations.  The lessons' code is read as
:mod:`course.lesson_map` reads it (:func:`course.lesson_map.code_of`).
"""

from __future__ import annotations

import argparse
import ast
import sys
from dataclasses import dataclass, field
from functools import cache
from pathlib import Path

from course.lesson_map import ROOT, code_of

__all__ = ["Call", "calls", "lesson_calls", "resolve"]

PACKAGE = ROOT / "shapelab"


@dataclass(frozen=True)
class _Package:
    exports: dict[str, str]  # public name -> submodule (relative)
    eager: dict[str, str]  # name the __init__ imports -> submodule (relative)
    submodules: frozenset[str]
    moved: dict[str, str]


def _file(dotted: str) -> Path | None:
    """The source file of the module ``dotted`` (``shapelab.plot.matching``), or None."""
    p = ROOT.joinpath(*dotted.split("."))
    if (p / "__init__.py").exists():
        return p / "__init__.py"
    if p.with_suffix(".py").exists():
        return p.with_suffix(".py")
    return None


def _literal(node: ast.AST) -> object:
    try:
        return ast.literal_eval(node)
    except ValueError:
        return None


@cache
def _package(dotted: str) -> _Package:
    """The lazy-export tables of the package ``dotted`` (empty for a plain module)."""
    path = _file(dotted)
    exports: dict[str, str] = {}
    eager: dict[str, str] = {}
    submodules: set[str] = set()
    moved: dict[str, str] = {}
    if path is not None and path.name == "__init__.py":
        submodules = {q.stem for q in path.parent.glob("[a-z]*.py")}
        submodules |= {q.name for q in path.parent.iterdir() if (q / "__init__.py").exists()}
        for node in ast.parse(path.read_text(encoding="utf-8")).body:
            if isinstance(node, (ast.Assign, ast.AnnAssign)):
                target = node.targets[0] if isinstance(node, ast.Assign) else node.target
                if not isinstance(target, ast.Name) or node.value is None:
                    continue
                value = _literal(node.value)
                if target.id == "_EXPORTS" and isinstance(value, dict):
                    exports = value
                elif target.id == "_SUBMODULES" and isinstance(value, (set, list, tuple)):
                    submodules |= set(value)
                elif target.id == "_MOVED" and isinstance(value, dict):
                    moved = value
            elif isinstance(node, ast.ImportFrom) and node.level == 1 and node.module:
                for a in node.names:
                    if not a.name.startswith("_"):
                        eager[a.asname or a.name] = node.module
    return _Package(exports, eager, frozenset(submodules | set(moved)), moved)


def _defined_in(module: str, name: str) -> str:
    """The module that defines ``module.name``: follows the package tables and the
    module-level ``from .x import name`` of the module itself."""
    for _ in range(10):
        parent, _sep, last = module.rpartition(".")
        if parent and last in _package(parent).moved:
            module = f"{parent}.{_package(parent).moved[last]}"
        pkg = _package(module)
        if name in pkg.exports:
            module = f"{module}.{pkg.exports[name]}"
            continue
        if name in pkg.eager:
            module = f"{module}.{pkg.eager[name]}"
            continue
        path = _file(module)
        if path is None:
            return module
        step = None
        for node in ast.parse(path.read_text(encoding="utf-8")).body:
            if isinstance(node, ast.ImportFrom) and node.level >= 1 and node.module:
                if any((a.asname or a.name) == name and a.name == name for a in node.names):
                    base = module.split(".")
                    base = base if path.name == "__init__.py" else base[:-1]
                    base = base[: len(base) - (node.level - 1)]
                    step = ".".join([*base, *node.module.split(".")])
        if step is None:
            return module
        module = step
    return module


def resolve(dotted: str) -> tuple[str, str] | None:
    """``(module, name)`` for a dotted reference such as ``shapelab.plot.disks``, or None
    when it names a module (``shapelab.plot``) or a private name.

    >>> resolve("shapelab.alpha_filtration")
    ('shapelab.filtration', 'alpha_filtration')
    >>> resolve("shapelab.plot") is None
    True
    """
    parts = dotted.split(".")
    if parts[0] != "shapelab":
        return None
    module = "shapelab"
    for i, part in enumerate(parts[1:], start=1):
        if part.startswith("_"):
            return None
        pkg = _package(module)
        if part in pkg.exports or part in pkg.eager or part not in pkg.submodules:
            # a name; what follows it (a method, an attribute) is the name's own business
            return (_defined_in(module, part), part)
        module = f"{module}.{pkg.moved.get(part, part)}"
        if i == len(parts) - 1:
            return None
    return None


def _references(code: str) -> set[str]:
    """The dotted ``shapelab...`` references of a lesson's code."""
    aliases: dict[str, str] = {}  # local name -> dotted shapelab module
    found: set[str] = set()
    tree = ast.parse(code)
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                if a.name.split(".")[0] == "shapelab":
                    if a.asname:
                        aliases[a.asname] = a.name
                    else:
                        aliases["shapelab"] = "shapelab"
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            if node.module.split(".")[0] != "shapelab":
                continue
            for a in node.names:
                dotted = f"{node.module}.{a.name}"
                if resolve(dotted) is None:
                    aliases[a.asname or a.name] = dotted
                else:
                    found.add(dotted)
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute):
            chain = []
            value: ast.AST = node
            while isinstance(value, ast.Attribute):
                chain.append(value.attr)
                value = value.value
            if isinstance(value, ast.Name) and value.id in aliases:
                found.add(".".join([aliases[value.id], *reversed(chain)]))
    return found


@dataclass(frozen=True, order=True)
class Call:
    """One public name the lessons reach: where it is defined, and which lessons call it."""

    module: str
    name: str
    lessons: tuple[str, ...] = field(default=(), compare=False)

    @property
    def qualname(self) -> str:
        return f"{self.module}.{self.name}"


def lesson_calls(path: Path) -> set[tuple[str, str]]:
    """``(defining module, name)`` of every public shapelab name the lesson ``path`` reaches."""
    out = set()
    for dotted in _references(code_of(path)):
        hit = resolve(dotted)
        if hit is not None:
            out.add(hit)
    return out


def calls(lessons: list[Path] | None = None) -> list[Call]:
    """Every public shapelab name the lessons reach, sorted by module and name."""
    if lessons is None:
        lessons = sorted(
            p for p in (ROOT / "lessons").glob("[0-9][0-9]*_*.ipynb") if not p.name.endswith(".failed.ipynb")
        )
    by: dict[tuple[str, str], list[str]] = {}
    for path in lessons:
        for hit in lesson_calls(path):
            by.setdefault(hit, []).append(path.stem.split("_")[0])
    return sorted(Call(m, n, tuple(v)) for (m, n), v in by.items())


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--names", action="store_true", help="print the dotted names only")
    args = parser.parse_args(argv)
    for c in calls():
        print(c.qualname if args.names else f"{c.module:32} {c.name:32} {' '.join(c.lessons)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
