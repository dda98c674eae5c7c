"""The benchmark harness measures both sides in fresh processes and reports a ratio."""
import json
import os

from benchmarks import harness


def test_harness_runs_a_case_in_fresh_processes(tmp_path, monkeypatch):
    monkeypatch.setenv("SHAPELAB_BENCH_MODULES", "tests.bench_smoke")
    case = {c.name: c for c in harness.all_cases()}["smoke_norm"]
    row = harness.run_case(case, repeats=5)
    assert row["repeats"] == 5
    assert len(row["runs"]["ours"]) == len(row["runs"]["peer"]) == 5
    assert row["ours_s"] > 0 and row["peer_s"] > 0
    assert abs(row["ratio"] - row["ours_s"] / row["peer_s"]) < 1e-12
    assert row["met"] is True
    assert row["notes"] and row["notes"][0].startswith("max diff")
    table = harness._table([row])
    assert "| smoke_norm |" in table and "ours/peer" in table
    json.dumps(row)  # serialisable as written to benchmarks/results/


def test_case_names_are_unique_and_targets_sane():
    for case in harness.all_cases():
        assert case.repeats >= 5
        assert case.target is None or case.target > 0


def test_peak_memory_is_the_timed_calls_not_the_setups(monkeypatch):
    """Setup allocates and frees 400 MB; the timed calls hold 40 MB (ours) and 160 MB (peer).
    The reported peaks must be about those, not the setup's transient."""
    monkeypatch.setenv("SHAPELAB_BENCH_MODULES", "tests.bench_smoke")
    case = {c.name: c for c in harness.all_cases()}["smoke_memory"]
    row = harness.run_case(case, repeats=5)
    ours = [r["peak_kib"] / 1024 for r in row["runs"]["ours"]]
    peer = [r["peak_kib"] / 1024 for r in row["runs"]["peer"]]
    assert all(30 < m < 80 for m in ours), ours
    assert all(140 < m < 200 for m in peer), peer
    assert 30 < row["ours_peak_mib"] < 80 and 0.15 < row["memory_ratio"] < 0.4


def test_peak_memory_counts_heap_memory_the_warm_up_freed(monkeypatch):
    """The peer allocates 100 MB in small malloc chunks, in the warm-up and again in the
    timed call.  glibc keeps the warm-up's freed chunks resident and reuses them, so
    unless the harness hands them back to the system first, the timed call's 100 MB
    would look like almost nothing (this made GUDHI's peak look 4x smaller)."""
    monkeypatch.setenv("SHAPELAB_BENCH_MODULES", "tests.bench_smoke")
    case = {c.name: c for c in harness.all_cases()}["smoke_heap"]
    row = harness.run_case(case, repeats=5)
    peer = [r["peak_kib"] / 1024 for r in row["runs"]["peer"]]
    assert all(85 < m < 140 for m in peer), peer


def test_a_case_whose_results_disagree_is_not_met(monkeypatch):
    """Speed is no use if the answer is wrong: a check note starting with MISMATCH fails
    the case, while the same check on agreeing results (smoke_norm) passes it."""
    monkeypatch.setenv("SHAPELAB_BENCH_MODULES", "tests.bench_smoke")
    cases = {c.name: c for c in harness.all_cases()}
    row = harness.run_case(cases["smoke_mismatch"], repeats=5)
    assert row["ratio"] <= cases["smoke_mismatch"].target
    assert row["notes"] and row["notes"][0].startswith(harness.MISMATCH)
    assert row["met"] is False
    assert "| NO |" in harness._table([row])
