"""Lessons of a class's length (issue 34): course/wordcount.py's measure and limit."""

from __future__ import annotations

from pathlib import Path

import pytest

from course import wordcount

ROOT = Path(__file__).resolve().parents[2]
LESSONS = sorted((ROOT / "lessons").glob("[0-9][0-9]_*.ipynb"))


def _nb(tmp_path, *cells):
    import json

    path = tmp_path / "x.ipynb"
    path.write_text(json.dumps({"cells": [{"cell_type": t, "source": s} for t, s in cells]}), encoding="utf-8")
    return path


def test_words_are_what_wc_counts():
    assert wordcount.words("one two  three\nfour $x^2 + y$") == 7


def test_going_deeper_runs_to_the_next_heading_of_its_level(tmp_path):
    path = _nb(
        tmp_path,
        ("markdown", "# Title\n\nfive words of core prose"),
        ("markdown", "## Going deeper: cohomology\n\nthree deeper words\n\n### still deeper here"),
        ("code", "print('code is not prose at all')"),
        ("markdown", "## Exercises\n\nback to core"),
        ("markdown", "## References\n\n- A. Author, 2001."),
    )
    c = wordcount.count(path)
    assert c == {"core": 2 + 5 + 2 + 3, "deeper": 4 + 3 + 4, "references": 2 + 4}
    assert wordcount.length(c) == c["core"] + c["references"]


@pytest.mark.parametrize("path", LESSONS, ids=[p.stem for p in LESSONS])
def test_no_lesson_is_over_the_limit(path):
    n = wordcount.length(wordcount.count(path))
    assert n <= wordcount.LIMIT, f"{path.name}: {n:,} words outside Going deeper (limit {wordcount.LIMIT:,})"
