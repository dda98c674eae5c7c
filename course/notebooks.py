"""What every course tool reads in a lesson: solution markers, tags and slide types."""

from __future__ import annotations

import re

__all__ = ["BEGIN", "END", "SOLUTION_TAG", "is_solution", "slide_type"]

#: the lines that open and close a solution block in a code cell
BEGIN = re.compile(r"^\s*#+\s*BEGIN SOLUTION\s*$")
END = re.compile(r"^\s*#+\s*END SOLUTION\s*$")
#: the tag of a cell that holds (or is) a solution
SOLUTION_TAG = "solution"


def is_solution(cell) -> bool:
    """True for a cell tagged ``solution`` (its code between the markers, or a model answer)."""
    return SOLUTION_TAG in cell.get("metadata", {}).get("tags", [])


def slide_type(cell) -> str:
    """The cell's ``slideshow.slide_type`` (``-`` when it has none)."""
    return cell.get("metadata", {}).get("slideshow", {}).get("slide_type", "-") or "-"
