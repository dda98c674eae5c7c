"""The benchmark harness measures both sides in fresh processes and reports a ratio."""

import json

import pytest

from benchmarks import harness


def test_harness_runs_a_case_in_fresh_processes(tmp_path, monkeypatch):
    monkeypatch.setenv("SHAPELAB_BENCH_MODULES", "tests.course.bench_smoke")
    case = {c.name: c for c in harness.all_cases()}["smoke_norm"]
    row = harness.run_case(case, repeats=5)
    assert row["repeats"] == 5
    assert len(row["runs"]["ours"]) == len(row["runs"]["peer"]) == 5
    assert row["ours_s"] > 0 and row["peer_s"] > 0
    assert abs(row["ratio"] - row["ours_s"] / row["peer_s"]) < 1e-12
    # the first call in each fresh process is reported beside the warm median
    assert row["ours_cold_s"] > 0 and row["peer_cold_s"] > 0
    assert abs(row["cold_ratio"] - row["ours_cold_s"] / row["peer_cold_s"]) < 1e-12
    assert all("cold_seconds" in r for r in row["runs"]["ours"] + row["runs"]["peer"])
    assert row["met"] is True
    assert row["notes"] and row["notes"][0].startswith("max diff")
    table = harness._table([row])
    assert "| smoke_norm |" in table and "warm ours/peer" in table and "cold ours/peer" in table
    json.dumps(row)  # serialisable as written to benchmarks/results/


def test_case_names_are_unique_and_targets_sane():
    for case in harness.all_cases():
        assert case.repeats >= 5
        assert case.target is None or case.target > 0


def test_peak_memory_is_the_timed_calls_not_the_setups(monkeypatch):
    """Setup allocates and frees 400 MB; the timed calls hold 40 MB (ours) and 160 MB (peer).
    The reported peaks must be about those, not the setup's transient."""
    monkeypatch.setenv("SHAPELAB_BENCH_MODULES", "tests.course.bench_smoke")
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
    monkeypatch.setenv("SHAPELAB_BENCH_MODULES", "tests.course.bench_smoke")
    case = {c.name: c for c in harness.all_cases()}["smoke_heap"]
    row = harness.run_case(case, repeats=5)
    peer = [r["peak_kib"] / 1024 for r in row["runs"]["peer"]]
    assert all(85 < m < 140 for m in peer), peer


def test_a_case_whose_results_disagree_is_not_met(monkeypatch):
    """Speed is no use if the answer is wrong: a check note starting with MISMATCH fails
    the case, while the same check on agreeing results (smoke_norm) passes it."""
    monkeypatch.setenv("SHAPELAB_BENCH_MODULES", "tests.course.bench_smoke")
    cases = {c.name: c for c in harness.all_cases()}
    row = harness.run_case(cases["smoke_mismatch"], repeats=5)
    assert row["ratio"] <= cases["smoke_mismatch"].target
    assert row["notes"] and row["notes"][0].startswith(harness.MISMATCH)
    assert row["met"] is False
    assert "| NO |" in harness._table([row])


def test_scaling_ladder_fits_exponents_and_draws_the_figure(tmp_path, monkeypatch):
    """One fresh process per side and rung; the fitted exponent of a linear-time
    computation is near 1 (loose bounds: the machine is shared); the figure is written."""
    from benchmarks import scaling

    monkeypatch.setenv("SHAPELAB_BENCH_MODULES", "tests.course.bench_smoke")
    case = {c.name: c for c in harness.all_cases()}["smoke_norm"]
    points = harness.run_ladder(case)
    assert [p["n"] for p in points] == [100_000, 100_000, 300_000, 300_000, 1_000_000, 1_000_000]
    exps, name = scaling.draw(case, points, tmp_path)
    assert (tmp_path / name).stat().st_size > 1000
    assert 0.3 < exps["ours_time"] < 1.7 and 0.3 < exps["peer_time"] < 1.7
    assert scaling.fit_exponent([10, 100, 1000], [5.0, 50.0, 500.0]) == 1.0
    assert scaling.fit_exponent([10, 100], [1e-6, 1e-6], floor=1e-3) is None


def test_machine_report_names_cpu_flags_and_blas():
    info = harness.machine()
    line = harness.machine_line(info)
    assert info["cpus"] >= 1 and "cpu_flags" in info and "blas" in info
    assert "BLAS:" in line and "CPU flags:" in line
    pytest.importorskip("threadpoolctl")
    assert "kernel" in info["blas"]


def test_a_case_that_cannot_run_is_reported_and_the_run_goes_on(tmp_path, monkeypatch):
    """A peer that will not import on this machine fails its own case, not the run:
    its row says NOT RUN and why, the next case is measured, and the results are
    written (the exit status says that something did not run)."""
    monkeypatch.setenv("SHAPELAB_BENCH_MODULES", "tests.course.bench_smoke")
    monkeypatch.setattr(harness, "RESULTS", tmp_path)
    status = harness.main(["smoke_unavailable", "smoke_norm", "--no-scaling", "--repeats", "5"])
    assert status == 1
    text = (tmp_path / "latest.md").read_text()
    assert "(complete)" in text
    bad = next(ln for ln in text.splitlines() if ln.startswith("| smoke_unavailable |"))
    assert "NOT RUN" in bad and "shapelab_no_such_peer" in bad and "| NO |" in bad
    good = next(ln for ln in text.splitlines() if ln.startswith("| smoke_norm |"))
    assert "| yes |" in good
    rows = json.loads((tmp_path / "smoke_unavailable.json").read_text())["results"]
    assert rows[0]["failed"] is True and rows[0]["met"] is False
