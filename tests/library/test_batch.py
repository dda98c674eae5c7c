"""shapelab.batch and ``python -m shapelab report PATH PATH ...``: many structures at once (Notes §23.1).

The oracle of every batch is the single-file command line, run on each structure on
its own (``python -m shapelab report FILE``, a code path that does not go through
``shapelab.batch``): the batch must write the same files, byte for byte, and its
summary's counts must be those of the single-file CSV tables.  Resuming is checked by
counting the reports actually computed.
"""

from __future__ import annotations

import contextlib
import csv
import filecmp
import importlib
import io
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

import shapelab as sl
from shapelab.datasets import structure_path
from shapelab.tools.batch import SUMMARY_COLUMNS, BatchSummary, expand_paths, output_stem, report_batch

ROOT = Path(__file__).resolve().parents[2]
DATA = structure_path("1hvr").parent
SHIPPED = ["globule.pdb", "1hvr.pdb.gz", "t4l_l99a_receptor.pdb.gz"]
STEMS = {"globule.pdb": "globule", "1hvr.pdb.gz": "1hvr", "t4l_l99a_receptor.pdb.gz": "t4l_l99a_receptor"}
BAD = "ATOM      1  CA  ALA A   1      1.000   xyz     3.000  1.00  0.00           C\n"
cli = importlib.import_module("shapelab.tools.cli")
report_module = importlib.import_module("shapelab.report")


def run_cli(args, cwd):
    env = dict(os.environ, PYTHONPATH=str(ROOT))
    return subprocess.run(
        [sys.executable, "-m", "shapelab", "report", *args],
        cwd=cwd,
        env=env,
        capture_output=True,
        text=True,
        timeout=600,
    )


def tiny_pdb(path: Path, shift=0.0, n=12):
    """A cage of ``n`` (at most 12) carbons on an icosahedron: a file that reports in milliseconds."""
    phi = (1 + 5**0.5) / 2
    ico = [(0.0, a, b * phi) for a in (-1, 1) for b in (-1, 1)]
    ico = [p for q in ico for p in (q, (q[1], q[2], q[0]), (q[2], q[0], q[1]))][:n]
    lines = [
        f"ATOM  {k + 1:>5}  C{k % 10}  CAG A   1    {2.2 * x + shift:8.3f}{2.2 * y:8.3f}{2.2 * z:8.3f}"
        f"  1.00  0.00           C"
        for k, (x, y, z) in enumerate(ico)
    ]
    path.write_text("\n".join(lines) + "\nEND\n")
    return path


def csv_rows(path):
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    """Three shipped structures and one malformed file, in one folder."""
    d = tmp_path_factory.mktemp("inputs")
    for name in SHIPPED:
        shutil.copy(DATA / name, d / name)
    (d / "bad.pdb").write_text(BAD)
    return d


@pytest.fixture(scope="module")
def single(folder, tmp_path_factory):
    """The oracle: the single-file command line on each structure, each into its own folder."""
    outs = {}
    for name in SHIPPED:
        out = tmp_path_factory.mktemp("single")
        buf = io.StringIO()
        with contextlib.redirect_stdout(buf):
            assert cli.main(["report", str(folder / name), "--out", str(out)]) == 0
        assert buf.getvalue().startswith(f"## Cavities of {STEMS[name]} ")
        assert not (out / "shapelab_summary.csv").exists()  # one file: no batch
        outs[name] = out
    return outs


@pytest.fixture(scope="module")
def batch_cli(folder, tmp_path_factory):
    """The folder through ``python -m shapelab report FOLDER --jobs 1``."""
    out = tmp_path_factory.mktemp("batch1")
    res = run_cli([str(folder), "--out", str(out), "--jobs", "1"], folder.parent)
    return out, res


@pytest.fixture(scope="module")
def batch_jobs2(folder, tmp_path_factory):
    out = tmp_path_factory.mktemp("batch2")
    return out, report_batch(folder, out=out, jobs=2, progress=False)


def test_batch_exit_status_and_streams(batch_cli, folder):
    out, res = batch_cli
    assert res.returncode == 1, res.stderr  # one input failed
    assert res.stdout == ""  # progress and messages never go to stdout
    err = res.stderr.splitlines()
    assert [line.split()[0] for line in err[:4]] == ["1/4", "2/4", "3/4", "4/4"]
    bad = str(folder / "bad.pdb")
    assert f"error: {bad}: line 1: could not read y from columns 39-46: 'xyz'" in err
    assert err[-1].startswith("4 structures: 3 ok, 0 skipped, 1 failed; summary: ")


def test_summary_rows_match_the_single_file_tables(batch_cli, single, folder):
    out, _ = batch_cli
    rows = csv_rows(out / "shapelab_summary.csv")
    assert list(rows[0]) == list(SUMMARY_COLUMNS)
    # input order: the folder's files in sorted order
    assert [r["path"] for r in rows] == [str(folder / n) for n in sorted([*SHIPPED, "bad.pdb"])]
    by_path = {Path(r["path"]).name: r for r in rows}
    b = by_path["bad.pdb"]
    assert b["status"] == "failed" and b["error"].startswith("line 1:") and b["atoms"] == b["voids"] == ""
    for name in SHIPPED:
        r = by_path[name]
        table = csv_rows(single[name] / f"{STEMS[name]}_cavities.csv")
        voids = [float(t["volume_sa"]) for t in table if t["kind"] == "void"]
        pockets = [float(t["volume_sa"]) for t in table if t["kind"] == "pocket"]
        assert (r["status"], r["error"], r["stem"]) == ("ok", "", STEMS[name])
        assert int(r["atoms"]) == len(sl.read_pdb(folder / name))
        assert (int(r["voids"]), int(r["pockets"])) == (len(voids), len(pockets))
        # the default report is ranked and drops cavities under 10 Å³: 1hvr, read with its
        # ligand in the site, lists none; t4l lists both kinds (an empty kind: no largest)
        for kind, vols in (("void", voids), ("pocket", pockets)):
            got = r[f"largest_{kind}_volume"]
            assert (float(got) == pytest.approx(max(vols), abs=2e-6)) if vols else got == ""
        assert float(r["seconds"]) > 0
    assert {n for n in SHIPPED if int(by_path[n]["voids"]) and int(by_path[n]["pockets"])} == {SHIPPED[2]}


def test_outputs_identical_to_the_single_file_cli(batch_cli, batch_jobs2, single):
    for out in (batch_cli[0], batch_jobs2[0]):
        for name in SHIPPED:
            stem = STEMS[name]
            ref = sorted(p.name for p in single[name].iterdir())
            assert ref == [f"{stem}_cavities.{e}" for e in ("cif", "csv", "md", "pdb")]
            match, mismatch, errors = filecmp.cmpfiles(single[name], out, ref, shallow=False)
            assert (mismatch, errors) == ([], []), (out, mismatch, errors)
        expected = {f"{STEMS[n]}_cavities.{e}" for n in SHIPPED for e in ("cif", "csv", "md", "pdb", "done.json")}
        assert {p.name for p in out.iterdir()} == expected | {"shapelab_summary.csv"} | (
            {"shapelab_summary.parquet"} if _has("pyarrow") else set()
        )


def _has(module):
    return importlib.util.find_spec(module) is not None


def test_two_jobs_give_the_same_summary(batch_cli, batch_jobs2):
    out1, _ = batch_cli
    out2, summary = batch_jobs2
    rows1 = csv_rows(out1 / "shapelab_summary.csv")
    rows2 = csv_rows(out2 / "shapelab_summary.csv")
    drop = lambda rows: [{k: v for k, v in r.items() if k != "seconds"} for r in rows]
    assert drop(rows1) == drop(rows2)
    assert (out2 / "shapelab_summary.csv").read_text() == summary.to_csv_text()
    assert summary.counts() == {"ok": 3, "failed": 1, "skipped": 0}
    assert [r["status"] for r in summary] == [r["status"] for r in rows1]


def test_resume_recomputes_only_an_interrupted_structure(batch_cli, folder, tmp_path, monkeypatch):
    out = tmp_path / "out"
    shutil.copytree(batch_cli[0], out)
    (out / "globule_cavities.done.json").unlink()  # interrupted after writing its files, before its marker
    before = {p.name: p.stat().st_mtime_ns for p in out.iterdir() if not p.name.startswith(("globule", "shapelab"))}
    computed = []
    real = report_module.report

    def counting(s, probe=1.4, **kw):
        computed.append(kw.get("name"))
        return real(s, probe, **kw)

    monkeypatch.setattr(report_module, "report", counting)
    summary = report_batch(folder, out=out, resume=True, progress=False)
    assert computed == ["globule"]
    assert [(Path(r["path"]).name, r["status"]) for r in summary] == [
        ("1hvr.pdb.gz", "skipped"),
        ("bad.pdb", "failed"),
        ("globule.pdb", "ok"),
        ("t4l_l99a_receptor.pdb.gz", "skipped"),
    ]
    after = {p.name: p.stat().st_mtime_ns for p in out.iterdir() if p.name in before}
    assert after == before  # the complete structures' files were not touched
    # a skipped row carries the counts of the run that made it
    old = {r["path"]: r for r in csv_rows(batch_cli[0] / "shapelab_summary.csv")}
    new = csv_rows(out / "shapelab_summary.csv")
    for r in new:
        keep = ("atoms", "voids", "pockets", "largest_void_volume", "largest_pocket_volume")
        assert {k: r[k] for k in keep} == {k: old[r["path"]][k] for k in keep}
    # run again: now everything that can be is complete
    computed.clear()
    again = report_batch(folder, out=out, resume=True, progress=False)
    assert computed == [] and again.counts() == {"ok": 0, "failed": 1, "skipped": 3}


def test_resume_redoes_a_changed_input_or_other_options(tmp_path, monkeypatch):
    src, out = tmp_path / "in", tmp_path / "out"
    src.mkdir()
    out.mkdir()
    a, b = tiny_pdb(src / "a.pdb"), tiny_pdb(src / "b.pdb", shift=1.0)
    first = report_batch(src, out=out, progress=False)
    assert first["status"] == ["ok", "ok"] and first["atoms"] == [12, 12]
    tiny_pdb(a, n=11)  # a changed input
    computed = []
    real = report_module.report
    monkeypatch.setattr(report_module, "report", lambda s, p=1.4, **kw: computed.append(kw["name"]) or real(s, p, **kw))
    second = report_batch(src, out=out, resume=True, progress=False)
    assert computed == ["a"] and second["status"] == ["ok", "skipped"] and second["atoms"] == [11, 12]
    assert len(sl.read_pdb(out / "a_cavities.pdb")) == 11
    computed.clear()
    third = report_batch(src, out=out, resume=True, probe=1.0, progress=False)  # another probe: redo all
    assert computed == ["a", "b"] and third["status"] == ["ok", "ok"]
    computed.clear()
    report_batch([b], out=out, resume=True, probe=1.0, hetatm=False, progress=False)  # another reading option
    assert computed == ["b"]
    computed.clear()
    (out / "b_cavities.md").unlink()  # a file the marker lists is gone
    assert report_batch([b], out=out, resume=True, probe=1.0, hetatm=False, progress=False)["status"] == ["ok"]
    assert computed == ["b"]
    computed.clear()
    kw = dict(out=out, resume=True, probe=1.0, hetatm=False, progress=False)
    assert report_batch([b], rank="none", **kw)["status"] == ["ok"]  # another ranking option: redo
    assert report_batch([b], rank="none", **kw)["status"] == ["skipped"]  # the same: skip
    assert report_batch([b], rank="none", top=1, **kw)["status"] == ["ok"]
    assert computed == ["b", "b"]
    assert (out / "b_cavities.md").read_text() == real(
        sl.read_pdb(b, hetatm=False), 1.0, name="b", rank="none", top=1
    ).to_markdown()


def test_resume_on_one_file_from_the_command_line(tmp_path):
    p, out = tiny_pdb(tmp_path / "cage.pdb"), tmp_path / "out"
    out.mkdir()
    res = run_cli([str(p), "--out", str(out), "--resume", "--no-progress"], tmp_path)
    assert (res.returncode, res.stdout) == (0, "")
    assert res.stderr.startswith("1 structures: 1 ok, 0 skipped, 0 failed")
    res = run_cli([str(p), "--out", str(out), "--resume", "--no-progress"], tmp_path)
    assert res.returncode == 0 and res.stderr.startswith("1 structures: 0 ok, 1 skipped, 0 failed")
    assert csv_rows(out / "shapelab_summary.csv")[0]["status"] == "skipped"


def test_one_file_keeps_its_output(tmp_path):
    # one existing file: stdout is its Markdown table, exactly as before; no summary, no marker
    p, out = tiny_pdb(tmp_path / "cage.pdb"), tmp_path / "out"
    out.mkdir()
    res = run_cli([str(p), "--out", str(out)], tmp_path)
    assert res.returncode == 0 and res.stderr == ""
    assert res.stdout == sl.report(sl.read_pdb(p), 1.4, name="cage").to_markdown()
    assert sorted(f.name for f in out.iterdir()) == [f"cage_cavities.{e}" for e in ("cif", "csv", "md", "pdb")]


def test_progress_goes_to_stderr(tmp_path, capsys):
    src, out = tmp_path / "in", tmp_path / "out"
    src.mkdir()
    out.mkdir()
    tiny_pdb(src / "a.pdb")
    (src / "b.ent").write_text("")
    summary = report_batch(src, out=out)
    cap = capsys.readouterr()
    assert cap.out == ""
    assert summary["status"] == ["ok", "failed"] and "empty" in summary[1]["error"]
    # stderr is not a terminal here: plain lines, even where tqdm is installed
    assert cap.err.splitlines() == [
        f"1/2  {src / 'a.pdb'}  ok",
        f"2/2  {src / 'b.ent'}  failed: {summary[1]['error']}",
    ]
    report_batch(src, out=out, progress=False)
    assert capsys.readouterr() == ("", "")


def test_expand_paths(tmp_path):
    d = tmp_path / "d"
    (d / "sub" / ".hidden").mkdir(parents=True)
    for name in ("x.pdb", "y.ENT.gz", "z.cif", "w.bcif.gz", "notes.txt", "x_cavities.pdb", ".h.pdb"):
        (d / name).write_text("")
    (d / "sub" / "v.pdb").write_text("")
    (d / "sub" / ".hidden" / "u.pdb").write_text("")
    (tmp_path / "empty").mkdir()
    got = expand_paths([d, d / "x.pdb", str(d / "sub" / "*.pdb"), tmp_path / "empty", "nothing*.pdb", "gone.pdb"])
    assert [(Path(label).relative_to(tmp_path) if p else label, e) for label, p, e in got] == [
        (Path("d/sub/v.pdb"), None),
        (Path("d/w.bcif.gz"), None),
        (Path("d/x.pdb"), None),  # listed once although named twice
        (Path("d/y.ENT.gz"), None),
        (Path("d/z.cif"), None),
        (str(tmp_path / "empty"), "no structure files (*.pdb, *.ent, *.cif, *.mmcif, *.bcif, .gz) in this folder"),
        ("nothing*.pdb", "no file matches this pattern"),
        ("gone.pdb", "no such file or directory"),
    ]
    # a file named on purpose is taken whatever its name
    assert expand_paths(d / "notes.txt") == [(str(d / "notes.txt"), d / "notes.txt", None)]
    with pytest.raises(TypeError, match="paths must be"):
        expand_paths([3])


@pytest.mark.parametrize(
    "name, stem",
    [
        ("1abc.pdb", "1abc"),
        ("1abc.pdb.gz", "1abc"),
        ("pdb1abc.ent.gz", "pdb1abc"),
        ("1abc.cif.gz", "1abc"),
        ("1abc.bcif", "1abc"),
        ("1ABC.PDB", "1ABC"),
        ("..pdb", "structure"),
        ("notes.txt", "notes.txt"),
    ],
)
def test_output_stem(name, stem):
    assert output_stem(Path("some/dir") / name) == stem


def test_same_stem_twice_fails_the_second(tmp_path):
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    tiny_pdb(tmp_path / "a" / "x.pdb")
    tiny_pdb(tmp_path / "b" / "x.ent")
    out = tmp_path / "out"
    out.mkdir()
    s = report_batch([tmp_path / "a", tmp_path / "b"], out=out, progress=False)
    assert s["status"] == ["ok", "failed"]
    assert s[1]["error"] == f"its output name x_cavities.* is already taken by {tmp_path / 'a' / 'x.pdb'}"


def test_every_input_is_read_by_content(tmp_path, monkeypatch):
    """read_structure reads every input (PDB or mmCIF by content, not by name)."""
    shapelab_io = importlib.import_module("shapelab.io")
    p = tiny_pdb(tmp_path / "cage.pdb")
    cif = tmp_path / "cage2.cif"
    cif.write_text("data_x\n")
    out = tmp_path / "out"
    out.mkdir()
    seen = []

    def fake_read_structure(path, **kw):
        seen.append(Path(path).name)
        return sl.read_pdb(p, **kw)

    monkeypatch.setattr(shapelab_io, "read_structure", fake_read_structure)
    s = report_batch([p, cif], out=out, progress=False, water=True)
    assert s["status"] == ["ok", "ok"] and seen == ["cage.pdb", "cage2.cif"]


def test_bad_options_and_output(tmp_path, capsys):
    p = tiny_pdb(tmp_path / "cage.pdb")
    with pytest.raises(ValueError, match="jobs must be at least 1, got 0"):
        report_batch(p, out=tmp_path, jobs=0)
    with pytest.raises(TypeError, match="jobs must be an integer"):
        report_batch(p, out=tmp_path, jobs=1.5)
    with pytest.raises(ValueError, match="probe must be non-negative"):
        report_batch(p, out=tmp_path, probe=-1.0)
    with pytest.raises(ValueError, match="summary must be"):
        report_batch(p, out=tmp_path, summary="a/b")
    with pytest.raises(FileNotFoundError, match="output directory"):
        report_batch(p, out=tmp_path / "missing")
    assert cli.main(["report", str(p), str(p), "--out", str(tmp_path / "missing")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("error: output directory") and err.count("\n") == 1
    assert cli.main(["report", str(p), str(p), "--out", str(tmp_path), "--jobs", "0"]) == 2
    assert capsys.readouterr().err == "error: jobs must be at least 1, got 0\n"
    assert not (tmp_path / "shapelab_summary.csv").exists()


def test_summary_table():
    row = dict.fromkeys(SUMMARY_COLUMNS)
    row.update(path="p", stem="p", status="ok", error="", atoms=3, voids=0, pockets=1, largest_pocket_volume=0.5)
    t = BatchSummary(rows=(row,))
    assert len(t) == 1 and t["atoms"] == [3] and t[0] is row and list(t) == [row]
    assert t.columns == SUMMARY_COLUMNS and t.failed == ()
    assert t.to_csv_text().splitlines()[1] == "p,p,ok,,3,0,1,,0.500000,"
    with pytest.raises(KeyError, match="no column 'volume'"):
        t["volume"]


def test_pandas_and_parquet(batch_jobs2):
    out, summary = batch_jobs2
    if _has("pandas"):
        df = summary.to_pandas()
        assert list(df.columns) == list(SUMMARY_COLUMNS) and list(df["status"]) == summary["status"]
    if _has("pyarrow"):
        import pyarrow.parquet as pq

        assert pq.read_table(out / "shapelab_summary.parquet").to_pylist() == list(summary.rows)
    else:
        assert summary.files == (out / "shapelab_summary.csv",)


def test_no_marker_survives_files_it_does_not_describe(tmp_path, monkeypatch):
    # files rewritten for another probe, then interrupted before their marker: the old
    # marker (probe 1.4) must not make --resume at probe 1.4 skip the probe-1.0 files
    batch = importlib.import_module("shapelab.tools.batch")
    src, out = tmp_path / "in", tmp_path / "out"
    src.mkdir()
    out.mkdir()
    tiny_pdb(src / "a.pdb")
    assert report_batch(src, out=out, progress=False)["status"] == ["ok"]

    real = batch._write_atomic

    def interrupted(path, text):
        if path.name.endswith(".done.json"):
            raise OSError("interrupted before the marker")
        real(path, text)

    monkeypatch.setattr(batch, "_write_atomic", interrupted)
    s = report_batch(src, out=out, probe=1.0, progress=False)
    assert s["status"] == ["failed"] and s["error"] == ["interrupted before the marker"]
    assert "probe 1 Å" in (out / "a_cavities.md").read_text()  # the files are the probe-1.0 report
    monkeypatch.undo()
    assert report_batch(src, out=out, resume=True, progress=False)["status"] == ["ok"]
    assert "probe 1.4 Å" in (out / "a_cavities.md").read_text()


def test_one_file_and_a_batch_name_a_bcif_file_alike(tmp_path):
    # the single-file command line kept ".bcif" in the name (x.bcif_cavities.*), the batch did not
    import gzip

    from shapelab.tools import cli

    pytest.importorskip("biotite")  # the BinaryCIF reader (shapelab[bcif])
    src = tmp_path / "x.bcif.gz"  # a real BinaryCIF entry, gzip'd (P2Rank's test data, tests/data/SOURCES.json)
    src.write_bytes(gzip.compress((ROOT / "tests" / "data" / "1fbl.bcif").read_bytes()))
    (tmp_path / "one").mkdir()
    (tmp_path / "many").mkdir()
    with contextlib.redirect_stdout(io.StringIO()):
        assert cli.main(["report", str(src), "--out", str(tmp_path / "one"), "--rank", "none"]) == 0
    report_batch([src], out=tmp_path / "many", rank="none", progress=False)
    one = sorted(p.name for p in (tmp_path / "one").iterdir())
    assert one == sorted(
        p.name
        for p in (tmp_path / "many").iterdir()
        if p.suffix in (".csv", ".md", ".cif", ".pdb") and "summary" not in p.name
    )
    assert one[0].startswith("x_cavities.")


def test_progress_on_a_terminal_without_a_size_is_lines(monkeypatch):
    # tqdm on a terminal of 0 columns (script, some CI runners) drew nothing at all
    import fcntl
    import importlib.util
    import pty
    import struct
    import termios

    batch = importlib.import_module("shapelab.tools.batch")
    master, slave = pty.openpty()
    with os.fdopen(slave, "w") as tty:
        fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 0, 0, 0, 0))
        monkeypatch.setattr(sys, "stderr", tty)
        assert batch._Progress(3, True).bar is None
        if importlib.util.find_spec("tqdm") is not None:
            fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 80, 0, 0))
            bar = batch._Progress(3, True)
            assert bar.bar is not None
            bar.close()
    os.close(master)
