"""``python -m benchmarks`` (``make bench``): the whole run is the cases, then the
binding-site benchmark, then what a user waits for (issue 25, item 3), then the union
measure on 1 and 2 threads against its peers (item 1); one case, the list or a worker
runs none of the last three."""

from __future__ import annotations

import runpy
import sys

import pytest


@pytest.fixture
def calls(monkeypatch):
    from benchmarks import harness, measure_peers, pocket_sites, user_wait

    seen = []
    monkeypatch.setattr(harness, "main", lambda *a: seen.append("cases") or 0)
    monkeypatch.setattr(pocket_sites, "main", lambda argv=None: seen.append("pocket_sites") or 0)
    monkeypatch.setattr(user_wait, "main", lambda argv=None: seen.append("user_wait") or 0)
    monkeypatch.setattr(measure_peers, "main", lambda argv=None: seen.append(("measure_peers", *argv)) or 0)
    return seen


@pytest.mark.parametrize(
    "argv, expected",
    [
        (
            [],
            [
                "cases",
                "pocket_sites",
                "user_wait",
                ("measure_peers", "--threads", "2", "--out", "benchmarks/results/measure_peers_threads.json"),
            ],
        ),
        (
            ["--repeats", "5"],
            [
                "cases",
                "pocket_sites",
                "user_wait",
                ("measure_peers", "--threads", "2", "--out", "benchmarks/results/measure_peers_threads.json"),
            ],
        ),
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


def test_a_partial_user_wait_run_keeps_the_other_parts_and_the_notes(tmp_path):
    # `python -m benchmarks.user_wait --only cli` used to rewrite the results with the
    # CLI part alone, dropping the lessons, the import profile and the notes
    import json

    from benchmarks import user_wait as uw

    out = tmp_path / "user_wait.md"
    lesson = {"lesson": "00_start_here", "runs": 5, "error": None, "wall_s": 1.0, "import_cell_s": 0.3}
    old = {
        "when": "2026-01-01 00:00",
        "commit": "abc1234",
        "load": {"lessons": "1.00 / 1.00", "cli": "2.00 / 2.00"},
        "lessons": [lesson | {"first_call_s": 0.01}],
        "cli": {"command": "old", "runs": 5, "wall_s": 9.0, "all_s": [9.0] * 5},
    }
    out.with_suffix(".json").write_text(json.dumps(old), encoding="utf-8")
    out.write_text("# tables\n\n## Notes on this run\n\nwritten by hand\n", encoding="utf-8")
    doc = {"machine": "m", "when": "2026-02-02 00:00", "commit": "def5678", "repeats": 5, "load": {}, "runs": {}}
    doc, notes = uw._previous(out, doc, ["cli"])
    assert doc["lessons"] == old["lessons"] and "cli" not in doc  # cli is re-measured
    assert doc["runs"] == {"lessons": {"when": "2026-01-01 00:00", "commit": "abc1234"}}
    assert notes == "\n## Notes on this run\n\nwritten by hand\n"
    doc["cli"] = {"command": "new", "runs": 5, "wall_s": 1.5, "all_s": [1.5] * 5}
    doc["load"]["cli"], doc["runs"]["cli"] = "3.00 / 3.00", {"when": "2026-02-02 00:00", "commit": "def5678"}
    uw._save(doc, out, notes)
    text = out.read_text(encoding="utf-8")
    assert "00_start_here" in text and "**1.50 s**" in text and text.endswith("written by hand\n")
    assert "lessons 2026-01-01 00:00 UTC at shapelab commit abc1234" in text
    assert "cli 2026-02-02 00:00 UTC at shapelab commit def5678" in text
