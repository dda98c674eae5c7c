"""shapelab.batch on a Dask cluster: ``report_batch(client=...)`` and ``--scheduler ADDRESS``.

The oracle is the local batch (``jobs=1``, itself tested against the single-file command
line in test_batch.py): on a two-worker ``distributed.LocalCluster`` on loopback the
same shipped structures and one malformed file give the same files, byte for byte (done
markers included), and the same summary but for its ``seconds`` column.  Resuming on the
cluster is checked by the statuses and by the untouched files of skipped structures.
Every test is bounded by an alarm and every subprocess by a timeout, so that a cluster
that does not answer fails the test instead of hanging CI.  Skips without dask.distributed
(the optional extra ``shapelab[dask]``).
"""

from __future__ import annotations

import filecmp
import importlib
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from shapelab.datasets import structure_path
from shapelab.tools.batch import SUMMARY_COLUMNS, report_batch

dask = pytest.importorskip("dask", reason='dask is not installed (pip install "shapelab[dask]")')
distributed = pytest.importorskip(
    "distributed", reason='dask.distributed is not installed (pip install "shapelab[dask]")'
)

ROOT = Path(__file__).resolve().parents[2]
DATA = structure_path("1hvr").parent
SHIPPED = ["globule.pdb", "1grm_single.pdb.gz", "1hvr.pdb.gz"]
BAD = "ATOM      1  CA  ALA A   1      1.000   xyz     3.000  1.00  0.00           C\n"
LIMIT = 120  # seconds for any one test: far above what it takes, far below a hung CI job


@pytest.fixture(autouse=True)
def alarm():
    """Fail, instead of hanging, a test that waits on a cluster that never answers."""

    def fire(signum, frame):
        raise TimeoutError(f"the test took more than {LIMIT} s: is the Dask cluster answering?")

    old = signal.signal(signal.SIGALRM, fire)
    signal.alarm(LIMIT)
    yield
    signal.alarm(0)
    signal.signal(signal.SIGALRM, old)


@pytest.fixture(scope="module")
def cluster():
    # Dask's nanny starts its workers with MALLOC_TRIM_THRESHOLD_=65536, which makes glibc
    # return the library's mid-sized arrays to the system at once: two to three times the CPU
    # time (page faults).  Unset, as the README says for real clusters ("On a Dask cluster").
    def fire(signum, frame):  # the function-scoped alarm is not armed yet: a cluster that never starts
        raise TimeoutError(f"the LocalCluster did not start within {LIMIT} s")

    old = signal.signal(signal.SIGALRM, fire)
    signal.alarm(LIMIT)
    try:
        with dask.config.set({"distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_": None}):
            c = distributed.LocalCluster(
                n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1", dashboard_address=None
            )
        client = distributed.Client(c, timeout=60, set_as_default=False)  # not the default client
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)
    with c, client:
        yield c, client


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    """Three shipped structures and one malformed file."""
    d = tmp_path_factory.mktemp("inputs")
    for name in SHIPPED:
        shutil.copy(DATA / name, d / name)
    (d / "bad.pdb").write_text(BAD)
    return d


@pytest.fixture(scope="module")
def local(folder, tmp_path_factory):
    out = tmp_path_factory.mktemp("local")
    return out, report_batch(folder, out=out, progress=False)


@pytest.fixture(scope="module")
def on_cluster(folder, cluster, tmp_path_factory):
    out = tmp_path_factory.mktemp("dask")
    return out, report_batch(folder, out=out, client=cluster[1], progress=False)


def without_seconds(summary):
    return [{k: r[k] for k in SUMMARY_COLUMNS if k != "seconds"} for r in summary]


def summary_lines(path):
    """The summary CSV's lines without the seconds column (the last one)."""
    lines = Path(path).read_text().splitlines()
    assert lines[0].endswith(",seconds")
    return [line.rsplit(",", 1)[0] for line in lines]


def assert_same_files(a: Path, b: Path, names=None):
    # the summaries (CSV, Parquet) hold the seconds column: compared apart, without it
    names = (
        sorted(p.name for p in a.iterdir() if not p.name.startswith("shapelab_summary.")) if names is None else names
    )
    assert names, "nothing to compare"
    match, mismatch, errors = filecmp.cmpfiles(a, b, names, shallow=False)
    assert (mismatch, errors) == ([], []), f"differ: {mismatch}, missing: {errors}"
    return names


def test_cluster_writes_what_a_local_batch_writes(local, on_cluster):
    (a, sa), (b, sb) = local, on_cluster
    names = assert_same_files(a, b)
    # four files and a marker per structure that reports; nothing for the malformed one
    assert {n.split("_cavities")[0] for n in names} == {"globule", "1grm_single", "1hvr"}
    assert len(names) == 15 and not any(n.startswith("bad") for n in names)
    assert sorted(p.name for p in a.iterdir()) == sorted(p.name for p in b.iterdir())
    assert summary_lines(a / "shapelab_summary.csv") == summary_lines(b / "shapelab_summary.csv")
    assert without_seconds(sa) == without_seconds(sb)
    if (a / "shapelab_summary.parquet").exists():  # with pyarrow installed (the test extra)
        import pyarrow.parquet as pq

        rows = [pq.read_table(d / "shapelab_summary.parquet").to_pylist() for d in (a, b)]
        assert without_seconds(rows[0]) == without_seconds(rows[1]) == without_seconds(sa)
    assert [(Path(r["path"]).name, r["status"]) for r in sb] == [
        ("1grm_single.pdb.gz", "ok"),
        ("1hvr.pdb.gz", "ok"),
        ("bad.pdb", "failed"),
        ("globule.pdb", "ok"),
    ]
    # the worker read a private copy, but the error reads as the local one (no temporary path)
    assert sb.failed[0]["error"] == "line 1: could not read y from columns 39-46: 'xyz'"
    assert all(r["seconds"] >= 0 for r in sb)


def test_resume_on_the_cluster(local, on_cluster, folder, cluster, tmp_path):
    out = tmp_path / "out"
    shutil.copytree(on_cluster[0], out)
    (out / "1hvr_cavities.done.json").unlink()  # interrupted after its files, before its marker
    (out / "globule_cavities.md").unlink()  # a listed file lost: not complete either
    kept = {p.name: p.stat().st_mtime_ns for p in out.iterdir() if p.name.startswith("1grm_single")}
    summary = report_batch(folder, out=out, resume=True, client=cluster[1], progress=False)
    assert [(Path(r["path"]).name, r["status"]) for r in summary] == [
        ("1grm_single.pdb.gz", "skipped"),
        ("1hvr.pdb.gz", "ok"),
        ("bad.pdb", "failed"),
        ("globule.pdb", "ok"),
    ]
    assert {n: (out / n).stat().st_mtime_ns for n in kept} == kept  # skipped: not rewritten
    assert_same_files(local[0], out)  # and everything is as a local batch wrote it
    again = report_batch(folder, out=out, resume=True, client=cluster[1], progress=False)
    assert again.counts() == {"ok": 0, "failed": 1, "skipped": 3}
    # the local batch accepts the cluster's markers, and the other way round
    assert report_batch(folder, out=out, resume=True, progress=False).counts()["skipped"] == 3


def _spy_on_reads():
    """On a worker: record every path shapelab.io.read_structure is given."""
    import shapelab.io as sio

    real = sio.read_structure
    seen = []

    def spy(path, **kw):
        seen.append(str(path))
        return real(path, **kw)

    spy.real, spy.seen = real, seen
    sio.read_structure = spy


def _stop_spying():
    import shapelab.io as sio

    seen = sio.read_structure.seen
    sio.read_structure = sio.read_structure.real
    return seen


def test_workers_read_a_copy_of_the_bytes_not_the_input(folder, cluster, tmp_path):
    client = cluster[1]
    client.run(_spy_on_reads)
    try:
        summary = report_batch([folder / "1grm_single.pdb.gz"], out=tmp_path, client=client, progress=False)
    finally:
        seen = [p for paths in client.run(_stop_spying).values() for p in paths]
    assert summary["status"] == ["ok"]
    assert len(seen) == 1 and seen[0].endswith("/1grm_single.pdb.gz")  # under its own name ...
    assert not seen[0].startswith(str(folder))  # ... in the worker's temporary folder, not the input
    assert not Path(seen[0]).exists()  # removed once read


def test_progress_lines_as_the_local_batch(folder, cluster, tmp_path, capsys):
    paths = [folder / "1grm_single.pdb.gz", folder / "bad.pdb", folder / "missing.pdb"]
    report_batch(paths, out=tmp_path, client=cluster[1])
    captured = capsys.readouterr()
    assert captured.out == ""
    lines = captured.err.splitlines()
    assert lines[0] == f"1/3  {folder / 'missing.pdb'}  failed: no such file or directory"  # known at once
    assert sorted(line.split("  ")[0] for line in lines[1:]) == ["2/3", "3/3"]
    assert sorted(line.split("  ", 1)[1] for line in lines[1:]) == [
        f"{folder / '1grm_single.pdb.gz'}  ok",
        f"{folder / 'bad.pdb'}  failed: line 1: could not read y from columns 39-46: 'xyz'",
    ]


def test_command_line_with_scheduler_and_figure(local, folder, cluster, tmp_path):
    out = tmp_path / "cli"
    out.mkdir()
    res = subprocess.run(
        [
            sys.executable,
            "-m",
            "shapelab",
            "report",
            str(folder),
            "--out",
            str(out),
            "--scheduler",
            cluster[0].scheduler_address,
            "--figure",
            str(out / "summary.png"),
        ],
        env=dict(os.environ, PYTHONPATH=str(ROOT)),
        capture_output=True,
        text=True,
        timeout=LIMIT - 10,
    )
    assert res.returncode == 1, res.stderr  # one input failed
    assert res.stdout == ""
    assert f"error: {folder / 'bad.pdb'}: line 1: could not read y" in res.stderr
    assert "4 structures: 3 ok, 0 skipped, 1 failed" in res.stderr
    assert str(out / "summary.png") in res.stderr.splitlines()[-1]
    assert (out / "summary.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert_same_files(local[0], out)
    assert summary_lines(local[0] / "shapelab_summary.csv") == summary_lines(out / "shapelab_summary.csv")


def test_command_line_refuses_jobs_with_scheduler_and_a_bad_figure(folder, tmp_path, capsys):
    from shapelab.tools import cli

    assert cli.main(["report", str(folder), "--out", str(tmp_path), "--jobs", "2", "--scheduler", "tcp://x:1"]) == 2
    assert "--jobs" in capsys.readouterr().err
    assert cli.main(["report", str(folder), "--out", str(tmp_path), "--figure", str(tmp_path / "s.xyz")]) == 2
    assert ".png" in capsys.readouterr().err
    assert cli.main(["report", str(folder), "--out", str(tmp_path), "--figure", str(tmp_path / "no" / "s.png")]) == 2
    assert "does not exist" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []  # refused before anything ran


def test_bad_client_arguments(folder, cluster, tmp_path):
    client = cluster[1]
    with pytest.raises(ValueError, match="not both"):
        report_batch(folder, out=tmp_path, client=client, scheduler=cluster[0].scheduler_address)
    with pytest.raises(ValueError, match="jobs=2"):
        report_batch(folder, out=tmp_path, client=client, jobs=2)
    with pytest.raises(TypeError, match="client must be a dask.distributed.Client"):
        report_batch(folder, out=tmp_path, client="tcp://127.0.0.1:1")
    with pytest.raises(TypeError, match="scheduler"):
        report_batch(folder, out=tmp_path, scheduler=8786)
    assert list(tmp_path.iterdir()) == []


def clients(cluster):
    return cluster[1].run_on_scheduler(lambda dask_scheduler: len(dask_scheduler.clients))


def test_scheduler_address_connects_and_disconnects(folder, cluster, tmp_path):
    before = clients(cluster)
    summary = report_batch(
        [folder / "globule.pdb"], out=tmp_path, scheduler=cluster[0].scheduler_address, progress=False
    )
    assert summary["status"] == ["ok"]
    for _ in range(100):  # the scheduler hears of the closed client soon after it closes
        if clients(cluster) == before:
            break
        time.sleep(0.1)
    assert clients(cluster) == before  # the batch's own client is closed


def test_a_large_input_travels_without_dask_warning(cluster, tmp_path):
    """An input of more than Dask's 10 MB large-graph threshold: sent in its task (so that
    another worker can retry it) without a warning per file, and failed as locally."""
    import warnings

    big = tmp_path / "in" / "remarks.pdb"
    big.parent.mkdir()
    big.write_bytes((b"REMARK 999 " + b"x" * 68 + b"\n") * 140_000)  # 11.2 MB, no atoms
    (tmp_path / "a").mkdir()
    (tmp_path / "b").mkdir()
    local = report_batch([big], out=tmp_path / "a", progress=False)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        remote = report_batch([big], out=tmp_path / "b", client=cluster[1], progress=False)
    assert [str(w.message).splitlines()[0] for w in caught if "large graph" in str(w.message)] == []
    assert without_seconds(remote) == without_seconds(local)
    assert remote["status"] == ["failed"] and "no ATOM or HETATM records" in remote[0]["error"]


class _DieOn(distributed.WorkerPlugin):
    """On every worker, present and to come: a report on a structure named ``die_here``
    ends the worker's process (as a segfault or the kernel's OOM killer would)."""

    name = "shapelab-test-die-on"

    def setup(self, worker):
        cr = importlib.import_module("shapelab.report")

        real = getattr(cr.report, "real", cr.report)

        def report(s, probe, name=None, **kw):
            if name == "die_here":
                os._exit(9)
            return real(s, probe, name=name, **kw)

        report.real = real
        cr.report = report


def test_a_structure_that_kills_every_worker_is_named_and_the_batch_finishes(folder, cluster, tmp_path):
    client = cluster[1]
    (tmp_path / "in").mkdir()
    shutil.copy(DATA / "globule.pdb", tmp_path / "in" / "die_here.pdb")

    def failures(n):  # the scheduler's allowed-failures (3 by default): 1 keeps the test to two deaths
        return client.run_on_scheduler(lambda dask_scheduler: setattr(dask_scheduler, "allowed_failures", n))

    default = client.run_on_scheduler(lambda dask_scheduler: dask_scheduler.allowed_failures)
    failures(1)
    client.register_plugin(_DieOn())
    try:
        summary = report_batch(
            [tmp_path / "in" / "die_here.pdb", folder / "1grm_single.pdb.gz"],
            out=tmp_path,
            client=client,
            progress=False,
        )
    finally:
        client.unregister_worker_plugin(_DieOn.name)
        failures(default)
    assert summary["status"] == ["failed", "ok"]  # retried once on another (or restarted) worker, then given up
    assert summary[0]["error"] == "the worker process died while reporting on this structure"
    assert not any(p.name.startswith("die_here") for p in tmp_path.iterdir())
    client.wait_for_workers(2, timeout=LIMIT - 20)  # the nannies restart them: slow on a loaded machine


def test_a_worker_that_cannot_write_its_temporary_copy_fails_the_file_not_the_batch(folder, cluster, tmp_path):
    client = cluster[1]
    full = (
        "import shapelab.tools.batch as b, tempfile\n"
        "def full(*a, **k):\n"
        "    raise OSError(28, 'No space left on device')\n"
        "b.tempfile = type('T', (), {'TemporaryDirectory': staticmethod(full)})\n"
    )
    client.run(exec, full, {})
    try:
        summary = report_batch(
            [folder / "globule.pdb", folder / "missing.pdb"], out=tmp_path, client=client, progress=False
        )
    finally:
        client.run(exec, "import shapelab.tools.batch as b, tempfile; b.tempfile = tempfile", {})
    assert summary["status"] == ["failed", "failed"]
    assert summary[0]["error"] == "[Errno 28] No space left on device"
    assert summary[1]["error"] == "no such file or directory"
    import importlib.util

    summaries = {"shapelab_summary.csv"} | (
        {"shapelab_summary.parquet"} if importlib.util.find_spec("pyarrow") else set()
    )
    assert {p.name for p in tmp_path.iterdir()} == summaries  # the summary only: no report of a failed file


def test_an_address_where_no_scheduler_answers(folder, cluster, tmp_path):
    """Something else at the address (a web server, a worker): an OSError naming it, not
    Distributed's MemoryError or TypeError followed by a minute's wait for the half-made client."""
    import socket
    import threading

    server = socket.create_server(("127.0.0.1", 0))
    port = server.getsockname()[1]

    def http():
        with server:
            while True:
                try:
                    conn, _ = server.accept()
                except OSError:
                    return
                with conn:
                    conn.recv(100)
                    conn.sendall(b"HTTP/1.1 400 Bad Request\r\nContent-Length: 0\r\n\r\n")

    threading.Thread(target=http, daemon=True).start()
    try:
        with pytest.raises(OSError, match=f"no Dask scheduler answers at 'tcp://127.0.0.1:{port}'.*protocol"):
            report_batch(folder, out=tmp_path, scheduler=f"tcp://127.0.0.1:{port}", progress=False)
    finally:
        server.close()
    worker = sorted(cluster[1].scheduler_info()["workers"])[0]
    with pytest.raises(OSError, match="a Dask Worker does: give its scheduler's address"):
        report_batch(folder, out=tmp_path, scheduler=worker, progress=False)
    assert list(tmp_path.iterdir()) == []


def test_workers_without_shapelab_are_named_before_anything_is_sent(folder, cluster, tmp_path):
    """A worker that cannot unpickle a task ends, and the batch would wait for workers forever."""
    client = cluster[1]
    hide = "import sys; sys.saved_shapelab = sys.modules.get('shapelab'); sys.modules['shapelab'] = None"
    show = "import sys; sys.modules.pop('shapelab'); sys.saved_shapelab and sys.modules.update(shapelab=sys.saved_shapelab)"
    client.run(exec, hide, {})
    try:
        with pytest.raises(ImportError, match="a worker of the Dask cluster cannot import shapelab"):
            report_batch(folder, out=tmp_path, client=client, progress=False)
    finally:
        client.run(exec, show, {})
    client.run(exec, "import shapelab; shapelab.saved_version = shapelab.__version__; shapelab.__version__ = '0.0'", {})
    try:
        with pytest.raises(ImportError, match=r"need shapelab .*, as here, but tcp://127\.0\.0\.1:\d+ has 0\.0"):
            report_batch(folder, out=tmp_path, client=client, progress=False)
    finally:
        client.run(exec, "import shapelab; shapelab.__version__ = shapelab.saved_version", {})
    assert list(tmp_path.iterdir()) == []
    assert report_batch([folder / "bad.pdb"], out=tmp_path, client=client, progress=False)["status"] == ["failed"]


def test_ctrl_c_says_how_to_finish(folder, tmp_path, monkeypatch, capsys):
    from shapelab.tools import batch, cli

    def interrupted(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(batch, "report_batch", interrupted)
    assert cli.main(["report", str(folder), "--out", str(tmp_path), "--scheduler", "tcp://127.0.0.1:1"]) == 130
    assert capsys.readouterr().err == (
        "interrupted: the structures finished are kept; run again with --resume to finish\n"
    )


def test_without_dask_the_error_names_the_extra(folder, tmp_path, monkeypatch, capsys):
    monkeypatch.setitem(sys.modules, "distributed", None)  # import distributed now fails
    with pytest.raises(ImportError, match=r"pip install \"shapelab\[dask\]\""):
        report_batch(folder, out=tmp_path, scheduler="tcp://127.0.0.1:1")
    from shapelab.tools import cli

    assert cli.main(["report", str(folder), "--out", str(tmp_path), "--scheduler", "tcp://127.0.0.1:1"]) == 2
    assert 'pip install "shapelab[dask]"' in capsys.readouterr().err


def test_local_batches_never_import_dask(tmp_path):
    code = (
        "import sys, shapelab, shapelab.tools.batch, shapelab.tools.cli\n"
        "from shapelab.tools.batch import report_batch\n"
        "from shapelab.datasets import structure_path\n"
        f"s = report_batch([structure_path('1grm')], out={str(tmp_path)!r}, progress=False)\n"
        "assert s['status'] == ['ok'], s.rows\n"
        "print(sorted(m for m in sys.modules if m.split('.')[0] in ('dask', 'distributed')))\n"
    )
    res = subprocess.run(
        [sys.executable, "-c", code],
        env=dict(os.environ, PYTHONPATH=str(ROOT)),
        capture_output=True,
        text=True,
        timeout=LIMIT - 10,
    )
    assert res.returncode == 0, res.stderr
    assert res.stdout.strip() == "[]"
