"""The course map: which lessons each lesson needs, and two suggested paths (issue 34).

    python -m course.prerequisites            # the map as Markdown (lesson → needs, the weeks)
    python -m course.prerequisites --write    # book/course_map.md's generated part and book/course_map.svg

This module is the one source of the lessons' dependency graph.  Every lesson's first
cell has a ``**Prerequisites:**`` paragraph that links exactly the lessons
:data:`PREREQUISITES` gives it (``tests/course/test_prerequisites.py``), the book's
course map (``book/course_map.md``) draws the graph with :func:`figure` and lists it
with :func:`table`, and the two paths, :data:`WEEKS_6` and :data:`WEEKS_12`, put every
lesson in one week.

Lessons are named by their file stems (``"04_alpha_filtration"``), and nothing else
here names a lesson: a renaming of the lessons is a plain substitution of their stems
in this file.  A lesson's number is the part of its stem before the first ``_``, and
the course's order is the order of the stems as strings (``"01_…" < "01b_…" < "02_…"``).

A lesson's prerequisites are the earlier lessons whose results, functions or
definitions it uses directly (not the lessons those need in turn): :func:`closure` adds
those, and :func:`reduction` drops an arrow that a longer path implies, for the figure.
"""

from __future__ import annotations

import json
import re
import sys
import textwrap
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
LESSONS = ROOT / "lessons"
PAGE = ROOT / "book" / "course_map.md"
SVG = ROOT / "book" / "course_map.svg"

#: lesson → the earlier lessons it uses directly (their stems)
PREREQUISITES: dict[str, tuple[str, ...]] = {
    "00_start_here": (),
    "01_power_diagrams": ("00_start_here",),
    "02_homology": ("01_power_diagrams",),
    "03_dual_complex": ("01_power_diagrams", "02_homology"),
    "04_alpha_filtration": ("01_power_diagrams", "02_homology", "03_dual_complex"),
    "05_union_measure": ("01_power_diagrams", "02_homology", "03_dual_complex", "04_alpha_filtration"),
    "06_dual_complex_3d": ("02_homology", "03_dual_complex", "04_alpha_filtration"),
    "07_voids": ("02_homology", "04_alpha_filtration", "06_dual_complex_3d"),
    "08_pockets": ("02_homology", "04_alpha_filtration", "07_voids"),
    "09_pocket_flow": ("01_power_diagrams", "07_voids", "08_pockets"),
    "10_tunnels": ("02_homology", "07_voids", "08_pockets"),
    "11_persistence": ("02_homology", "08_pockets", "10_tunnels"),
    "12_molecule_case_study": ("08_pockets", "10_tunnels", "11_persistence"),
    "13_critical_points": ("00_start_here",),
    "14_hausdorff": ("00_start_here",),
    "15_icp": ("13_critical_points", "14_hausdorff"),
    "16_quaternions": ("00_start_here",),
    "17_optimal_rotation": ("15_icp", "16_quaternions"),
    "18_docking": (
        "05_union_measure",
        "08_pockets",
        "12_molecule_case_study",
        "14_hausdorff",
        "15_icp",
        "17_optimal_rotation",
    ),
    "19_shape_classification": ("02_homology", "04_alpha_filtration", "07_voids", "11_persistence"),
    "20_binding_sites": ("08_pockets", "09_pocket_flow", "12_molecule_case_study", "18_docking"),
}

#: the lessons being written under these stems, with working titles until they exist
PLANNED: dict[str, str] = {
    "02_homology": "Homology over Z/2",
    "09_pocket_flow": "The discrete flow and real pockets",
}

#: the course's parts (each ends with its quiz, in lessons 06, 12 and 17), for the figure
PARTS: tuple[tuple[str, tuple[str, ...]], ...] = (
    (
        "I · The union of balls",
        (
            "00_start_here",
            "01_power_diagrams",
            "02_homology",
            "03_dual_complex",
            "04_alpha_filtration",
            "05_union_measure",
            "06_dual_complex_3d",
        ),
    ),
    (
        "II · Voids, pockets, tunnels, persistence",
        ("07_voids", "08_pockets", "09_pocket_flow", "10_tunnels", "11_persistence", "12_molecule_case_study"),
    ),
    ("III · Shape matching", ("13_critical_points", "14_hausdorff", "15_icp", "16_quaternions", "17_optimal_rotation")),
    ("Applications", ("18_docking", "19_shape_classification", "20_binding_sites")),
)

#: a 12-week course: one or two lessons a week, every "Going deeper" section kept
WEEKS_12: tuple[tuple[str, ...], ...] = (
    ("00_start_here", "01_power_diagrams"),
    ("02_homology",),
    ("03_dual_complex", "04_alpha_filtration"),
    ("05_union_measure", "06_dual_complex_3d"),
    ("07_voids",),
    ("08_pockets", "09_pocket_flow"),
    ("10_tunnels", "11_persistence"),
    ("12_molecule_case_study",),
    ("13_critical_points", "14_hausdorff"),
    ("15_icp", "16_quaternions"),
    ("17_optimal_rotation", "18_docking"),
    ("19_shape_classification", "20_binding_sites"),
)

#: a 6-week course: three or four lessons a week, every "Going deeper" section skipped
WEEKS_6: tuple[tuple[str, ...], ...] = (
    ("00_start_here", "01_power_diagrams", "02_homology"),
    ("03_dual_complex", "04_alpha_filtration", "05_union_measure"),
    ("06_dual_complex_3d", "07_voids", "08_pockets", "09_pocket_flow"),
    ("10_tunnels", "11_persistence", "12_molecule_case_study"),
    ("13_critical_points", "14_hausdorff", "15_icp", "16_quaternions"),
    ("17_optimal_rotation", "18_docking", "19_shape_classification", "20_binding_sites"),
)

#: what each path does with the sections headed "Going deeper" (course.wordcount counts them apart)
GOING_DEEPER = {
    "WEEKS_6": "skip every section headed “Going deeper” (each lesson's core stays within 3,000 words)",
    "WEEKS_12": "keep every section headed “Going deeper”",
}


def number(stem: str) -> str:
    """The lesson's number as the course writes it: ``"03"``, ``"01b"``."""
    return stem.split("_", 1)[0]


def lessons() -> list[str]:
    """Every lesson of the map, in the course's order."""
    return sorted(PREREQUISITES)


def title(stem: str) -> str:
    """The lesson's title, from its first heading (``# 03 · The growth model …``), or
    the working title of a lesson not yet written."""
    path = LESSONS / f"{stem}.ipynb"
    if path.exists():
        first = "".join(json.loads(path.read_text(encoding="utf-8"))["cells"][0]["source"])
        m = re.match(r"#\s+\S+\s+·\s+(.+)", first.strip())
        if m:
            return m.group(1).strip()
    return PLANNED.get(stem, stem)


def closure(stem: str) -> set[str]:
    """Every lesson ``stem`` builds on: its prerequisites, theirs, and so on."""
    seen: set[str] = set()
    todo = list(PREREQUISITES[stem])
    while todo:
        s = todo.pop()
        if s not in seen:
            seen.add(s)
            todo.extend(PREREQUISITES[s])
    return seen


def reduction() -> list[tuple[str, str]]:
    """The arrows (prerequisite, lesson) that no longer path implies: what the figure draws."""
    edges = []
    for stem, needs in PREREQUISITES.items():
        for p in needs:
            if not any(p in closure(q) for q in needs if q != p):
                edges.append((p, stem))
    return sorted(edges, key=lambda e: (e[1], e[0]))


def cycle() -> list[str] | None:
    """A cycle of the graph if it has one (depth-first search), else ``None``."""
    state: dict[str, int] = {}

    def visit(s, path):
        state[s] = 1
        for p in PREREQUISITES.get(s, ()):
            if state.get(p) == 1:
                return path + [s, p]
            if p not in state:
                found = visit(p, path + [s])
                if found:
                    return found
        state[s] = 2
        return None

    for s in PREREQUISITES:
        if s not in state:
            found = visit(s, [])
            if found:
                return found
    return None


def _link(stem: str, prefix: str) -> str:
    return f"[{number(stem)}]({prefix}{stem}.ipynb)"


def table(prefix: str = "lessons/") -> str:
    """The graph as a Markdown table a screen reader reads row by row: lesson, title,
    the lessons it needs, every lesson it builds on."""
    rows = [
        "| lesson | title | needs | builds on (all, with what those need) |",
        "|---|---|---|---|",
    ]
    for stem in lessons():
        needs = ", ".join(_link(p, prefix) for p in PREREQUISITES[stem]) or "none"
        allof = ", ".join(number(p) for p in sorted(closure(stem))) or "none"
        rows.append(f"| {_link(stem, prefix)} | {title(stem)} | {needs} | {allof} |")
    return "\n".join(rows)


def weeks(path: tuple[tuple[str, ...], ...], prefix: str = "lessons/") -> str:
    """A path as a Markdown table: week, its lessons."""
    rows = ["| week | lessons |", "|---|---|"]
    for i, week in enumerate(path, 1):
        rows.append(f"| {i} | " + "; ".join(f"{_link(s, prefix)} {title(s)}" for s in week) + " |")
    return "\n".join(rows)


def describe() -> str:
    """The figure's text alternative: its layout and every arrow it draws."""
    red = reduction()
    arrows = "; ".join(
        f"{number(p)} to {', '.join(number(s) for q, s in red if q == p)}"
        for p in lessons()
        if any(q == p for q, _ in red)
    )
    parts = "; ".join(
        f"{'part ' + name.split(' · ')[0] if ' · ' in name else name.lower()}: lessons {', '.join(number(s) for s in ss)}"
        for name, ss in PARTS
    )
    return (
        f"The course map: the {len(PREREQUISITES)} lessons as boxes in one row per part ({parts}), "
        "each further right than every lesson it needs. An arrow leads from a lesson to a lesson that "
        f"needs it (arrows implied by a longer path are left out): {arrows}. The table below lists the same graph."
    )


def _depth() -> dict[str, int]:
    depth: dict[str, int] = {}
    for s in lessons():  # prerequisites come earlier in this order
        depth[s] = 1 + max((depth[p] for p in PREREQUISITES[s]), default=-1)
    return depth


def figure():
    """The dependency graph drawn with matplotlib: a row per part, a column per depth
    (the longest chain of prerequisites below a lesson), an arrow per edge of
    :func:`reduction`.  Returns a ``matplotlib.figure.Figure``."""
    from matplotlib.figure import Figure
    from matplotlib.patches import FancyArrowPatch

    colours = ("#0072B2", "#009E73", "#D55E00", "#CC79A7")  # Okabe–Ito, one per part
    depth = _depth()
    pos: dict[str, tuple[float, float]] = {}
    part_of: dict[str, int] = {}
    for row, (_, stems) in enumerate(PARTS):
        used: dict[int, int] = {}
        for s in stems:
            k = used.get(depth[s], 0)
            used[depth[s]] = k + 1
            pos[s] = (depth[s] + 0.3 * k, -3.0 * row - 1.3 * k)
            part_of[s] = row
    first = lessons()[0]
    pos[first] = (0.0, -3.0)  # the start, between the parts it leads to
    fig = Figure(figsize=(16, 9), layout="constrained")
    ax = fig.add_subplot()
    for p, s in reduction():
        (x0, y0), (x1, y1) = pos[p], pos[s]
        bend = 0.0 if abs(y1 - y0) < 1e-9 and x1 - x0 <= 1 else 0.12 if y1 >= y0 else -0.12
        ax.add_patch(
            FancyArrowPatch(
                (x0, y0),
                (x1, y1),
                connectionstyle=f"arc3,rad={bend}",
                arrowstyle="-|>",
                mutation_scale=16,
                lw=1.3,
                color="#555555",
                shrinkA=22,
                shrinkB=22,
                zorder=1,
            )
        )
    for s, (x, y) in pos.items():
        ax.text(
            x,
            y,
            number(s),
            ha="center",
            va="center",
            fontsize=15,
            fontweight="bold",
            color="white",
            zorder=3,
            bbox={"boxstyle": "round,pad=0.45", "fc": colours[part_of[s]], "ec": "black", "lw": 1.0},
        )
        lines = textwrap.wrap(title(s), 17)
        short = "\n".join(lines[:3]) + (" …" if len(lines) > 3 else "")
        ax.text(x, y - 0.38, short, ha="center", va="top", fontsize=7.5, linespacing=1.0, zorder=3)
    for row, (name, _) in enumerate(PARTS):
        ax.text(-0.7, -3.0 * row + 0.55, name, ha="left", va="bottom", fontsize=12, color=colours[row])
    ax.set_xlim(-0.8, max(depth.values()) + 0.8)
    ax.set_ylim(-3.0 * (len(PARTS) - 1) - 1.2, 1.2)
    ax.set_axis_off()
    ax.set_title("Course map: an arrow leads from a lesson to a lesson that needs it", fontsize=14)
    return fig


BEGIN = "<!-- begin: written by python -m course.prerequisites --write; edit course/prerequisites.py -->"
END = "<!-- end: written by python -m course.prerequisites --write -->"


def generated() -> str:
    """The part of book/course_map.md that this module writes."""
    return "\n\n".join(
        [
            "## Lesson → the lessons it needs",
            table(),
            "## A 12-week course",
            f"One or two lessons a week; {GOING_DEEPER['WEEKS_12']}.",
            weeks(WEEKS_12),
            "## A 6-week course",
            f"Three or four lessons a week; {GOING_DEEPER['WEEKS_6']}.",
            weeks(WEEKS_6),
        ]
    )


def write_page(page: Path = PAGE, svg: Path = SVG) -> None:
    """Rewrite the generated part of the course map page and its figure."""
    from course.figures import save

    text = page.read_text(encoding="utf-8")
    start, end = text.index(BEGIN) + len(BEGIN), text.index(END)
    page.write_text(text[:start] + "\n\n" + generated() + "\n\n" + text[end:], encoding="utf-8")
    save(figure(), svg, alt=describe())


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    if "--write" in argv:
        write_page()
        print(f"wrote {PAGE.relative_to(ROOT)} and {SVG.relative_to(ROOT)}")
    else:
        print(generated())
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
