"""The public API's docstrings lead somewhere: numpydoc sections in order, See Also
targets that exist, References numbered, and every public name of the documented
modules with a See Also section.

numpydoc's own validator is not a dependency; the rules checked here are the part of
its section rules (GL06/GL07, SA04) the course relies on.
"""

from __future__ import annotations

import importlib
import inspect
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
PKG = ROOT / "shapelab"

ORDER = [
    "Parameters",
    "Returns",
    "Yields",
    "Receives",
    "Other Parameters",
    "Raises",
    "Warns",
    "Warnings",
    "See Also",
    "Notes",
    "References",
    "Examples",
]

# Modules whose every public name has a See Also section.  Add a module here when its
# docstrings are complete; never remove one.
DOCUMENTED = [
    "balls",
    "tools.batch",
    "cavities",
    "cavities.cavity",
    "cavities.complement",
    "cavities.void",
    "cavities.pocket",
    "cavities.mouths",
    "cavities.tunnel",
    "check.answers",
    "check.balls",
    "check.homology",
    "check.matching",
    "check.quizzes",
    "check.rotation",
    "check.topology",
    "_engine.certify",
    "critical",
    "datasets",
    "datasets.figures",
    "datasets.molecules",
    "datasets.shapes",
    "datasets.structures",
    "diagrams",
    "distance",
    "docking",
    "embedding",
    "features",
    "filtration",
    "cavities.flow",
    "cavities.freespace",
    "homology",
    "_engine.incremental",
    "io",
    "matching",
    "measure",
    "oracles",
    "plot.balls",
    "plot.homology",
    "plot.matching",
    "plot.critical",
    "plot.hausdorff_distance",
    "plot.docking",
    "plot.classification",
    "plot.rotation",
    "plot.topology",
    "plot.viewer3d",
    "power",
    "triangulation",
    "_engine.predicates",
    "predicates",
    "quaternion",
    "registration",
    "report",
    "tools.cli",
    "simplification",
    "topology",
    "tools.trajectory",
    "tracking",
    "widgets.balls",
    "widgets.matching",
    "widgets.rotation",
    "widgets.static",
    "widgets.topology",
]


def _public_modules():
    for p in sorted(PKG.rglob("*.py")):
        rel = p.relative_to(PKG)
        if any(part.startswith("_") for part in rel.parts[:-1]):
            continue
        if rel.name.startswith("_") and rel.name != "__init__.py":
            continue
        parts = ["shapelab", *rel.with_suffix("").parts]
        if parts[-1] == "__init__":
            parts = parts[:-1]
        yield ".".join(parts)


def _public_defs():
    """(public module, name, docstring) of every function and class a public module
    lists in ``__all__`` (the lazy maps of the packages are checked against the
    modules' ``__all__`` in test_architecture), each object once, under the public
    module that exports it (``shapelab.io.read_pdb``, defined in ``shapelab.io._pdb``)."""
    seen = set()
    for module in _public_modules():
        if module in ("shapelab", "shapelab.plot", "shapelab.widgets", "shapelab.check", "shapelab.tools"):
            continue  # lazy maps: their names are their modules'
        mod = importlib.import_module(module)
        for name in getattr(mod, "__all__", ()):
            obj = getattr(mod, name)
            if not (inspect.isfunction(obj) or inspect.isclass(obj)) or id(obj) in seen:
                continue
            seen.add(id(obj))
            yield module, name, inspect.cleandoc(obj.__doc__ or "")


def _sections(doc: str) -> list[str]:
    lines = doc.splitlines()
    out = []
    for a, b in zip(lines, lines[1:]):
        if a.strip() in ORDER and b.strip() and set(b.strip()) == {"-"}:
            out.append(a.strip())
    return out


ALL = list(_public_defs())


def test_the_scan_sees_the_api():
    assert len(ALL) > 150
    assert ("shapelab.quaternion", "Quaternion") in {(m, n) for m, n, _ in ALL}


@pytest.mark.parametrize("module, name, doc", ALL, ids=[f"{m}.{n}" for m, n, _ in ALL])
def test_sections_in_numpydoc_order(module, name, doc):
    secs = _sections(doc)
    assert len(secs) == len(set(secs)), f"{module}.{name}: a section appears twice: {secs}"
    assert secs == sorted(secs, key=ORDER.index), f"{module}.{name}: sections out of order: {secs}"


def _resolve(module: str, target: str) -> bool:
    for base in (module, "shapelab", None):
        try:
            parts = target.split(".")
            if base is None:
                obj = importlib.import_module(parts[0])
                parts = parts[1:]
            else:
                obj = importlib.import_module(base)
            for p in parts:
                try:
                    obj = getattr(obj, p)
                except AttributeError:
                    obj = importlib.import_module(f"{obj.__name__}.{p}")
            return True
        except (ImportError, AttributeError):
            continue
    return False


def _see_also(doc: str) -> list[str]:
    lines = doc.splitlines()
    out, inside = [], False
    for i, line in enumerate(lines):
        s = line.strip()
        if s == "See Also" and i + 1 < len(lines) and set(lines[i + 1].strip()) == {"-"}:
            inside = True
            continue
        if inside:
            if s in ORDER and s != "See Also":
                break
            if s and set(s) != {"-"} and not line[:1].isspace():
                # a target line: "name" or "name : description"
                for t in s.split(":")[0].split(","):
                    if t.strip():
                        out.append(t.strip())
    return out


@pytest.mark.parametrize("module, name, doc", ALL, ids=[f"{m}.{n}" for m, n, _ in ALL])
def test_see_also_targets_exist(module, name, doc):
    missing = [t for t in _see_also(doc) if not _resolve(module, t)]
    assert not missing, f"{module}.{name}: See Also names what does not exist: {missing}"


@pytest.mark.parametrize("module, name, doc", ALL, ids=[f"{m}.{n}" for m, n, _ in ALL])
def test_references_numbered_in_order(module, name, doc):
    if "References" not in _sections(doc):
        return
    nums = [int(n) for n in re.findall(r"^\s*\.\. \[(\d+)\]", doc, flags=re.M)]
    assert nums == list(range(1, len(nums) + 1)), f"{module}.{name}: references {nums}"


@pytest.mark.parametrize("module", DOCUMENTED)
def test_documented_modules_lead_somewhere(module):
    undocumented = [n for m, n, d in ALL if m == f"shapelab.{module}" and "See Also" not in _sections(d)]
    assert not undocumented, f"shapelab.{module}: no See Also in {undocumented}"


def test_the_see_also_scan_can_fail():
    doc = "Summary.\n\nSee Also\n--------\nnot_a_name_anywhere\n    Nothing.\n"
    assert _see_also(doc) == ["not_a_name_anywhere"]
    assert not _resolve("shapelab.triangulation", "not_a_name_anywhere")
    assert _resolve("shapelab.triangulation", "power_diagram")
    assert _sections("A.\n\nNotes\n-----\nx\n\nParameters\n----------\n") == ["Notes", "Parameters"]
