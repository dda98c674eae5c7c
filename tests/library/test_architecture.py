"""The package's structure, read from its source with ``ast`` (no import needed).

* No module imports another module's private (underscore) name: what several
  modules share is named as shared (a public name, in the module that owns it or in
  the private toolkit ``shapelab._toolkit``, whose names are public inside the
  package).  A private *module* (``plot/_style.py``, ``widgets/_frame.py``,
  ``check/_runner.py``) may be imported by the modules of its own package.
* No module keeps a module-level cache of derived results: results derived from a
  Filtration live on it (``Filtration.derived``), not in module dictionaries.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2] / "shapelab"
MODULES = sorted(p for p in ROOT.rglob("*.py"))

# Known crossings in modules refactored on another branch (issue 11); remove an entry
# when it is fixed there.  Each is (module path relative to shapelab/, "module.name").
KNOWN: set = set()  # every crossing is gone


def _private(name: str) -> bool:
    return name.startswith("_") and not (name.startswith("__") and name.endswith("__"))


def _module_name(path: Path) -> list[str]:
    rel = path.relative_to(ROOT.parent).with_suffix("")
    parts = list(rel.parts)
    return parts[:-1] if parts[-1] == "__init__" else parts


def _resolve(path: Path, node: ast.ImportFrom) -> list[str]:
    """The absolute dotted module a ``from ... import`` names, as a list of parts."""
    if node.level == 0:
        return (node.module or "").split(".")
    pkg = _module_name(path)
    if path.name != "__init__.py":
        pkg = pkg[:-1]
    base = pkg[: len(pkg) - (node.level - 1)]
    return base + (node.module.split(".") if node.module else [])


def _is_module(parts: list[str]) -> bool:
    p = ROOT.parent.joinpath(*parts)
    return p.with_suffix(".py").exists() or (p / "__init__.py").exists()


def _package(parts: list[str]) -> list[str]:
    return parts if (ROOT.parent.joinpath(*parts) / "__init__.py").exists() else parts[:-1]


def _private_module_allowed(importer: Path, target: list[str]) -> bool:
    """May ``importer`` import the module ``target`` (given as parts)?  The toolkit from
    anywhere in shapelab; another private module only from inside its own package."""
    if "_toolkit" in target:
        return True
    private_at = [i for i, p in enumerate(target) if _private(p)]
    if not private_at:
        return True
    owner = target[: private_at[0]]
    return _module_name(importer)[: len(owner)] == owner


def crossings(path: Path) -> list[str]:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    me = _module_name(path)
    found = []
    aliases = {}  # local name -> shapelab module parts
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            target = _resolve(path, node)
            if target[:1] != ["shapelab"]:
                continue
            if not _private_module_allowed(path, target):
                found.append(".".join(target[1:]))
            for a in node.names:
                sub = target + [a.name]
                if _is_module(sub):
                    aliases[a.asname or a.name] = sub
                    if not _private_module_allowed(path, sub):
                        found.append(".".join(sub[1:]))
                elif _private(a.name) and target != me:
                    found.append(f"{target[-1]}.{a.name}")
        elif isinstance(node, ast.Import):
            for a in node.names:
                parts = a.name.split(".")
                if parts[0] == "shapelab":
                    aliases[a.asname or parts[0]] = parts if a.asname else parts[:1]
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in aliases:
            target = aliases[node.value.id]
            if _private(node.attr) and target != me and not _is_module(target + [node.attr]):
                found.append(f"{target[-1]}.{node.attr}")
    return found


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(ROOT)))
def test_no_private_name_crosses_modules(path):
    rel = str(path.relative_to(ROOT))
    bad = [c for c in crossings(path) if (rel, c) not in KNOWN]
    assert not bad, f"{rel} uses private names of other modules: {bad}"


def test_the_checker_catches_what_it_should(tmp_path):
    """The checker itself, on code written to break the rule (and to keep it)."""
    fake = ROOT / "cavities.py"

    def check(src):
        tree_path = tmp_path / "x.py"
        tree_path.write_text(src)
        # reuse the resolution rules of a real module path
        orig = Path.read_text
        try:
            Path.read_text = lambda self, encoding=None: src if self == fake else orig(self, encoding=encoding)
            return crossings(fake)
        finally:
            Path.read_text = orig

    assert check("from .persistence import _summary\n") == ["persistence._summary"]
    assert check("from . import persistence as T\nT._reduce_h1\n") == ["persistence._reduce_h1"]
    assert check("from .plot import _style\n") == ["plot._style"]
    assert check("from ._toolkit.validate import as_tau\nfrom .topology import summary\n") == []
    assert check("def _own():\n    pass\n_own()\n") == []


# ------------------------------------------------------------ module-level caches
_CACHE_FACTORIES = {"dict", "defaultdict", "OrderedDict", "WeakKeyDictionary", "WeakValueDictionary"}
_CACHE_DECORATORS = {"lru_cache", "cache"}
_DERIVED_ARGS = {"F", "filtration", "balls", "K", "complex", "diagram"}


def _call_name(node) -> str:
    f = node.func if isinstance(node, ast.Call) else node
    return f.attr if isinstance(f, ast.Attribute) else getattr(f, "id", "")


def module_caches(path: Path) -> list[str]:
    """Module-level names bound to an *empty* mutable mapping (filled later: a cache),
    any module-level weak dictionary, and memoised functions of a filtration, balls,
    complex or diagram."""
    tree = ast.parse(path.read_text(encoding="utf-8"))
    found = []
    for node in tree.body:
        if isinstance(node, (ast.Assign, ast.AnnAssign)) and node.value is not None:
            v = node.value
            empty_literal = isinstance(v, ast.Dict) and not v.keys
            factory = (
                isinstance(v, ast.Call)
                and _call_name(v) in _CACHE_FACTORIES
                and (_call_name(v).startswith("Weak") or not (v.args or v.keywords))
            )
            if empty_literal or factory:
                targets = node.targets if isinstance(node, ast.Assign) else [node.target]
                found += [ast.unparse(t) for t in targets]
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            if any(_call_name(d) in _CACHE_DECORATORS for d in node.decorator_list):
                args = {a.arg for a in node.args.args + node.args.kwonlyargs}
                if args & _DERIVED_ARGS:
                    found.append(f"@cache {node.name}({', '.join(sorted(args))})")
    return found


# Registries filled at import time by a decorator: constant once imported, not caches.
REGISTRIES = {("figures.py", "FIGURES")}


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(ROOT)))
def test_no_module_level_cache_of_derived_results(path):
    rel = str(path.relative_to(ROOT))
    bad = [c for c in module_caches(path) if (rel, c) not in REGISTRIES]
    assert bad == [], f"{rel} keeps a module-level cache: {bad}"


def test_the_cache_checker_catches_what_it_should(tmp_path):
    for src, want in [
        ("_CACHE = {}\n", ["_CACHE"]),
        ("import weakref\n_T = weakref.WeakKeyDictionary()\n", ["_T"]),
        ("from functools import lru_cache\n@lru_cache\ndef f(F):\n    pass\n", ["@cache f(F)"]),
        ("_EXPORTS = {'a': 'b'}\nfrom functools import lru_cache\n@lru_cache(8)\ndef g(p):\n    pass\n", []),
    ]:
        p = tmp_path / "m.py"
        p.write_text(src)
        assert module_caches(p) == want, src


# ------------------------------------------------------------ lazy exports match __all__

LAZY_PACKAGES = ["shapelab", "shapelab.plot", "shapelab.widgets", "shapelab.check"]


def _lazy_exports():
    import importlib

    for pkg in LAZY_PACKAGES:
        for name, module in importlib.import_module(pkg)._EXPORTS.items():
            yield pkg, name, module


@pytest.mark.parametrize("pkg, name, module", list(_lazy_exports()), ids=lambda x: str(x))
def test_every_lazy_export_resolves_to_a_name_its_module_exports(pkg, name, module):
    """A lazy export is the module's own public name: it exists, and it is in the
    module's ``__all__`` (so ``from shapelab.<module> import *``, the docs and the
    docstring checks see it too)."""
    import importlib

    mod = importlib.import_module(f"{pkg}.{module}")
    assert hasattr(mod, name), f"{pkg}.{name} points at {pkg}.{module}, which has no {name}"
    assert name in getattr(mod, "__all__", ()), f"{pkg}.{name} is exported lazily but not in {pkg}.{module}.__all__"
    assert getattr(importlib.import_module(pkg), name) is getattr(mod, name)
