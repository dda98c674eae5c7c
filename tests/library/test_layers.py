"""The package's layers: no import cycle and no upward import, counting the imports
inside functions (which hide a cycle from Python but not from a reader).

The layers, bottom to top (a module may import only from its own layer or below):

0. ``shapelab._toolkit``: validation, tolerances, geometry helpers, lazy exports;
1. geometry: ``balls``, ``exact`` (predicates, certification, incremental), ``power``;
2. ``filtration`` and what is computed from a filtration or from balls;
3. presentation and programs: ``plot``, ``widgets``, ``check``, ``cli``.

The test builds the graph of ``shapelab`` modules from every ``import`` statement in
each file (module level or not) and fails on a cycle among different modules, or on an
import from a lower layer into a higher one.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PKG = Path(__file__).resolve().parents[2] / "shapelab"

LAYER_1 = {"balls", "exact", "power"}
LAYER_3 = {"plot", "widgets", "check", "cli", "__main__"}


def module_name(path: Path, root: Path = PKG) -> str:
    parts = ["shapelab", *path.relative_to(root).with_suffix("").parts]
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts)


def _resolve(current: str, is_package: bool, node: ast.ImportFrom) -> list[str]:
    if node.level == 0:
        base = node.module or ""
    else:
        parts = current.split(".")
        if not is_package:
            parts = parts[:-1]
        parts = parts[: len(parts) - (node.level - 1)]
        base = ".".join(parts + ([node.module] if node.module else []))
    # "from . import cavity_report" imports a module; "from .x import name" imports x
    return [f"{base}.{a.name}" for a in node.names] + [base]


def import_graph(root: Path = PKG) -> dict[str, set[str]]:
    modules = {module_name(p, root): p for p in root.rglob("*.py")}
    graph: dict[str, set[str]] = {m: set() for m in modules}
    for m, p in modules.items():
        tree = ast.parse(p.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            targets = []
            if isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                targets = _resolve(m, p.name == "__init__.py", node)
            for t in targets:
                # the longest shapelab module that the target names
                while t and t not in modules:
                    t = t.rpartition(".")[0]
                if t and t != m and t.startswith("shapelab"):
                    graph[m].add(t)
    return graph


def cycles(graph: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components with more than one module (Tarjan)."""
    index, low, stack, on, out, counter = {}, {}, [], set(), [], [0]

    def visit(v):
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on.add(v)
        for w in sorted(graph[v]):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(graph):
        if v not in index:
            visit(v)
    return out


def layer(module: str) -> int:
    parts = module.split(".")
    if len(parts) == 1:
        return 3  # the package's own __init__: lazy re-exports of everything
    top = parts[1]
    if top == "_toolkit":
        return 0
    if top in LAYER_1:
        return 1
    if top in LAYER_3:
        return 3
    return 2


def test_no_import_cycle():
    found = cycles(import_graph())
    assert not found, f"import cycles (imports inside functions count): {found}"


def test_no_upward_import():
    g = import_graph()
    bad = sorted(
        (m, t)
        for m, ts in g.items()
        for t in ts
        if layer(t) > layer(m) and t != "shapelab"  # "shapelab" itself: the version only
    )
    assert not bad, f"a lower layer imports a higher one: {bad}"


def test_the_checks_can_fail(tmp_path):
    pkg = tmp_path / "shapelab"
    (pkg / "_toolkit").mkdir(parents=True)
    (pkg / "__init__.py").write_text("")
    (pkg / "_toolkit" / "__init__.py").write_text("")
    (pkg / "_toolkit" / "validate.py").write_text("def f():\n    from ..balls import Balls\n")
    (pkg / "balls.py").write_text("from ._toolkit.validate import f\n")
    g = import_graph(pkg)
    assert cycles(g) == [["shapelab._toolkit.validate", "shapelab.balls"]]
    assert layer("shapelab._toolkit.validate") < layer("shapelab.balls")


@pytest.mark.parametrize("module", ["shapelab.filtration", "shapelab.topology", "shapelab.cavities"])
def test_graph_sees_function_level_imports(module):
    assert module in import_graph()
