"""The "Read the code" cell of each lesson: the core module that holds its algorithm.

    python -m course.read_the_code          # write or refresh the cell in every lesson named below
    python -m course.read_the_code --check  # fails when a cell is missing or out of date

A lesson that teaches an algorithm names the public module that holds it, with the
module's length and the functions to read, right after its first cell, and invites the
student to read it top to bottom (issue 33).  ``CODE`` is the one source: the cell is
generated from it, and ``tests/teaching/test_read_the_code.py`` checks that every named
module and function exists and that the cell says what the module is today.
"""

from __future__ import annotations

import ast
import json
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
LESSONS = ROOT / "lessons"
MARK = "**Read the code.**"

#: lesson stem -> (module path inside the repository, the functions that are the algorithm)
CODE = {
    "01_power_diagrams": ("shapelab/triangulation.py", ("power_diagram", "regular_triangulation")),
    "02_homology": ("shapelab/homology.py", ("boundary_matrix", "rank_mod2", "betti_numbers")),
    "03_dual_complex": ("shapelab/filtration.py", ("dual_complex",)),
    "04_alpha_filtration": ("shapelab/filtration.py", ("alpha_filtration",)),
    "05_union_measure": ("shapelab/measure.py", ("union_measure",)),
    "06_dual_complex_3d": ("shapelab/triangulation.py", ("regular_triangulation",)),
    "07_voids": ("shapelab/cavities/void.py", ("voids",)),
    "08_pockets": ("shapelab/cavities/pocket.py", ("pockets", "growth_pockets")),
    "09_pocket_flow": ("shapelab/cavities/flow.py", ("discrete_flow", "flow_pockets")),
    "10_tunnels": ("shapelab/cavities/tunnel.py", ("tunnels",)),
    "11_persistence": ("shapelab/persistence.py", ("reduce_boundary", "persistence")),
    "12_molecule_case_study": ("shapelab/report.py", ("report",)),
    "13_critical_points": ("shapelab/critical.py", ("critical_points",)),
    "14_hausdorff": ("shapelab/hausdorff.py", ("directed_hausdorff", "hausdorff")),
    "15_icp": ("shapelab/icp.py", ("icp",)),
    "16_quaternions": ("shapelab/quaternion.py", ("Quaternion",)),
    "17_optimal_rotation": ("shapelab/rotation.py", ("optimal_rotation",)),
    "18_docking": ("shapelab/docking.py", ("docking_score",)),
    "19_shape_classification": ("shapelab/diagrams.py", ("bottleneck_distance", "wasserstein_distance")),
    "20_binding_sites": ("shapelab/ranking.py", ("pocket_features", "rank_score")),
}


def lines_of(module: str) -> int:
    """The number of lines of the file ``module`` (a path inside the repository)."""
    return len((ROOT / module).read_text(encoding="utf-8").splitlines())


def defined(module: str) -> set[str]:
    """The top-level functions and classes the file ``module`` defines."""
    tree = ast.parse((ROOT / module).read_text(encoding="utf-8"))
    return {n.name for n in tree.body if isinstance(n, (ast.FunctionDef, ast.ClassDef))}


def text(stem: str) -> str:
    """The cell's Markdown for the lesson ``stem``."""
    module, names = CODE[stem]
    calls = ", ".join(f"`{n}`" for n in names)
    return (
        f"{MARK} This lesson's algorithm is {calls} in "
        f"[`{module}`](../{module}) ({lines_of(module):,} lines, docstrings included). "
        "Open it beside the lesson and read it top to bottom: it is written in the notes' words. "
        "Calls into `shapelab._engine` (exact predicates, certificates, fast kernels) are the "
        'machinery behind `precision="exact"`; you may skip them.'
    )


#: on the page and in the student edition, not on the slides
_METADATA = {"slideshow": {"slide_type": "skip"}}


def _cell_index(cells: list) -> int | None:
    for i, cell in enumerate(cells[:4]):
        if cell["cell_type"] == "markdown" and "".join(cell["source"]).startswith(MARK):
            return i
    return None


def refresh(path: Path, check: bool = False) -> bool:
    """Write (or, with ``check``, compare) the cell of the lesson at ``path``; True if current."""
    nb = json.loads(path.read_text(encoding="utf-8"))
    want = text(path.stem)
    i = _cell_index(nb["cells"])
    if i is not None and "".join(nb["cells"][i]["source"]) == want and nb["cells"][i]["metadata"] == _METADATA:
        return True
    if check:
        return False
    cell = {
        "cell_type": "markdown",
        "id": f"read-the-code-{path.stem[:2]}",
        "metadata": _METADATA,
        "source": want.splitlines(keepends=True),
    }
    if i is None:
        nb["cells"].insert(1, cell)
    else:
        nb["cells"][i] = {**nb["cells"][i], "source": cell["source"], "metadata": cell["metadata"]}
    path.write_text(json.dumps(nb, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
    return True


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    check = "--check" in argv
    stale = [stem for stem in CODE if not refresh(LESSONS / f"{stem}.ipynb", check=check)]
    if stale:
        print("out of date (run python -m course.read_the_code): " + ", ".join(stale), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
