"""Shared pytest configuration.

Besides fixtures and the Hypothesis profile, this enforces the course's notebook budget: a lesson whose cells
take more than 60 s in total under nbval fails (the budget is for 2 cores).
"""
from __future__ import annotations

import os
import time
from collections import defaultdict

import matplotlib
import pytest
from hypothesis import settings

matplotlib.use("Agg")

# Hypothesis draws the same examples on every run, so that CI is reproducible (a random
# draw once failed a test whose tolerance was wrong, on one run in many).  To explore new
# examples: SHAPELAB_HYPOTHESIS=explore make test (see CONTRIBUTING.md).
settings.register_profile("ci", derandomize=True, print_blob=True)
settings.register_profile("explore", derandomize=False, max_examples=400, print_blob=True)
settings.load_profile(os.environ.get("SHAPELAB_HYPOTHESIS", "ci"))
os.environ.setdefault("PYDEVD_DISABLE_FILE_VALIDATION", "1")

NOTEBOOK_BUDGET_S = 60.0
_spent: dict[str, float] = defaultdict(float)


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_call(item):
    t0 = time.perf_counter()
    yield
    if str(item.fspath).endswith(".ipynb"):
        key = str(item.fspath)
        _spent[key] += time.perf_counter() - t0
        if _spent[key] > NOTEBOOK_BUDGET_S:
            pytest.fail(
                f"{os.path.basename(key)} has run {_spent[key]:.1f} s, over the {NOTEBOOK_BUDGET_S:.0f} s budget "
                "for one lesson on 2 cores; make it lighter",
                pytrace=False,
            )
