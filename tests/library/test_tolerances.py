"""The library's tolerances (shapelab/_toolkit/tolerances.py): documented, wired,
and in the relations their guarantees need.

The central relation is between the accuracy to which entry times are certified and
the rules that treat nearly equal entry times as equal:

* ``shapelab.filtration`` certifies every entry time to ``ENTRY_TIME_RTOL`` (1e-9)
  relative to the value itself: a float value is accepted only when twice its
  first-order error bound is at most 1e-9 |v|, otherwise it is recomputed in long
  double or exact rationals (rounded once).
* Two simplices whose *exact* entry times are equal (a tie, e.g. on a grid, or a
  persistence pair born and killed by the same event) can therefore come out as
  ``v (1 ± ENTRY_TIME_RTOL)``: apart by up to ``2 ENTRY_TIME_RTOL |v| / (1 - RTOL)``.
* A rule that must recognise every such tie as a tie needs a tolerance *at least*
  that large.  A larger tolerance can only merge genuinely distinct values closer
  than itself, which the certified values cannot tell from a tie anyway; a smaller
  one lets a tie through as a spurious, very short pair (or interval).  So the
  relation goes ``tolerance >= certified accuracy``, not the other way round.
"""

from __future__ import annotations

import inspect
import re

import numpy as np

from shapelab import measure, topology
from shapelab._engine import hausdorff as distance
from shapelab._engine import orthospheres, predicates
from shapelab._toolkit import tolerances as T

EPS = float(np.finfo(np.float64).eps)
RTOL = T.ENTRY_TIME_RTOL


def test_every_tolerance_is_documented():
    """Each public constant has a ``#:`` comment right above it (what it guards,
    relative to what, why its value)."""
    lines = inspect.getsource(T).splitlines()
    for name in T.__all__:
        at = next(i for i, line in enumerate(lines) if re.match(rf"{name} = ", line))
        above = lines[at - 1]
        # a constant sharing the comment of the one above it (xatol/fatol pairs)
        while not above.startswith("#:") and re.match(r"[A-Z_]+ = ", above):
            at -= 1
            above = lines[at - 1]
        assert above.startswith("#:"), name
        assert isinstance(getattr(T, name), float), name


def test_filtration_and_topology_are_wired():
    """The engine's orthospheres (once filtration.py) and topology.py take their
    constants from the toolkit (they kept copies once): the very objects, not equal
    copies that could drift."""
    assert orthospheres._RTOL is T.ENTRY_TIME_RTOL
    assert orthospheres._SAFETY is T.ENTRY_TIME_SAFETY
    assert topology.ROUNDOFF is T.PERSISTENCE_ROUNDOFF


#: the modules whose tolerances all live in the toolkit (commit 68559d7)
WIRED = (
    "triangulation",
    "_engine.triangulation",
    "_engine.certify",
    "_engine.predicates",
    "_engine.incremental",
    "measure",
    "_engine.measure",
    "cavities.freespace",
    "_engine.freespace",
    "_engine.flow",
    "_engine.mouths",
    "cavities.void",
    "cavities.pocket",
    "cavities.tunnel",
    "cavities.flow",
    "cavities.mouths",
    "cavities.complement",
    "critical",
    "distance",
    "matching",
    "filtration",
    "topology",
    "registration",
    "quaternion",
    "report",
    "embedding",
)


def small_literals(src: str) -> list:
    """Numeric literals below 1e-3 in the code of ``src``: not in docstrings, and not
    the documented defaults of keyword parameters (a user's ``atol=1e-6``)."""
    import ast

    tree = ast.parse(src)
    defaults = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef, ast.Lambda)):
            for d in node.args.defaults + [k for k in node.args.kw_defaults if k is not None]:
                defaults |= {id(n) for n in ast.walk(d)}
    found = []
    for node in ast.walk(tree):
        if (
            isinstance(node, ast.Constant)
            and isinstance(node.value, (int, float))
            and not isinstance(node.value, bool)
            and 0 < abs(node.value) < 1e-3
            and id(node) not in defaults
        ):
            found.append(node.lineno)
    return found


def test_no_small_literal_escaped_the_toolkit():
    """No numeric literal below 1e-3 in the code (not the docstrings, not a keyword's
    documented default) of the wired modules: a tolerance written in place would
    escape this file's relations."""
    import importlib

    for name in WIRED:
        src = inspect.getsource(importlib.import_module(f"shapelab.{name}"))
        lines = src.splitlines()
        bad = [f"shapelab/{name}.py:{n}: {lines[n - 1].strip()}" for n in small_literals(src)]
        assert bad == [], bad


def test_the_literal_finder_finds_what_it_should():
    src = 'def f(x, atol=1e-6):\n    """1e-9 in a docstring."""\n    return x < 1e-9 * atol\n'
    assert small_literals(src) == [3]
    assert small_literals("y = 0.5 - 2e-4\n") == [1]


def test_wired_modules_use_the_constants():
    assert measure.TIE_TOL is T.MEASURE_TIE
    assert measure.TANGENT_TOL is T.MEASURE_TANGENT
    assert measure.FLAT_TOL is T.MEASURE_FLAT
    assert distance._REL is T.DISTANCE_BOX_REL
    assert predicates._TINY is T.FILTER_UNDERFLOW


def test_measure_tie_rule_covers_the_certified_accuracy():
    """``v + MEASURE_TIE |v| < τ`` must leave out every simplex whose exact entry
    time is τ.  Its computed value v' is within RTOL of τ: for τ > 0, v' >= τ (1 -
    RTOL), and v' (1 + TIE) >= τ needs TIE >= RTOL / (1 - RTOL); for τ < 0,
    v' >= τ (1 + RTOL), and v' (1 - TIE) >= τ needs TIE >= RTOL / (1 + RTOL)."""
    assert T.MEASURE_TIE >= RTOL / (1.0 - RTOL)
    # and it does so for the worst rounding, in floating point
    from shapelab._engine.measure import before

    for tau in (1.0, -1.0, 3.7e5, -2.5e-7):
        worst = tau * (1.0 - RTOL) if tau > 0 else tau * (1.0 + RTOL)
        assert not before(np.array([worst]), tau)[0]


def test_persistence_roundoff_covers_the_certified_accuracy():
    """A pair ``(b, d)`` whose exact values are equal comes out with ``d - b`` up to
    ``2 RTOL max(|b|, |d|) / (1 - RTOL)``; the zero-length filter (``d - b <=
    ROUNDOFF max(|b|, |d|, scale)``) removes it for sure only if ``ROUNDOFF``
    is at least that (see the module docstring for why the relation goes this way)."""
    assert T.PERSISTENCE_ROUNDOFF >= 2.0 * RTOL / (1.0 - RTOL)


def test_roundoff_margins_exceed_the_rounding_they_absorb():
    """Margins that absorb a few ulps of rounding are far above them, and far below
    anything geometric (1e-6 relative)."""
    for name in (
        "MEASURE_TANGENT",
        "PLANE_FEASIBILITY",
        "EDGE_HEIGHT",
        "PARALLEL_NORMALS",
        "DISTANCE_BOX_REL",
        "DISTANCE_TIE_REL",
        "DISTANCE_AGREE",
        "QHULL_FLAT",
    ):
        v = getattr(T, name)
        assert 16 * EPS <= v <= 1e-6, name
    # the bounding-box prefilter of the cover count is a prefilter: generous
    assert T.COVER_PREFILTER >= 1e6 * EPS


def test_candidate_and_freespace_relations():
    # the steep band lies beyond the vertical band (both only shape Qhull's candidate)
    assert T.QHULL_VERTICAL < T.QHULL_STEEP < 1.0
    # incidence accepts every vertex the feasibility test let through
    assert T.PLANE_INCIDENCE_FACTOR > 1.0
    # an error bound just above the filter's floor still has a normal rounding error
    assert T.FILTER_UNDERFLOW * 2.0**-53 > np.finfo(np.float64).tiny
    assert T.UNDERFLOW_FLOOR < T.FILTER_UNDERFLOW


def test_curve_refinement_relations():
    """Two refinements of one extremum (from neighbouring samples) land within the
    refiners' accuracy of each other, which the merge tolerance must exceed; and the
    central difference's step is far above the root finder's resolution."""
    assert T.CURVE_MERGE > 10 * max(T.CURVE_MIN_XATOL, T.CURVE_ROOT_XTOL)
    assert T.CURVE_WRAP <= T.CURVE_MERGE
    assert T.CURVE_STEP > 1e6 * T.CURVE_MIN_XATOL
    assert T.CHANNEL_FATOL <= T.CHANNEL_XATOL
