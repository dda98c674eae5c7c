"""The public code a student reads per algorithm (issue 33): course/reading_size.py."""

from __future__ import annotations

import pytest

from course import reading_size as rs

#: ``pockets`` reaches the discrete flow through ``method="flow"`` and so reads both
#: algorithms (the flow has its own row); the growth model alone is about 850 lines.
OVER = {"pockets": 1200}


@pytest.fixture(scope="module")
def sizes():
    return rs.sizes()


def test_every_algorithm_is_within_its_reading_size(sizes):
    for label, per in sizes.items():
        total = sum(per.values())
        assert total <= OVER.get(label, rs.LIMIT), f"{label}: {total:,} public lines to read"


def test_the_walk_skips_private_modules_and_counts_the_public_ones(sizes):
    for label, per in sizes.items():
        assert all(rs.is_public(m) for m in per), (label, sorted(per))
    assert {"shapelab.filtration", "shapelab.triangulation"} <= set(sizes["α-filtration"])
    assert set(sizes["Hausdorff distance"]) == {"shapelab.hausdorff"}


def test_own_rows_stop_at_the_other_algorithms(sizes):
    own = rs.sizes(own=True)
    for label in sizes:
        assert sum(own[label].values()) <= sum(sizes[label].values())
    assert (
        "shapelab.triangulation" not in own["voids"]
        or own["voids"]["shapelab.triangulation"] < sizes["voids"]["shapelab.triangulation"] + 1
    )


def test_an_unknown_name_is_refused():
    with pytest.raises(KeyError, match="not a public function"):
        rs.Reader().reading("no_such_function")
