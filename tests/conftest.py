"""Shared pytest configuration: the Hypothesis profile and the plotting backend.

The lessons' time budget (60 s each on 2 cores) is a performance figure: it is measured by
``python -m benchmarks.lessons`` (``make bench``), not asserted here.
"""

from __future__ import annotations

import os

import matplotlib
from hypothesis import settings

matplotlib.use("Agg")

# Hypothesis draws the same examples on every run, so that CI is reproducible (a random
# draw once failed a test whose tolerance was wrong, on one run in many).  To explore new
# examples: SHAPELAB_HYPOTHESIS=explore make test (see CONTRIBUTING.md).
settings.register_profile("ci", derandomize=True, print_blob=True)
settings.register_profile("explore", derandomize=False, max_examples=400, print_blob=True)
settings.load_profile(os.environ.get("SHAPELAB_HYPOTHESIS", "ci"))
os.environ.setdefault("PYDEVD_DISABLE_FILE_VALIDATION", "1")
