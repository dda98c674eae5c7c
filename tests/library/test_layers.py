"""The package's layers: no import cycle and no upward import, counting the imports
inside functions (which hide a cycle from Python but not from a reader).

The layers, bottom to top (a module may import only from its own layer or below):

0. ``shapelab._toolkit``: validation, tolerances, geometry helpers, lazy exports;
1. geometry: ``balls``, the engine ``_engine`` (exact predicates, certification,
   incremental, blocks, certified orthospheres and entry times), ``predicates``,
   ``triangulation``;
2. ``filtration`` and what is computed from a filtration or from balls;
3. presentation: ``plot``, ``widgets``, ``check``;
4. the research tools beside the course: ``shapelab.tools`` (batch, cli, Dask,
   trajectories) and the program ``__main__``.  Layers 0-3 are the core: the core never
   imports the tools, directly, lazily (an import inside a function, a name of a lazy
   export map, an old path of ``shapelab._MOVED``) or through the top package
   (``import shapelab`` then ``shapelab.report_batch``); the tools may import the core.

The test builds the graph of ``shapelab`` modules from every ``import`` statement in
each file (module level or not) and from every ``importlib.import_module`` or
``__import__`` call with a literal name, and fails on a cycle among different modules,
or on an import from a lower layer into a higher one.  An old path of a moved module
(``shapelab._MOVED``: ``shapelab.batch`` is ``shapelab.tools.batch``) is an import of
the module it names now.  A name imported from a package
(``from shapelab import voids``) is an import of the module that the package's lazy
export map (``_EXPORTS``) names; ``import shapelab`` itself is an import of the top
layer (only ``__version__`` may be taken from it below).  A dynamic import (a name that
is not a literal) is allowed only in the lazy-export helper ``_toolkit.lazy``.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PKG = Path(__file__).resolve().parents[2] / "shapelab"

LAYER_1 = {"balls", "_engine", "predicates", "triangulation"}
LAYER_3 = {"plot", "widgets", "check"}
TOOLS = {"tools", "__main__"}  # layer 4, beside the course


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
    # "from . import cavity_report" imports a module (or a name the package exports);
    # "from .x import name" imports x (and name, if it is a module).  The top package
    # itself (lazy exports only) counts through the names taken from it.
    return [f"{base}.{a.name}" for a in node.names] + ([base] if "." in base else [])


def lazy_exports(root: Path = PKG) -> dict[str, str]:
    """``{"shapelab.voids": "shapelab.cavities", ...}``: every package's ``_EXPORTS`` map."""
    out = {}
    for init in root.rglob("__init__.py"):
        package = module_name(init, root)
        for node in ast.walk(ast.parse(init.read_text(encoding="utf-8"))):
            if (
                isinstance(node, ast.Assign)
                and any(isinstance(t, ast.Name) and t.id == "_EXPORTS" for t in node.targets)
                and isinstance(node.value, ast.Dict)
            ):
                for k, v in zip(node.value.keys, node.value.values):
                    if isinstance(k, ast.Constant) and isinstance(v, ast.Constant):
                        out[f"{package}.{k.value}"] = f"{package}.{v.value}"
    return out


def moved_modules(root: Path = PKG) -> dict[str, str]:
    """``{"shapelab.batch": "shapelab.tools.batch", ...}``: the package's ``_MOVED`` map."""
    out = {}
    for node in ast.walk(ast.parse((root / "__init__.py").read_text(encoding="utf-8"))):
        targets = [node.target] if isinstance(node, ast.AnnAssign) else getattr(node, "targets", [])
        if any(isinstance(t, ast.Name) and t.id == "_MOVED" for t in targets) and isinstance(node.value, ast.Dict):
            for k, v in zip(node.value.keys, node.value.values):
                if isinstance(k, ast.Constant) and isinstance(v, ast.Constant):
                    out[f"{root.name}.{k.value}"] = f"{root.name}.{v.value}"
    return out


def _moved(target: str, moves: dict[str, str]) -> str:
    for old, new in moves.items():
        if target == old or target.startswith(old + "."):
            return new + target[len(old) :]
    return target


DYNAMIC_IMPORT_ALLOWED = {"shapelab._toolkit.lazy"}


def _call_targets(current: str, is_package: bool, node: ast.Call) -> list[str] | None:
    """What ``importlib.import_module(...)`` or ``__import__(...)`` imports: a list of
    names, [] if the call is no import, None if the name is not a literal."""
    f = node.func
    name = f.attr if isinstance(f, ast.Attribute) else f.id if isinstance(f, ast.Name) else None
    if name not in ("import_module", "__import__"):
        return []
    if not node.args or not (isinstance(node.args[0], ast.Constant) and isinstance(node.args[0].value, str)):
        return None
    target = node.args[0].value
    if name == "import_module" and target.startswith("."):
        level = len(target) - len(target.lstrip("."))
        fake = ast.ImportFrom(module=target[level:] or None, names=[], level=level)
        return _resolve(current, is_package, fake)
    return [target]


def import_graph(root: Path = PKG, dynamic: list | None = None) -> dict[str, set[str]]:
    """The import graph of the package; ``dynamic`` collects (module, line) of imports
    whose name is not a literal."""
    modules = {module_name(p, root): p for p in root.rglob("*.py")}
    exports = lazy_exports(root)
    moves = moved_modules(root)
    graph: dict[str, set[str]] = {m: set() for m in modules}
    for m, p in modules.items():
        tree = ast.parse(p.read_text(encoding="utf-8"))
        is_package = p.name == "__init__.py"
        for node in ast.walk(tree):
            targets = []
            if isinstance(node, ast.Import):
                targets = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom):
                targets = _resolve(m, is_package, node)
                if len(node.names) and all(a.name == "__version__" for a in node.names):
                    continue  # the version string, from the package itself
            elif isinstance(node, ast.Call):
                targets = _call_targets(m, is_package, node)
                if targets is None:
                    if dynamic is not None and m not in DYNAMIC_IMPORT_ALLOWED:
                        dynamic.append((m, node.lineno))
                    continue
            for t in targets:
                # an old path is the module's new one; a name of a lazy export map is its module's
                t = _moved(t, moves)
                t = exports.get(t, t)
                # the longest shapelab module that the target names
                while t and t not in modules:
                    t = t.rpartition(".")[0]
                if t and t != m and t.split(".")[0] == root.name:
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
    if top in TOOLS:
        return 4
    return 2


def test_no_import_cycle():
    found = cycles(import_graph())
    assert not found, f"import cycles (imports inside functions count): {found}"


def upward_imports(graph: dict[str, set[str]]) -> list[tuple[str, str]]:
    return sorted((m, t) for m, ts in graph.items() for t in ts if layer(t) > layer(m))


def test_no_upward_import():
    bad = upward_imports(import_graph())
    assert not bad, f"a lower layer imports a higher one: {bad}"


def is_tools(module: str) -> bool:
    return layer(module) == 4


def tools_names(root: Path = PKG) -> set[str]:
    """What ``shapelab.X`` reaches in the tools: the top package's lazy exports defined
    there, its submodule ``tools`` and the old paths that now name a tools module."""
    names = {"tools"}
    names |= {k.split(".")[1] for k, v in lazy_exports(root).items() if k.count(".") == 1 and is_tools(v)}
    names |= {k.split(".")[1] for k, v in moved_modules(root).items() if is_tools(v)}
    return names


def tools_through_the_top(root: Path = PKG) -> list[tuple[str, str]]:
    """(core module, ``shapelab.X``) where a core module that imports the top package
    reaches the tools through it (the graph sees ``import shapelab``, not what is taken
    from it afterwards)."""
    reach = tools_names(root)
    found = []
    for p in sorted(root.rglob("*.py")):
        m = module_name(p, root)
        if m == root.name or is_tools(m):
            continue
        for node in ast.walk(ast.parse(p.read_text(encoding="utf-8"))):
            if (
                isinstance(node, ast.Attribute)
                and isinstance(node.value, ast.Name)
                and node.value.id == root.name
                and node.attr in reach
            ):
                found.append((m, f"{root.name}.{node.attr}"))
    return found


def test_the_core_never_imports_the_tools():
    """tools -> core -> engine, arrows down only: a course module that needed a research
    tool would make the tools part of what a student reads.  Move what the core needs
    into the core, or the caller into shapelab.tools."""
    graph = import_graph()
    bad = sorted((m, t) for m, ts in graph.items() if not is_tools(m) for t in ts if is_tools(t))
    bad += tools_through_the_top()
    assert not bad, f"the core imports shapelab.tools (tools may import the core, never the reverse): {bad}"


def test_the_tools_rule_can_fail(tmp_path):
    pkg = tmp_path / "shapelab"
    (pkg / "tools").mkdir(parents=True)
    (pkg / "__init__.py").write_text(
        '_EXPORTS = {"report_batch": "tools.batch"}\n_MOVED: dict = {"batch": "tools.batch"}\n'
    )
    (pkg / "tools" / "__init__.py").write_text("")
    (pkg / "tools" / "batch.py").write_text("from ..cavities import f\n")  # tools -> core: allowed
    (pkg / "cavities.py").write_text("def f():\n    from shapelab.batch import g\n")  # an old path
    (pkg / "report.py").write_text("from shapelab import report_batch\n")  # a lazy export
    (pkg / "check").mkdir()
    (pkg / "check" / "__init__.py").write_text("")
    (pkg / "check" / "quiz.py").write_text("import shapelab\n\ndef f():\n    return shapelab.tools\n")  # the top
    g = import_graph(pkg)
    assert g["shapelab.cavities"] == {"shapelab.tools.batch"}
    assert g["shapelab.report"] == {"shapelab.tools.batch"}
    assert upward_imports(g) == [
        ("shapelab.cavities", "shapelab.tools.batch"),
        ("shapelab.report", "shapelab.tools.batch"),
    ]
    assert tools_through_the_top(pkg) == [("shapelab.check.quiz", "shapelab.tools")]


def test_no_dynamic_import():
    dynamic = []
    import_graph(dynamic=dynamic)
    assert not dynamic, f"imports whose module name is not a literal (the graph cannot see them): {dynamic}"


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


@pytest.mark.parametrize("module", ["shapelab.filtration", "shapelab.persistence", "shapelab.cavities"])
def test_graph_sees_function_level_imports(module):
    assert module in import_graph()


@pytest.mark.parametrize(
    "source, target",
    [
        ("from shapelab import voids\n", "shapelab.cavities"),  # a lazy export: its module
        ("from .. import voids\n", "shapelab.cavities"),
        ("import shapelab\n", "shapelab"),  # the top of the package
        (
            "def f():\n    import importlib\n    return importlib.import_module('shapelab.cavities')\n",
            "shapelab.cavities",
        ),
        (
            "def f():\n    from importlib import import_module\n    return import_module('..cavities', __package__)\n",
            "shapelab.cavities",
        ),
        ("def f():\n    return __import__('shapelab.cavities')\n", "shapelab.cavities"),
    ],
)
def test_every_form_of_import_is_seen(tmp_path, source, target):
    """Forms the graph missed (issue 22, review): a name taken from the package's lazy
    exports or the package itself was exempt, and importlib calls were not read."""
    pkg = tmp_path / "shapelab"
    (pkg / "_toolkit").mkdir(parents=True)
    (pkg / "__init__.py").write_text('_EXPORTS = {"voids": "cavities"}\n__version__ = "0"\n')
    (pkg / "_toolkit" / "__init__.py").write_text("")
    (pkg / "_toolkit" / "validate.py").write_text(source)
    (pkg / "cavities.py").write_text("from ._toolkit.validate import f\n")
    g = import_graph(pkg)
    assert upward_imports(g) == [("shapelab._toolkit.validate", target)]
    if target == "shapelab.cavities":
        assert cycles(g) == [["shapelab._toolkit.validate", "shapelab.cavities"]]


def test_the_version_and_dynamic_imports(tmp_path):
    pkg = tmp_path / "shapelab"
    (pkg / "_toolkit").mkdir(parents=True)
    (pkg / "__init__.py").write_text('__version__ = "0"\n')
    (pkg / "_toolkit" / "__init__.py").write_text("")
    (pkg / "_toolkit" / "validate.py").write_text(
        "from shapelab import __version__\nimport importlib\n\ndef f(n):\n    return importlib.import_module(n)\n"
    )
    dynamic = []
    g = import_graph(pkg, dynamic=dynamic)
    assert g["shapelab._toolkit.validate"] == set()
    assert dynamic == [("shapelab._toolkit.validate", 5)]


def test_cavities_is_a_subpackage_of_the_core_layer():
    """``shapelab.cavities`` (issue 33) is one layer, the core's (2): its modules may
    import the filtration, never plot, widgets, check or the command line."""
    graph = import_graph()
    subs = [m for m in graph if m.startswith("shapelab.cavities.")]
    assert {"shapelab.cavities.void", "shapelab.cavities.pocket", "shapelab.cavities.tunnel"} <= set(subs)
    assert all(layer(m) == 2 for m in subs + ["shapelab.cavities"])
    assert not [(m, t) for m in subs for t in graph[m] if layer(t) > 2]
