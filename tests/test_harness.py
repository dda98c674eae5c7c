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
