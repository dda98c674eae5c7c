"""Structure of the committed lessons.

nbval (run by ``make test`` on ``lessons/``) re-executes every lesson and compares
outputs strictly.  These tests check what nbval cannot: that outputs were
committed at all, executed once top to bottom, with no error and no stderr, and
that each lesson follows the course's conventions (CONTRIBUTING.md).
"""

from __future__ import annotations

import re
from pathlib import Path

import nbformat
import pytest

LESSONS = sorted((Path(__file__).resolve().parents[2] / "lessons").glob("[0-9][0-9]_*.ipynb"))
NAME = re.compile(r"^\d\d_[a-z0-9_]+\.ipynb$")


def code_cells(nb):
    return [c for c in nb.cells if c.cell_type == "code" and c.source.strip()]


def test_there_are_lessons():
    assert LESSONS, "no lessons found in lessons/"
    assert LESSONS[0].name == "00_start_here.ipynb"


@pytest.fixture(params=LESSONS, ids=[p.stem for p in LESSONS])
def lesson(request):
    return request.param, nbformat.read(request.param, as_version=4)


def test_name_follows_convention(lesson):
    path, _ = lesson
    assert NAME.match(path.name), f"{path.name}: lessons are named NN_topic.ipynb"


def test_valid_notebook(lesson):
    _, nb = lesson
    nbformat.validate(nb)


def test_executed_once_in_order(lesson):
    path, nb = lesson
    counts = [c.execution_count for c in code_cells(nb)]
    assert counts, f"{path.name} has no code"
    assert None not in counts, f"{path.name}: committed with cells never executed"
    assert counts == list(range(1, len(counts) + 1)), f"{path.name}: not executed once, top to bottom: {counts}"


def test_has_outputs(lesson):
    path, nb = lesson
    assert any(c.outputs for c in code_cells(nb)), f"{path.name}: committed without outputs"


def test_no_errors_or_stderr(lesson):
    path, nb = lesson
    for i, cell in enumerate(code_cells(nb)):
        for out in cell.outputs:
            assert out.output_type != "error", f"{path.name} cell {i}: error output {out.get('ename')}"
            if out.output_type == "stream":
                assert out.name != "stderr", f"{path.name} cell {i}: stderr output {out.text[:200]!r}"


def test_opens_with_goals_and_notes_section(lesson):
    path, nb = lesson
    first = nb.cells[0]
    assert first.cell_type == "markdown" and first.source.lstrip().startswith("# "), f"{path.name}: starts with a title"
    head = "\n".join(c.source for c in nb.cells[:2] if c.cell_type == "markdown")
    assert "Learning goals" in head, f"{path.name}: learning goals come first"
    assert re.search(r"§\s?23", head) or path.name.startswith("00_"), f"{path.name}: names the section of the notes"


def test_closes_with_exercises_and_solutions(lesson):
    path, nb = lesson
    titles = [c.source for c in nb.cells if c.cell_type == "markdown" and c.source.lstrip().startswith("## ")]
    assert any("Exercises" in t for t in titles), f"{path.name}: has an Exercises section"
    ex = max(i for i, c in enumerate(nb.cells) if c.cell_type == "markdown" and "## Exercises" in c.source)
    later = nb.cells[ex:]
    sols = [c for c in later if "solution" in c.metadata.get("tags", [])]
    assert sols, f"{path.name}: exercises have solutions in cells tagged 'solution'"
    for c in sols:
        if c.cell_type == "code":
            assert "# BEGIN SOLUTION" in c.source and "# END SOLUTION" in c.source, (
                f"{path.name}: solution code sits between '# BEGIN SOLUTION' and '# END SOLUTION'"
            )


def test_no_network(lesson):
    path, nb = lesson
    for c in code_cells(nb):
        assert not re.search(r"\b(urllib|requests|http\.client|urlopen|wget|curl)\b", c.source), (
            f"{path.name}: lessons never use the network"
        )


LINK = re.compile(r"\]\(([^)\s#]+\.(?:ipynb|md))(?:#[^)]*)?\)")


def test_links_between_lessons_resolve(lesson):
    """A cross-reference such as ``[Figure 23.1](01_power_diagrams.ipynb)`` must name a real
    lesson: the book turns it into a page link, and a typo there is a dead link on the site."""
    path, nb = lesson
    dead = [
        f"cell {i}: {m.group(0)}"
        for i, c in enumerate(nb.cells)
        if c.cell_type == "markdown"
        for m in LINK.finditer(c.source)
        if not (path.parent / m.group(1)).exists()
    ]
    assert not dead, f"{path.name} links to missing files: {dead}"


def test_has_speaker_notes_for_the_deck_only(lesson):
    """Each lesson carries speaker notes (slide type ``notes``) for its deck; they are tagged
    ``remove-cell`` so the course website, which students read, leaves them out."""
    path, nb = lesson
    notes = [c for c in nb.cells if c.get("metadata", {}).get("slideshow", {}).get("slide_type") == "notes"]
    assert notes, f"{path.name}: no speaker notes (a markdown cell with slide type 'notes')"
    for c in notes:
        assert c.cell_type == "markdown" and "remove-cell" in c.metadata.get("tags", []), (
            f"{path.name}: speaker notes must be markdown tagged 'remove-cell'"
        )
