"""Which ``shapelab`` modules each lesson uses, read from its code cells.

    python -m course.lesson_map        # the Markdown table of CONTRIBUTING.md, "The first hour"

A name counts when a code cell imports it (``from shapelab import voids``, ``from
shapelab.datasets import structure``) or reaches it as an attribute (``sl.icp``,
``shapelab.plot``); a name the package re-exports counts as the module that defines it
(``shapelab._EXPORTS``).  ``tests/course/test_student_path.py`` fails while the table in
CONTRIBUTING.md differs from this one.
"""

from __future__ import annotations

import ast
import json
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def _exports() -> tuple[dict[str, str], set[str]]:
    tree = ast.parse((ROOT / "shapelab" / "__init__.py").read_text(encoding="utf-8"))
    exports, submodules = {}, set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Assign) and isinstance(node.targets[0], ast.Name):
            if node.targets[0].id == "_EXPORTS":
                exports = ast.literal_eval(node.value)
            elif node.targets[0].id == "_SUBMODULES":
                submodules = set(ast.literal_eval(node.value))
    modules = submodules | set(exports.values())
    modules |= {p.stem for p in (ROOT / "shapelab").glob("[a-z]*.py")}
    modules |= {p.name for p in (ROOT / "shapelab").iterdir() if p.is_dir() and (p / "__init__.py").exists()}
    return exports, modules


def code_of(path: Path) -> str:
    cells = json.loads(path.read_text(encoding="utf-8"))["cells"]
    text = "\n".join("".join(c["source"]) for c in cells if c["cell_type"] == "code")
    return "\n".join("" if line.lstrip().startswith(("%", "!")) else line for line in text.splitlines())


def modules_used(path: Path) -> list[str]:
    exports, modules = _exports()
    code = code_of(path)
    used, aliases = set(), {"shapelab"}
    for node in ast.walk(ast.parse(code)):
        if isinstance(node, ast.Import):
            for a in node.names:
                if a.name.split(".")[0] == "shapelab":
                    parts = a.name.split(".")
                    if len(parts) > 1:
                        used.add(parts[1])
                    aliases.add(a.asname or "shapelab")
        elif isinstance(node, ast.ImportFrom) and node.module and node.module.split(".")[0] == "shapelab":
            parts = node.module.split(".")
            if len(parts) > 1:
                used.add(parts[1])
            else:
                for a in node.names:
                    used.add(a.name if a.name in modules else exports.get(a.name, a.name).split(".")[0])
    for m in re.finditer(r"\b(\w+)\.(\w+)", code):
        if m.group(1) in aliases:
            name = m.group(2)
            used.add(name if name in modules else exports.get(name, name).split(".")[0])
    return sorted(u for u in used if u in modules)


def table() -> str:
    rows = ["| lesson | shapelab modules it uses |", "|---|---|"]
    for path in sorted((ROOT / "lessons").glob("[0-9][0-9]_*.ipynb")):
        if path.name.endswith(".failed.ipynb"):
            continue
        rows.append(f"| {path.stem} | " + ", ".join(f"`{m}`" for m in modules_used(path)) + " |")
    return "\n".join(rows)


if __name__ == "__main__":
    print(table())
    sys.exit(0)
