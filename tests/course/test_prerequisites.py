"""The course map (course/prerequisites.py) is the one source of the lessons' dependencies:
every lesson's Prerequisites paragraph links exactly the lessons it gives, the graph is
acyclic and points only backwards, each path puts every lesson in exactly one week after
what it needs, and the book's course map shows the same graph."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from course import prerequisites as pr

ROOT = Path(__file__).resolve().parents[2]
LESSONS = sorted((ROOT / "lessons").glob("[0-9][0-9]*_*.ipynb"))
LINK = re.compile(r"\]\((?:\.\./)?(?:lessons/)?([0-9]{2}[a-z]?_[A-Za-z0-9_]+)\.ipynb\)")


def _first_cell(path: Path) -> str:
    return "".join(json.loads(path.read_text(encoding="utf-8"))["cells"][0]["source"])


def prerequisites_paragraph(text: str) -> str | None:
    """The paragraph of ``text`` that starts with **Prerequisites:**, or None."""
    for para in re.split(r"\n\s*\n", text):
        if para.lstrip().startswith("**Prerequisites:**"):
            return para
    return None


def linked_lessons(paragraph: str) -> set[str]:
    return set(LINK.findall(paragraph))


def test_every_lesson_is_on_the_map():
    stems = {p.stem for p in LESSONS}
    assert stems, "no lesson found"
    assert not stems - set(pr.PREREQUISITES), (
        f"lessons missing from course/prerequisites.py: {sorted(stems - set(pr.PREREQUISITES))}"
    )
    missing = set(pr.PREREQUISITES) - stems - set(pr.PLANNED)
    assert not missing, f"on the map but neither a lesson nor planned: {sorted(missing)}"


@pytest.mark.parametrize("path", LESSONS, ids=[p.stem for p in LESSONS])
def test_prerequisites_paragraph_names_exactly_the_maps_lessons(path):
    first = _first_cell(path)
    para = prerequisites_paragraph(first)
    assert para is not None, f"{path.name}: the first cell has no **Prerequisites:** paragraph"
    assert first.index("Learning goals") < first.index("**Prerequisites:**"), (
        f"{path.name}: Prerequisites come after the learning goals"
    )
    assert linked_lessons(para) == set(pr.PREREQUISITES[path.stem]), (
        f"{path.name}: the paragraph links {sorted(linked_lessons(para))}, "
        f"course/prerequisites.py gives {sorted(pr.PREREQUISITES[path.stem])}"
    )
    assert "notation.md" in para, f"{path.name}: link the notation table from the Prerequisites paragraph"


def test_the_paragraph_reader_sees_links_and_nothing_else():
    para = "**Prerequisites:** [lesson 02](02_homology.ipynb) (Betti numbers) and [lesson 04](04_alpha_filtration.ipynb); the [notation](../book/notation.md)."
    assert linked_lessons(para) == {"02_homology", "04_alpha_filtration"}
    assert prerequisites_paragraph("# T\n\n## Learning goals\n\n- x\n\n" + para) == para
    assert prerequisites_paragraph("# T\n\nPrerequisites: none") is None


def test_the_graph_points_backwards_and_has_no_cycle():
    for stem, needs in pr.PREREQUISITES.items():
        assert stem not in needs, stem
        assert len(set(needs)) == len(needs), f"{stem}: a prerequisite twice"
        for p in needs:
            assert p in pr.PREREQUISITES, f"{stem} needs {p}, which is not on the map"
            assert p < stem, f"{stem} needs {p}, a later lesson"
    assert pr.cycle() is None


def test_cycle_finds_a_cycle(monkeypatch):
    monkeypatch.setattr(pr, "PREREQUISITES", {"01_a": ("02_b",), "02_b": ("01_a",), "00_c": ()})
    assert set(pr.cycle()) == {"01_a", "02_b"}


def test_reduction_drops_only_implied_arrows(monkeypatch):
    monkeypatch.setattr(pr, "PREREQUISITES", {"00_a": (), "01_b": ("00_a",), "02_c": ("00_a", "01_b")})
    assert pr.reduction() == [("00_a", "01_b"), ("01_b", "02_c")]
    assert pr.closure("02_c") == {"00_a", "01_b"}


@pytest.mark.parametrize("name", ["WEEKS_6", "WEEKS_12"])
def test_every_lesson_is_in_exactly_one_week_after_what_it_needs(name):
    path = getattr(pr, name)
    assert len(path) == int(name.split("_")[1])
    order = [s for week in path for s in week]
    assert sorted(order) == sorted(pr.PREREQUISITES), f"{name}: each lesson exactly once"
    week_of = {s: i for i, week in enumerate(path) for s in week}
    for stem in order:
        for p in pr.PREREQUISITES[stem]:
            assert order.index(p) < order.index(stem) and week_of[p] <= week_of[stem], f"{name}: {stem} before {p}"
    assert name in pr.GOING_DEEPER


def test_the_book_page_shows_the_same_graph():
    page = (ROOT / "book" / "course_map.md").read_text(encoding="utf-8")
    start, end = page.index(pr.BEGIN) + len(pr.BEGIN), page.index(pr.END)
    rows = [line for line in page[start:end].splitlines() if line.startswith("| [")]
    table = {}
    for line in rows:
        cells = [c.strip() for c in line.strip("|").split("|")]
        if len(cells) == 4:  # lesson | title | needs | builds on
            (stem,) = linked_lessons(cells[0])
            table[stem] = linked_lessons(cells[2])
    assert table == {s: set(n) for s, n in pr.PREREQUISITES.items()}, "run python -m course.prerequisites --write"
    weeks = [line for line in page[start:end].splitlines() if re.match(r"\| \d+ \|", line)]
    listed = [linked_lessons(w) for w in weeks]
    assert listed == [set(w) for w in pr.WEEKS_12] + [set(w) for w in pr.WEEKS_6], (
        "run python -m course.prerequisites --write"
    )


def test_the_figure_and_its_text_alternative_are_current():
    from course.sphinx_a11y import svg_alt

    assert svg_alt(pr.SVG) == pr.describe(), "run python -m course.prerequisites --write"
    fig = pr.figure()
    boxes = [t.get_text() for t in fig.axes[0].texts]
    assert all(pr.number(s) in boxes for s in pr.PREREQUISITES)
    for p, s in pr.reduction():
        assert re.search(rf"\b{pr.number(p)} to [^;]*\b{pr.number(s)}\b", pr.describe()), (p, s)


def test_the_book_lists_the_pages():
    toc = (ROOT / "book" / "_toc.yml").read_text(encoding="utf-8")
    assert "file: course_map" in toc and "file: notation" in toc
    intro = (ROOT / "book" / "intro.md").read_text(encoding="utf-8")
    assert "course_map.md" in intro and "notation.md" in intro
