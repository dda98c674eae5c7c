"""The public code a student reads per algorithm (issue 33): course/reading_size.py."""

from __future__ import annotations

import pytest

from course import reading_size as rs

#: none: ``pockets`` selects between two algorithms, each with its own row (the growth
#: model, ``growth_pockets``, and the discrete flow), as ``scipy.optimize.minimize``
#: selects its methods; the selector itself reads both
OVER: dict[str, int] = {}
ABOUT = rs.ABOUT  # "at most about 800 lines": the script's --check uses the same


@pytest.fixture(scope="module")
def sizes():
    return rs.sizes()


def test_every_algorithm_is_within_its_reading_size(sizes):
    for label, per in sizes.items():
        total = sum(per.values())
        assert total <= OVER.get(label, ABOUT * rs.LIMIT), f"{label}: {total:,} public lines to read"


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


def test_pockets_selects_the_growth_model_by_default():
    """The row's function is what ``pockets`` runs by default, the same objects."""
    import shapelab as sl
    from shapelab.cavities.pocket import growth_pockets

    F = sl.alpha_filtration(sl.datasets.figure_23_2()[0])
    for tau in (0.0, 0.3):
        a, b = sl.pockets(F, tau), growth_pockets(F, tau)
        assert len(a) > 0 and [repr(p) for p in a] == [repr(p) for p in b]
        assert [(p.cell_ids.tolist(), p.mouth_ids.tolist(), p.volume) for p in a] == [
            (p.cell_ids.tolist(), p.mouth_ids.tolist(), p.volume) for p in b
        ]
    assert "pockets (growth model)" in rs.ALGORITHMS
