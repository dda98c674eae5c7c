"""Editors and type checkers see the lazily exported API: every lazy package has a
current ``__init__.pyi`` (``python -m course.stubs`` writes them) and ``py.typed``."""

from __future__ import annotations

import ast

import pytest

from course import stubs


@pytest.mark.parametrize("package", stubs.PACKAGES)
def test_stub_is_current(package):
    path = stubs.stub_path(package)
    assert path.exists(), f"{path} is missing: run python -m course.stubs"
    assert path.read_text(encoding="utf-8") == stubs.stub_text(package), (
        f"{path} is stale (a lazy export was added or removed): run python -m course.stubs"
    )


@pytest.mark.parametrize("package", stubs.PACKAGES)
def test_stub_names_every_export_from_its_module(package):
    """An independent reading of the stub: each lazy export is imported from the module
    the package's map names, and the stub's ``__all__`` is the package's."""
    import importlib

    P = importlib.import_module(package)
    tree = ast.parse(stubs.stub_path(package).read_text(encoding="utf-8"))
    imported = {}
    declared_all = None
    for node in tree.body:
        if isinstance(node, ast.ImportFrom) and node.level == 1:
            for a in node.names:
                imported[a.asname or a.name] = node.module
        if isinstance(node, ast.Assign) and getattr(node.targets[0], "id", None) == "__all__":
            declared_all = ast.literal_eval(node.value)
    for name, module in P._EXPORTS.items():
        assert imported.get(name) == module, f"{package}.{name}: stub imports it from {imported.get(name)}"
    assert declared_all == list(P.__all__)


def test_py_typed_marker_ships():
    marker = stubs.ROOT / "shapelab" / "py.typed"
    assert marker.exists()
    import tomllib

    cfg = tomllib.loads((stubs.ROOT / "pyproject.toml").read_text(encoding="utf-8"))
    data = cfg["tool"]["setuptools"]["package-data"]
    assert any("py.typed" in p or "*.pyi" in p for p in sum(map(list, data.values()), [])), data
