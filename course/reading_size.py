"""How much public code a student reads to follow each algorithm of the course (issue 33).

    python -m course.reading_size             # a Markdown table, one row per algorithm
    python -m course.reading_size --detail    # and, per algorithm, the lines per module
    python -m course.reading_size --check     # fails when an algorithm is over ABOUT * LIMIT

The *reading size* of a public function is the number of non-blank lines (code, comments
and docstrings) of every function and class reachable from it by its calls, counted
only in public modules: a module whose dotted path has no component starting with an
underscore (``shapelab.filtration`` is public; ``shapelab._engine.certify`` and
``shapelab._toolkit.validate`` are not, and the walk stops there, as a student skips
them).  A private function *inside* a public module counts: the student meets it.

Calls are followed statically (``ast``): a name defined in the module, a name imported
from another shapelab module (``from .power import x``), or an attribute of an imported
shapelab module (``_engine.certify(...)`` stops; ``power.x(...)`` is followed).  A
class counts its own lines without its methods, plus ``__init__``/``__post_init__``;
a method counts once some reached code calls an attribute of that name.  Dynamic calls
(``getattr``, dispatch tables) are not followed, so the figure is a lower bound for
code written that way; the core is written so that it is not.
"""

from __future__ import annotations

import ast
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PACKAGE = ROOT / "shapelab"
LIMIT = 800
#: "at most about 800 lines" (issue 33): 5 % over is still about 800 (``--check``, the test)
ABOUT = 1.05

#: the algorithms the course teaches, by their public names (issue 33)
ALGORITHMS = {
    "power diagram": "power_diagram",
    "regular triangulation": "regular_triangulation",
    "α-filtration": "alpha_filtration",
    "union area and volume": "union_measure",
    "voids": "voids",
    "pockets (growth model)": "cavities.pocket.growth_pockets",
    "tunnels": "tunnels",
    "discrete flow": "discrete_flow",
    "persistence": "persistence.persistence",
    "Hausdorff distance": "hausdorff",
    "ICP": "icp",
    "optimal rotation (Horn)": "optimal_rotation",
}
#: functions that select between algorithms of the table by an option: what a student
#: reads on the default path, the selected rows' code stopped at their functions
SELECTORS = {"pockets": ("cavities.flow.flow_pockets",)}  # method="flow": the discrete flow
_CTORS = {"__init__", "__post_init__", "__new__", "__call__"}
#: calls the walk follows although no name is called: ``a @ b`` is ``a.__matmul__(b)``
#: (RigidMotion's composition in ICP) and ``len(x)`` is ``x.__len__()``.  Arithmetic
#: operators are not followed: in the reached code they are numpy's, and following them
#: would count every reached class's ``__mul__``, run or not.
_OPERATORS = {ast.MatMult: "__matmul__"}


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def is_public(module: str) -> bool:
    """True when no component of the dotted ``module`` path starts with ``_``."""
    return not any(part.startswith("_") for part in module.split("."))


def _nonblank(lines: list[str], node: ast.AST) -> int:
    start = min([node.lineno] + [d.lineno for d in getattr(node, "decorator_list", [])])
    return sum(1 for line in lines[start - 1 : node.end_lineno] if line.strip())


class _Module:
    def __init__(self, name: str, path: Path):
        self.name, self.path = name, path
        text = path.read_text(encoding="utf-8")
        self.lines = text.splitlines()
        self.tree = ast.parse(text)
        self.defs: dict[str, ast.AST] = {}
        self.imports: dict[str, tuple[str, str | None]] = {}  # local -> (module, attr or None)
        for node in self.tree.body:
            if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
                self.defs[node.name] = node
        for node in ast.walk(self.tree):
            if isinstance(node, ast.ImportFrom):
                base = self._resolve_from(node)
                for alias in node.names:
                    local = alias.asname or alias.name
                    sub = f"{base}.{alias.name}"
                    if (PACKAGE.parent / (sub.replace(".", "/") + ".py")).exists() or (
                        PACKAGE.parent / sub.replace(".", "/") / "__init__.py"
                    ).exists():
                        self.imports[local] = (sub, None)
                    else:
                        self.imports[local] = (base, alias.name)
            elif isinstance(node, ast.Import):
                for alias in node.names:
                    if alias.name.startswith("shapelab"):
                        self.imports[alias.asname or alias.name.split(".")[0]] = (
                            alias.name if alias.asname else "shapelab",
                            None,
                        )

    def _resolve_from(self, node: ast.ImportFrom) -> str:
        if node.level == 0:
            return node.module or ""
        parts = self.name.split(".")
        if self.path.name != "__init__.py":
            parts = parts[:-1]
        parts = parts[: len(parts) - (node.level - 1)]
        return ".".join(parts + ([node.module] if node.module else []))


class Reader:
    """The static walk over the package's source."""

    def __init__(self):
        self.modules: dict[str, _Module] = {}
        for path in PACKAGE.rglob("*.py"):
            mod = _Module(_module_name(path), path)
            self.modules[mod.name] = mod

    def exports(self, package: str = "shapelab") -> dict[str, str]:
        """A package's lazy exports (its ``_EXPORTS``: name -> submodule, relative)."""
        mod = self.modules.get(package)
        if mod is None or mod.path.name != "__init__.py":
            return {}
        for node in mod.tree.body:
            if isinstance(node, ast.Assign) and getattr(node.targets[0], "id", "") == "_EXPORTS":
                return ast.literal_eval(node.value)
        return {}

    def _lookup(self, module: str, name: str, depth: int = 0):
        """The (module, def node) that ``module.name`` is, following re-exports."""
        mod = self.modules.get(module)
        if mod is None or depth > 10:
            return None
        if name in mod.defs:
            return module, mod.defs[name]
        if name in mod.imports:
            target, attr = mod.imports[name]
            if attr is not None:
                return self._lookup(target, attr, depth + 1)
        exports = self.exports(module)  # a package's lazy exports (shapelab, cavities, ...)
        if name in exports:
            return self._lookup(f"{module}.{exports[name]}", name, depth + 1)
        return None

    def entry(self, public_name: str):
        """The (module, def node) of ``public_name`` (exported, or ``module.name``)."""
        if "." in public_name:
            module, _, name = public_name.rpartition(".")
            found = self._lookup(f"shapelab.{module}", name)
        else:
            found = self._lookup("shapelab", public_name)
        if found is None:
            raise KeyError(f"{public_name!r} is not a public function of shapelab")
        return found

    def reading(self, public_name: str, stop=()) -> dict[str, int]:
        """Lines per public module reachable from ``public_name`` (exported, or ``module.name``)."""
        start = self.entry(public_name)
        stops = {(m, n.lineno) for m, n in (self.entry(name) for name in stop)} - {(start[0], start[1].lineno)}
        seen: set[tuple[str, str]] = set()
        counted: dict[tuple[str, int], int] = {}
        classes: list[tuple[str, ast.ClassDef]] = []
        attrs: set[str] = set()
        todo = [start]
        while todo:
            module, node = todo.pop()
            key = (module, node.lineno)
            if key in seen or key in stops or not is_public(module):
                continue
            seen.add(key)
            mod = self.modules[module]
            bodies: list[ast.AST]
            if isinstance(node, ast.ClassDef):
                classes.append((module, node))
                methods = [n for n in node.body if isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef))]
                own = _nonblank(mod.lines, node) - sum(_nonblank(mod.lines, m) for m in methods)
                counted[key] = own
                bodies = [n for n in node.body if not isinstance(n, (ast.FunctionDef, ast.AsyncFunctionDef))]
                for m in methods:
                    if m.name in _CTORS or m.name in attrs:
                        todo.append((module, m))
                bodies += [b for b in node.bases]
            else:
                counted[key] = _nonblank(mod.lines, node)
                bodies = [node]
            for body in bodies:
                for sub in ast.walk(body):
                    if isinstance(sub, ast.Name) and isinstance(sub.ctx, ast.Load):
                        found = self._lookup(module, sub.id)
                        if found:
                            todo.append(found)
                    elif (
                        isinstance(sub, ast.Attribute)
                        or type(getattr(sub, "op", None)) in _OPERATORS
                        or (isinstance(sub, ast.Call) and isinstance(sub.func, ast.Name) and sub.func.id == "len")
                    ):
                        if isinstance(sub, ast.Attribute):
                            name = sub.attr
                        else:
                            name = "__len__" if isinstance(sub, ast.Call) else _OPERATORS[type(sub.op)]
                        if name not in attrs:
                            attrs.add(name)
                            for cmod, cls in classes:
                                for m in cls.body:
                                    if isinstance(m, (ast.FunctionDef, ast.AsyncFunctionDef)) and m.name == name:
                                        todo.append((cmod, m))
                        if (
                            isinstance(sub, ast.Attribute)
                            and isinstance(sub.value, ast.Name)
                            and sub.value.id in mod.imports
                        ):
                            target, attr = mod.imports[sub.value.id]
                            if attr is None:
                                found = self._lookup(target, sub.attr)
                                if found:
                                    todo.append(found)
            if isinstance(node, ast.ClassDef):
                continue
            for cmod, cls in classes:
                for m in cls.body:
                    if isinstance(m, (ast.FunctionDef, ast.AsyncFunctionDef)) and m.name in attrs:
                        todo.append((cmod, m))
        per_module: dict[str, int] = {}
        for (module, _), n in counted.items():
            per_module[module] = per_module.get(module, 0) + n
        return dict(sorted(per_module.items(), key=lambda kv: -kv[1]))


def sizes(own: bool = False) -> dict[str, dict[str, int]]:
    """``{algorithm: {module: lines}}`` for every algorithm of :data:`ALGORITHMS`.

    With ``own=True`` the walk stops at the other algorithms of the table (``voids``
    calls ``alpha_filtration``, which has its own row): what is new to read.
    """
    reader = Reader()
    stop = tuple(ALGORITHMS.values()) if own else ()
    return {label: reader.reading(name, stop) for label, name in ALGORITHMS.items()}


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    result, own = sizes(), sizes(own=True)
    print(
        f"| algorithm | function | reading size (lines, limit {LIMIT}) | of it new (the other rows' code not counted) | public modules |"
    )
    print("|---|---|---:|---:|---:|")
    for label, per in result.items():
        total = sum(per.values())
        print(f"| {label} | `{ALGORITHMS[label]}` | {total:,} | {sum(own[label].values()):,} | {len(per)} |")
    for name, stops in SELECTORS.items():
        n = sum(Reader().reading(name, stops).values())
        print(f"\n`{name}`, the selector, on its default path (stopped at {', '.join(stops)}): {n:,} lines")
    if "--detail" in argv:
        for label, per in result.items():
            print(f"\n{label}: " + ", ".join(f"{m} {n}" for m, n in per.items()))
    if "--check" in argv:
        over = [label for label, per in result.items() if sum(per.values()) > ABOUT * LIMIT]
        if over:
            print(f"over about {LIMIT} lines ({ABOUT * LIMIT:.0f}): {', '.join(over)}", file=sys.stderr)
            return 1
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
