"""``python -m benchmarks`` (``make bench``): the whole run is the cases, then the
binding-site benchmark, then what a user waits for (issue 25, item 3); one case, the
list or a worker runs neither of the last two."""

from __future__ import annotations

import runpy
import sys

import pytest


@pytest.fixture
def calls(monkeypatch):
    from benchmarks import harness, pocket_sites, user_wait

    seen = []
    monkeypatch.setattr(harness, "main", lambda *a: seen.append("cases") or 0)
    monkeypatch.setattr(pocket_sites, "main", lambda argv=None: seen.append("pocket_sites") or 0)
    monkeypatch.setattr(user_wait, "main", lambda argv=None: seen.append("user_wait") or 0)
    return seen


@pytest.mark.parametrize(
    "argv, expected",
    [
        ([], ["cases", "pocket_sites", "user_wait"]),
        (["--repeats", "5"], ["cases", "pocket_sites", "user_wait"]),
        (["union_measure_vs_voronota"], ["cases"]),
        (["--list"], ["cases"]),
        (["pocket_sites"], ["pocket_sites"]),
    ],
)
def test_make_bench_runs_the_user_wait_part(monkeypatch, calls, argv, expected):
    monkeypatch.setattr(sys, "argv", ["benchmarks", *argv])
    with pytest.raises(SystemExit) as stop:
        runpy.run_module("benchmarks", run_name="__main__")
    assert stop.value.code == 0
    assert calls == expected
