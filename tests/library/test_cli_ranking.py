"""The command line's ranking options (``--rank``, ``--method``, ``--min-persistence``,
``--min-volume``, ``--top``): each is the report's argument of the same name.

Oracle: the library called directly (:func:`shapelab.report` on the structure the
CLI reads); the files written are compared byte for byte with its outputs.
"""

from __future__ import annotations

import importlib

import pytest

import shapelab as sl
from shapelab.datasets import structure_path

cli = importlib.import_module("shapelab.tools.cli")


@pytest.fixture(scope="module")
def hvr():
    path = structure_path("1hvr")
    return path, sl.read_structure(path, hetatm=False)


@pytest.mark.parametrize(
    "args, kw",
    [
        ([], {}),
        (["--rank", "none"], dict(rank="none")),
        (["--rank", "score"], dict(rank="score")),
        (["--rank", "score", "--min-volume", "5", "--top", "3"], dict(rank="score", min_volume=5.0, top=3)),
        (["--min-persistence", "0.5"], dict(min_persistence=0.5)),
        (
            ["--method", "flow", "--rank", "score", "--min-persistence", "0"],
            dict(method="flow", rank="score", min_persistence=0.0),
        ),
    ],
)
def test_options_round_trip_to_the_library(hvr, tmp_path, capsys, args, kw):
    path, s = hvr
    rc = cli.main(["report", str(path), "--no-hetatm", "--out", str(tmp_path), *args])
    out = capsys.readouterr()
    assert rc == 0, out.err
    lib = sl.report(s, 1.4, name="1hvr", **kw)
    assert out.out == lib.to_markdown()
    assert (tmp_path / "1hvr_cavities.csv").read_text() == lib._csv_text()
    assert (tmp_path / "1hvr_cavities.md").read_text() == lib.to_markdown()


def test_no_option_is_the_ranked_default_and_rank_none_the_old_table(hvr, tmp_path, capsys):
    """Without ranking options the CLI prints report(structure, probe)'s table, which is
    the ranking (rank="score", small cavities dropped and counted); --rank none prints
    the unfiltered table in CASTp's order."""
    path, s = hvr
    assert cli.main(["report", str(path), "--no-hetatm", "--out", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    ranked = sl.report(s, 1.4, name="1hvr", rank="score")
    assert out == sl.report(s, 1.4, name="1hvr").to_markdown() == ranked.to_markdown()
    every = sl.report(s, 1.4, name="1hvr", rank="none")
    assert f"{len(ranked.rows)} of {len(every.rows)} cavities listed" in out
    assert len(ranked.rows) < len(every.rows)
    assert cli.main(["report", str(path), "--no-hetatm", "--out", str(tmp_path), "--rank", "none"]) == 0
    old = capsys.readouterr().out
    assert old == every.to_markdown() and "filtered out" not in old


@pytest.mark.parametrize(
    "args, words",
    [
        (["--min-volume", "-1"], "min_volume must be non-negative"),
        (["--top", "0"], "top must be at least 1"),
        (["--min-persistence", "nan"], "min_persistence must be finite"),
    ],
)
def test_bad_values_exit_2_and_write_nothing(hvr, tmp_path, capsys, args, words):
    path, _ = hvr
    rc = cli.main(["report", str(path), "--out", str(tmp_path), *args])
    err = capsys.readouterr().err
    assert rc == 2 and words in err and err.count("\n") == 1
    assert list(tmp_path.iterdir()) == []


def test_bad_choices_are_refused_by_the_parser(hvr, tmp_path, capsys):
    path, _ = hvr
    for args in (["--rank", "best"], ["--method", "castp"]):
        with pytest.raises(SystemExit) as e:
            cli.main(["report", str(path), "--out", str(tmp_path), *args])
        assert e.value.code == 2
    assert "invalid choice" in capsys.readouterr().err


@pytest.mark.parametrize(
    "args, kw",
    [([], {}), (["--rank", "none"], dict(rank="none")), (["--top", "2"], dict(top=2))],
)
def test_the_batch_passes_ranking_options_to_each_report(tmp_path, capsys, args, kw):
    """Each structure's files in a batch are those of report(..., **options) called directly."""
    srcs = [structure_path("1grm"), structure_path("1hvr").parent / "globule.pdb"]
    rc = cli.main(["report", *map(str, srcs), "--out", str(tmp_path), "--no-progress", *args])
    assert rc == 0, capsys.readouterr().err
    for src in srcs:
        stem = src.name.split(".")[0]
        lib = sl.report(sl.read_structure(src), 1.4, name=stem, **kw)
        assert (tmp_path / f"{stem}_cavities.md").read_text() == lib.to_markdown()
        assert (tmp_path / f"{stem}_cavities.csv").read_text() == lib._csv_text()
