"""Cavity reports of many structures at once: files, folders and globs, in parallel (Notes §23.1).

:func:`report_batch` runs :func:`shapelab.report` on every structure file it is given
-- files, folders (searched recursively for ``*.pdb``, ``*.ent``, ``*.cif``,
``*.mmcif``, ``*.bcif`` and the same names ending in ``.gz``) and glob patterns -- and writes, for
each, the same files as the command line does for one file
(:meth:`shapelab.cavity_report.CavityReport.write`: ``<stem>_cavities.csv``, ``.md``,
``.cif`` and, when the format can hold it, ``.pdb``), then one summary table for the
batch.  It is the library behind ``python -m shapelab report PATH PATH ...``
(:mod:`shapelab.tools.cli`).

* **Parallel**: ``jobs=N`` runs ``N`` worker processes
  (:class:`concurrent.futures.ProcessPoolExecutor`, started with ``spawn``), each of
  which imports shapelab once, in its initializer, and then reports on structure
  after structure.
* **On a Dask cluster**: ``client=`` (a :class:`dask.distributed.Client`) or
  ``scheduler="tcp://HOST:PORT"`` sends the same tasks to Dask's workers instead
  (``pip install "shapelab[dask]"``; dask is imported only then).  The inputs travel
  to the workers as bytes and the reports come back: only this process reads the
  inputs and writes into the output directory, so the workers need shapelab
  installed and nothing else -- no shared file system.
* **Failures carry on**: a file that cannot be read, is malformed, or fails in the
  computation gets a row of status ``"failed"`` with its error message; the others
  are reported as usual.
* **Resumable**: each structure's files are written atomically, and then a *done
  marker* ``<stem>_cavities.done.json``, last.  A structure is **complete** when its
  marker exists, names the same input file with the same SHA-256 digest, the same
  probe and the same reading options, and every file it lists exists.  With
  ``resume=True`` complete structures are skipped (status ``"skipped"``; their
  counts come from the marker), so a batch that was interrupted -- or that is run
  again after some inputs changed -- recomputes only what is missing or out of date.
* **Summary**: ``<summary>.csv`` in the output directory, always, and
  ``<summary>.parquet`` too when ``pyarrow`` is installed (it is not a dependency of
  shapelab).  The rows are in input order, whatever order the workers finish in.

The summary is returned as a :class:`BatchSummary`, a small read-only table that
depends on nothing; :meth:`BatchSummary.to_pandas` turns it into a
:class:`pandas.DataFrame` when pandas is installed (it is not a dependency either).
Returning the same type whatever is installed keeps code that uses the result
portable.

Progress goes to standard error, never to standard output: a ``tqdm`` bar when tqdm
is installed and standard error is a terminal, otherwise one line ``k/n  PATH  status``
per structure (what a log file, a notebook or a CI job can read).
"""

from __future__ import annotations

import csv
import glob
import hashlib
import io as _stdio
import json
import os
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

from .._toolkit.validate import as_finite_scalar, as_positive_int

__all__ = [
    "BatchSummary",
    "report_batch",
    "expand_paths",
    "output_stem",
    "read_structure_file",
    "error_message",
    "STRUCTURE_SUFFIXES",
    "SUMMARY_COLUMNS",
]

#: File name endings a folder is searched for (each also with ``.gz``), lower case.
STRUCTURE_SUFFIXES = (".pdb", ".ent", ".cif", ".mmcif", ".bcif")

#: The summary's columns, in order.
SUMMARY_COLUMNS = (
    "path",
    "stem",
    "status",
    "error",
    "atoms",
    "voids",
    "pockets",
    "largest_void_volume",
    "largest_pocket_volume",
    "seconds",
)

_MARKER_VERSION = 1
_MMCIF = (".cif", ".mmcif", ".bcif")


# ============================================================================ inputs
def output_stem(path) -> str:
    """The prefix of a structure's output files: its file name without ``.gz`` and format suffix.

    The command line's rule for one file: ``.gz``, ``.pdb``, ``.ent``, ``.cif``,
    ``.mmcif`` and ``.bcif`` are removed from the end of the name, in that order,
    each where present (``1abc.pdb.gz`` -> ``1abc``, ``1abc.cif.gz`` -> ``1abc``).  A
    name that leaves nothing a file could be named by (``..pdb``) gives
    ``structure``.

    Parameters
    ----------
    path : str or os.PathLike
        The structure file; only its name is used.

    Returns
    -------
    str

    See Also
    --------
    report_batch
        Names each structure's files by it.
    shapelab.cavity_report.CavityReport.write
        Writes ``<stem>_cavities.*``.

    Examples
    --------
    >>> output_stem("data/1hvr.pdb.gz"), output_stem("x/2abc.cif"), output_stem("..pdb")
    ('1hvr', '2abc', 'structure')
    """
    stem = Path(path).name
    for suffix in (".gz", ".pdb", ".ent", ".cif", ".mmcif", ".bcif"):
        if stem.lower().endswith(suffix):
            stem = stem[: -len(suffix)]
    if stem in ("", ".", ".."):
        stem = "structure"
    return stem


def _is_structure_name(name: str) -> bool:
    n = name.lower()
    if n.endswith(".gz"):
        n = n[:-3]
    return n.endswith(STRUCTURE_SUFFIXES)


def _is_our_output(p: Path) -> bool:
    """A marked structure written by a report (``<stem>_cavities.pdb`` or ``.cif``)."""
    n = p.name.lower()
    return n.endswith(("_cavities.pdb", "_cavities.cif"))


def _walk(folder: Path) -> list[Path]:
    found = []
    for root, dirs, files in os.walk(folder):
        dirs[:] = sorted(d for d in dirs if not d.startswith("."))
        for f in sorted(files):
            if not f.startswith(".") and _is_structure_name(f):
                p = Path(root) / f
                if not _is_our_output(p):
                    found.append(p)
    return sorted(found, key=lambda p: p.relative_to(folder).parts)


def expand_paths(paths) -> list[tuple[str, Path | None, str | None]]:
    """The structure files that ``paths`` names: files, folders and glob patterns.

    Each entry of ``paths`` is, in this order of precedence: an existing
    **folder**, searched recursively (hidden names skipped; in sorted order of the
    paths) for
    files whose names end in ``.pdb``, ``.ent``, ``.cif``, ``.mmcif`` or ``.bcif``, each
    optionally followed by ``.gz``, case-insensitively -- leaving out
    ``*_cavities.pdb`` and ``*_cavities.cif``, the marked structures a report
    writes; an existing **file**, taken whatever its name; or a **glob pattern**
    (``*``, ``?``, ``[...]``, and ``**`` across folders), whose matches are taken in
    sorted order (folders among them searched as above).  A file reached twice is
    listed once, where it was first reached.

    Parameters
    ----------
    paths : str, os.PathLike or iterable of them

    Returns
    -------
    list of (str, pathlib.Path or None, str or None)
        ``(label, path, error)`` per input: ``label`` is the path as given or
        found, ``path`` the file (None when there is none) and ``error`` why an
        entry of ``paths`` gave no file (a missing path, a pattern that matches
        nothing, a folder without structure files), else None.

    See Also
    --------
    report_batch
        Reports on what this finds.

    Examples
    --------
    >>> from shapelab.datasets import structure_path
    >>> [p.name for _, p, _ in expand_paths(structure_path("1hvr").parent / "*.pdb")]
    ['globule.pdb']
    >>> expand_paths(["/no/such/file.pdb"])
    [('/no/such/file.pdb', None, 'no such file or directory')]
    """
    if isinstance(paths, (str, os.PathLike)):
        paths = [paths]
    out, seen = [], set()

    def add(p: Path):
        key = os.path.realpath(p)
        if key not in seen:
            seen.add(key)
            out.append((os.fspath(p), p, None))

    for entry in paths:
        if not isinstance(entry, (str, os.PathLike)):
            raise TypeError(f"paths must be file names, folder names or glob patterns, got {entry!r}")
        label = os.fspath(entry)
        p = Path(entry)
        if p.is_dir():
            found = _walk(p)
            if not found:
                out.append(
                    (label, None, "no structure files (*.pdb, *.ent, *.cif, *.mmcif, *.bcif, .gz) in this folder")
                )
            for f in found:
                add(f)
        elif p.exists():
            add(p)
        elif glob.has_magic(label):
            matches = sorted(glob.glob(label, recursive=True))
            files = []
            for m in matches:
                mp = Path(m)
                files.extend(_walk(mp) if mp.is_dir() else [mp] if mp.is_file() else [])
            if not files:
                out.append((label, None, "no file matches this pattern"))
            for f in files:
                add(f)
        else:
            out.append((label, None, "no such file or directory"))
    return out


# ============================================================================ one structure
def _sha256(path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def error_message(e: BaseException) -> str:
    """The first line of an exception's message, as the command line prints it.

    The exception's type is named too unless it is a ValueError, TypeError or
    OSError (the errors of a bad file, which say what is wrong in their message).

    See Also
    --------
    report_batch
        Records it as the ``error`` of a failed input.

    Examples
    --------
    >>> error_message(ValueError("line 3: bad x")), error_message(OSError()), error_message(ZeroDivisionError("division by zero"))
    ('line 3: bad x', 'OSError', 'ZeroDivisionError: division by zero')
    """
    msg = str(e).splitlines()[0] if str(e).strip() else type(e).__name__
    if not isinstance(e, (ValueError, TypeError, OSError)) and not msg.startswith(type(e).__name__):
        msg = f"{type(e).__name__}: {msg}"
    return msg


def read_structure_file(path, **options):
    """Read one structure file with :func:`shapelab.io.read_structure`, which decides the
    format by the file's content (PDB or mmCIF, plain or gzip), not by its name.

    Parameters
    ----------
    path : str or os.PathLike
    **options
        The reader's keyword arguments (``chain``, ``model``, ``hetatm``, ...).

    Returns
    -------
    shapelab.io.PDBStructure

    See Also
    --------
    shapelab.io.read_structure
        The reader and its options.
    report_batch
        Reads every input with it.
    """
    from .. import io

    return io.read_structure(path, **options)


def _marker_path(out: Path, stem: str) -> Path:
    return out / f"{stem}_cavities.done.json"


def _marker_key(task: dict, sha: str) -> dict:
    return {
        "input": os.path.realpath(task["path"]),
        "sha256": sha,
        "probe": task["probe"],
        "options": _jsonable(task["options"]),
        "report": task["report"],
    }


def _jsonable(options: dict) -> dict:
    return {k: sorted(v) if isinstance(v, (set, frozenset, list, tuple)) else v for k, v in options.items()}


def _write_atomic(path: Path, text: str) -> None:
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "w", encoding="utf-8", newline="") as fh:
            fh.write(text)
        mask = os.umask(0)
        os.umask(mask)
        os.chmod(tmp, 0o666 & ~mask)
        os.replace(tmp, path)
    finally:
        Path(tmp).unlink(missing_ok=True)


def _empty_row(label: str, stem: str | None) -> dict:
    row = dict.fromkeys(SUMMARY_COLUMNS)
    row.update(path=label, stem=stem, status="failed", error="")
    return row


def _ok(row: dict, structure, rep) -> None:
    """Fill a row with the counts of a computed report."""
    voids = [r.volume_sa for r in rep.voids]
    pockets = [r.volume_sa for r in rep.pockets]
    row.update(
        status="ok",
        atoms=len(structure),
        voids=len(voids),
        pockets=len(pockets),
        largest_void_volume=max(voids) if voids else None,
        largest_pocket_volume=max(pockets) if pockets else None,
    )


def _failed(row: dict, e: BaseException, path, shown=None) -> None:
    """Record a failure in a row: the error's first line, without the file's name in
    front (the row names its file already); ``shown`` is the path to name instead of
    ``path`` where the message names the file elsewhere (a worker's local copy)."""
    msg = error_message(e)
    if shown is not None and os.fspath(path) != shown:
        msg = msg.replace(os.fspath(path), shown)
        path = shown
    for prefix in (f"{os.fspath(path)!r}: ", f"{os.fspath(path)}: "):
        if msg.startswith(prefix):
            msg = msg[len(prefix) :]
    row.update(status="failed", error=msg)
    for k in ("atoms", "voids", "pockets", "largest_void_volume", "largest_pocket_volume"):
        row[k] = None


def _store(task: dict, sha: str, row: dict, rep, *, check: bool = True) -> None:
    """Write a computed report's files into the output directory, then its done marker
    (``check``: first :func:`shapelab.cavity_report.check_output`, unless done already)."""
    from .. import cavity_report

    out, stem = Path(task["out"]), task["stem"]
    if check:
        cavity_report.check_output(rep.structure, out, stem)
    written = rep.write(out, stem)
    marker = dict(
        _marker_key(task, sha),
        version=_MARKER_VERSION,
        files=[p.name for p in written],
        row={k: row[k] for k in ("atoms", "voids", "pockets", "largest_void_volume", "largest_pocket_volume")},
    )
    _write_atomic(_marker_path(out, stem), json.dumps(marker, indent=1, sort_keys=True) + "\n")


def _run_one(task: dict) -> dict:
    """Report on one structure (in a worker or in the calling process): read, check
    the output, compute, write the files, then the done marker."""
    from .. import cavity_report

    t0 = time.perf_counter()
    out, stem = Path(task["out"]), task["stem"]
    row = _empty_row(task["label"], stem)
    try:
        _marker_path(out, stem).unlink(missing_ok=True)  # no marker while the files change
        sha = _sha256(task["path"])
        s = read_structure_file(task["path"], **task["options"])
        cavity_report.check_output(s, out, stem)
        rep = cavity_report.report(s, task["probe"], name=stem, **task["report"])
        _ok(row, s, rep)
        _store(task, sha, row, rep, check=False)
    except Exception as e:  # any failure of one structure is recorded; the batch carries on
        _failed(row, e, task["path"])
    row["seconds"] = time.perf_counter() - t0
    return row


def _remote_one(task: dict, data: bytes) -> tuple:
    """A Dask worker's task: the report of one structure from its file's bytes.

    The worker needs neither the input file nor the output directory: it reads a
    private copy of the bytes (under the file's own name) and returns the row and the
    report (None if it failed), which the client writes (:func:`_store`).  Messages
    name the original path, as :func:`_run_one` does.
    """
    from .. import cavity_report

    t0 = time.perf_counter()
    stem = task["stem"]
    row = _empty_row(task["label"], stem)
    rep = None
    with tempfile.TemporaryDirectory(prefix="shapelab_batch_") as d:
        copy = Path(d, "in")
        copy.mkdir()
        copy = copy / Path(task["path"]).name
        copy.write_bytes(data)
        try:
            s = read_structure_file(copy, **task["options"])
            cavity_report.check_output(s, d, stem)  # what does not depend on the directory: the mmCIF labels
            rep = cavity_report.report(s, task["probe"], name=stem, **task["report"])
            _ok(row, s, rep)
        except Exception as e:  # recorded, as in _run_one
            rep = None
            _failed(row, e, copy, shown=task["path"])
    row["seconds"] = time.perf_counter() - t0
    return row, rep


def _complete(task: dict) -> dict | None:
    """The row of a structure whose outputs are complete and current, else None."""
    t0 = time.perf_counter()
    out, stem = Path(task["out"]), task["stem"]
    try:
        marker = json.loads(_marker_path(out, stem).read_text(encoding="utf-8"))
        if marker.get("version") != _MARKER_VERSION:
            return None
        if any(marker.get(k) != v for k, v in _marker_key(task, _sha256(task["path"])).items()):
            return None
        if not all((out / name).is_file() for name in marker["files"]):
            return None
        row = _empty_row(task["label"], stem)
        row.update(marker["row"], status="skipped")
    except (OSError, ValueError, KeyError, TypeError, AttributeError):
        return None
    row["seconds"] = time.perf_counter() - t0
    return row


def _init_worker() -> None:
    """A worker's initializer: import what every report needs, once per process, and
    one thread for the free space unless ``SHAPELAB_THREADS`` says otherwise (the
    workers already share out the CPUs: a pool in each would oversubscribe them)."""
    os.environ.setdefault("SHAPELAB_THREADS", "1")
    import shapelab.cavity_report  # noqa: F401
    import shapelab.io  # noqa: F401


# ============================================================================ progress
def _columns(stream) -> int:
    """The width of the terminal ``stream`` is, 0 if unknown: a terminal without a size
    (``script``, some CI runners) gets the lines, where tqdm would draw a bar of no width."""
    try:
        return os.get_terminal_size(stream.fileno()).columns
    except (AttributeError, OSError, ValueError):
        return 0


class _Progress:
    """tqdm on stderr when it is installed and stderr is a terminal, else one ``k/n``
    line per structure."""

    def __init__(self, total: int, enabled: bool):
        self.total, self.done, self.enabled, self.bar = total, 0, enabled, None
        if enabled:
            tqdm = None
            if getattr(sys.stderr, "isatty", lambda: False)() and _columns(sys.stderr) > 0:
                try:
                    from tqdm import tqdm
                except ImportError:
                    pass
            if tqdm is not None:
                self.bar = tqdm(total=total, unit="structure", file=sys.stderr, dynamic_ncols=True)

    def update(self, row: dict) -> None:
        self.done += 1
        if not self.enabled:
            return
        line = f"{self.done}/{self.total}  {row['path']}  {row['status']}"
        if row["status"] == "failed":
            line += f": {row['error']}"
        if self.bar is not None:
            if row["status"] == "failed":
                self.bar.write(line, file=sys.stderr)
            self.bar.update(1)
        else:
            print(line, file=sys.stderr, flush=True)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()


# ============================================================================ summary
def _cell(k: str, v) -> str:
    if v is None:
        return ""
    if k in ("largest_void_volume", "largest_pocket_volume"):
        return f"{v:.6f}"
    if k == "seconds":
        return f"{v:.3f}"
    return str(v)


@dataclass(frozen=True)
class BatchSummary:
    """The summary of a batch: one row per input, in input order (:func:`report_batch`).

    A read-only table that depends on nothing: ``len(summary)`` rows;
    ``summary[i]`` is row ``i`` as a dict, ``summary["status"]`` the column as a
    list; iterating gives the rows.  :meth:`to_pandas` makes a pandas DataFrame.

    Columns (:data:`SUMMARY_COLUMNS`): ``path`` (the file, as given or found),
    ``stem`` (its output files are ``<stem>_cavities.*``), ``status`` (``"ok"``,
    ``"failed"`` or ``"skipped"``), ``error`` (the message of a failure, else
    ``""``), ``atoms``, ``voids``, ``pockets``, ``largest_void_volume`` and
    ``largest_pocket_volume`` (in Å³, the solvent-accessible volume ``V SA`` of
    the report; None without such a feature) and ``seconds`` (the time spent on
    the input in this run).  The counts of a failed input are None; those of a
    skipped one come from its done marker.

    Attributes
    ----------
    rows : tuple of dict
    files : tuple of pathlib.Path
        The summary files written (CSV, then Parquet if pyarrow is installed).

    See Also
    --------
    report_batch
        Produces it.
    """

    rows: tuple
    files: tuple = ()

    def __len__(self) -> int:
        return len(self.rows)

    def __iter__(self):
        return iter(self.rows)

    def __getitem__(self, key):
        if isinstance(key, str):
            if key not in SUMMARY_COLUMNS:
                raise KeyError(f"no column {key!r}; the columns are {', '.join(SUMMARY_COLUMNS)}")
            return [r[key] for r in self.rows]
        return self.rows[key]

    @property
    def columns(self) -> tuple:
        """The column names, :data:`SUMMARY_COLUMNS`."""
        return SUMMARY_COLUMNS

    @property
    def failed(self) -> tuple:
        """The rows of status ``"failed"``."""
        return tuple(r for r in self.rows if r["status"] == "failed")

    def counts(self) -> dict:
        """How many inputs have each status: ``{"ok": n, "failed": n, "skipped": n}``."""
        return {s: sum(r["status"] == s for r in self.rows) for s in ("ok", "failed", "skipped")}

    def to_csv_text(self) -> str:
        """The table as CSV text (volumes to 6 decimals, seconds to 3; None as an empty cell)."""
        buf = _stdio.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(SUMMARY_COLUMNS)
        for r in self.rows:
            w.writerow([_cell(k, r[k]) for k in SUMMARY_COLUMNS])
        return buf.getvalue()

    def to_pandas(self):
        """The table as a :class:`pandas.DataFrame` (pandas must be installed; it is
        not a dependency of shapelab)."""
        try:
            import pandas as pd
        except ImportError as e:  # pragma: no cover - depends on the environment
            raise ImportError("BatchSummary.to_pandas needs pandas (pip install pandas)") from e
        return pd.DataFrame(list(self.rows), columns=list(SUMMARY_COLUMNS))


def _write_parquet(rows, path: Path) -> bool:
    try:
        import pyarrow as pa
        import pyarrow.parquet as pq
    except ImportError:
        return False
    schema = pa.schema(
        [
            ("path", pa.string()),
            ("stem", pa.string()),
            ("status", pa.string()),
            ("error", pa.string()),
            ("atoms", pa.int64()),
            ("voids", pa.int64()),
            ("pockets", pa.int64()),
            ("largest_void_volume", pa.float64()),
            ("largest_pocket_volume", pa.float64()),
            ("seconds", pa.float64()),
        ]
    )
    table = pa.Table.from_pylist([{k: r[k] for k in SUMMARY_COLUMNS} for r in rows], schema=schema)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    os.close(fd)
    try:
        pq.write_table(table, tmp)
        os.replace(tmp, path)
    finally:
        Path(tmp).unlink(missing_ok=True)
    return True


# ============================================================================ the batch
def _check_out(out) -> Path:
    out = Path(out)
    if not out.is_dir():
        raise FileNotFoundError(f"output directory {os.fspath(out)!r} does not exist")
    fd, tmp = tempfile.mkstemp(dir=out, prefix=".shapelab_batch.", suffix=".tmp")  # writable?
    os.close(fd)
    os.unlink(tmp)
    return out


def _pool_rows(tasks: list, jobs: int, on_row) -> dict:
    """Run ``tasks`` on ``jobs`` worker processes; {task index: row}.  A task whose
    worker died (the pool broke) is run again alone in a fresh pool; should that
    worker die too, its row says so."""
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor, as_completed
    from concurrent.futures.process import BrokenProcessPool

    ctx = multiprocessing.get_context("spawn")
    rows, broken = {}, []
    pool = ProcessPoolExecutor(max_workers=min(jobs, len(tasks)), mp_context=ctx, initializer=_init_worker)
    try:
        futures = {pool.submit(_run_one, t): i for i, t in enumerate(tasks)}
        for f in as_completed(futures):
            i = futures[f]
            try:
                rows[i] = f.result()
            except BrokenProcessPool:
                broken.append(i)
                continue
            on_row(rows[i])
    except BaseException:
        pool.shutdown(wait=False, cancel_futures=True)
        raise
    pool.shutdown(wait=True)
    for i in sorted(broken):
        with ProcessPoolExecutor(max_workers=1, mp_context=ctx, initializer=_init_worker) as alone:
            try:
                rows[i] = alone.submit(_run_one, tasks[i]).result()
            except BrokenProcessPool:
                rows[i] = _empty_row(tasks[i]["label"], tasks[i]["stem"])
                rows[i].update(error="the worker process died while reporting on this structure", seconds=0.0)
        on_row(rows[i])
    return rows


def _dask_rows(tasks: list, client, on_row) -> dict:
    """Run ``tasks`` on a Dask cluster; {task index: row}.  The client reads each input
    and sends its bytes; a worker computes the report and returns it; the client
    writes the files and the marker, as :func:`_run_one` does.  At most twice as
    many tasks as the cluster has threads are in flight (the inputs' bytes and the
    reports are held for those only)."""
    import uuid

    from .cluster import cancelled_error, cluster_threads, distributed_module, submit_with_bytes

    distributed = distributed_module("report_batch")
    cancelled = cancelled_error(distributed)
    rows, futures = {}, {}
    queue = iter(range(len(tasks)))

    def submit() -> bool:
        for i in queue:
            t, t0 = tasks[i], time.perf_counter()
            try:
                _marker_path(Path(t["out"]), t["stem"]).unlink(missing_ok=True)  # no marker while the files change
                data = Path(t["path"]).read_bytes()
            except OSError as e:  # as _run_one's _sha256 fails
                rows[i] = _empty_row(t["label"], t["stem"])
                _failed(rows[i], e, t["path"])
                rows[i]["seconds"] = time.perf_counter() - t0
                on_row(rows[i])
                continue
            key = f"shapelab-report-{t['stem']}-{uuid.uuid4().hex}"
            # The bytes travel inside the task, so that the scheduler can give it to another
            # worker if this one dies (a scattered copy would die with its worker).
            f = submit_with_bytes(client, _remote_one, t, data, key=key, pure=False)
            futures[f] = (i, hashlib.sha256(data).hexdigest())
            done.add(f)
            return True
        return False

    done = distributed.as_completed(loop=client.loop)
    for _ in range(2 * cluster_threads(client)):
        if not submit():
            break
    try:
        for f in done:
            i, sha = futures.pop(f)
            t = tasks[i]
            try:
                row, rep = f.result()
            except distributed.KilledWorker:  # the scheduler gave up after workers died on it
                row, rep = _empty_row(t["label"], t["stem"]), None
                row.update(error="the worker process died while reporting on this structure", seconds=0.0)
            except cancelled as e:  # the scheduler lost, or the task cancelled by someone else
                reason = getattr(e, "reason", None) or "cancelled"
                raise OSError(
                    f"the Dask cluster dropped the report on {t['label']} ({reason}); the structures finished "
                    "are complete: run the batch again with resume=True (--resume) to finish it"
                ) from None
            except Exception as e:  # raised on the worker outside the report (its temporary folder, ...)
                row, rep = _empty_row(t["label"], t["stem"]), None
                _failed(row, e, t["path"])
                row["seconds"] = 0.0
            if rep is not None:
                t0 = time.perf_counter()
                try:
                    _store(t, sha, row, rep)
                except Exception as e:  # the output directory, as in _run_one
                    _failed(row, e, t["path"])
                row["seconds"] += time.perf_counter() - t0
            rows[i] = row
            on_row(row)
            del rep
            while len(futures) < 2 * cluster_threads(client) and submit():
                pass
    except BaseException:
        try:
            client.cancel(list(futures))
        except Exception:  # the scheduler is gone: nothing left to cancel
            pass
        raise
    return rows


def report_batch(
    paths,
    *,
    probe=1.4,
    out=".",
    jobs=1,
    resume=False,
    progress=True,
    summary="shapelab_summary",
    chain=None,
    model=None,
    hetatm=True,
    water=False,
    hydrogens=False,
    default_radius=None,
    client=None,
    scheduler=None,
    rank="score",
    method="growth",
    min_persistence=None,
    min_volume=None,
    top=None,
) -> BatchSummary:
    """The cavity reports of many structures, written as for one, and one summary table.

    Finds the structure files of ``paths`` (:func:`expand_paths`: files, folders
    searched recursively, glob patterns), reads each as the command line reads one
    (:func:`shapelab.io.read_structure`: PDB or mmCIF, plain or gzip, decided by the
    content), computes ``shapelab.report(structure, probe, name=stem, rank=rank, ...)``
    (Notes §23.1; ranked by default, as one file's report) and writes its files into
    ``out`` exactly as ``python -m shapelab report FILE`` does
    (:meth:`shapelab.cavity_report.CavityReport.write`), then a done
    marker ``<stem>_cavities.done.json``.  A failing input is recorded and the batch
    carries on.  Finally it writes ``<summary>.csv`` (and ``<summary>.parquet`` when
    pyarrow is installed) into ``out`` and returns the summary.

    Parameters
    ----------
    paths : str, os.PathLike or iterable of them
        Files, folders and glob patterns.
    probe : float, default 1.4
        The probe radius (Å).
    out : str or os.PathLike, default "."
        An existing, writable directory for every structure's files and the summary.
    jobs : int, default 1
        Worker processes.  With 1 (or one structure to compute) everything runs in
        the calling process; otherwise a spawn-started
        :class:`~concurrent.futures.ProcessPoolExecutor` whose workers import
        shapelab once each.  The results do not depend on ``jobs``.
    resume : bool, default False
        Skip the inputs whose outputs are complete and current: their done marker
        names the same file with the same SHA-256 digest, probe and reading
        options, and every file it lists exists.  Anything else is computed again.
    progress : bool, default True
        Show progress on standard error: a tqdm bar if tqdm is installed and standard
        error is a terminal, else one ``k/n  PATH  status`` line per input (with the
        error of a failure).
    summary : str, default "shapelab_summary"
        File name (without extension) of the summary in ``out``.
    chain, model, hetatm, water, hydrogens, default_radius
        How each file is read, as in :func:`shapelab.io.read_pdb` (and its
        defaults).
    client : dask.distributed.Client, optional
        Run the structures on this Dask cluster instead of local processes (``jobs``
        must then be 1).  This process reads each input and sends its bytes to a
        worker; the worker computes the report and sends it back; this process
        writes the files and the done marker, in ``out``.  Workers need shapelab
        (and ``dask[distributed]``) installed, but neither the inputs nor ``out``.
        The files, the summary (but its ``seconds``), the markers, the progress and
        the failures are those of a local run.  The client is left open.
    scheduler : str, optional
        The address of a Dask scheduler (``"tcp://HOST:8786"``): connect to it, run as
        with ``client``, and disconnect at the end.  Dask is optional:
        ``pip install "shapelab[dask]"``.
    rank, method, min_persistence, min_volume, top
        Passed to :func:`shapelab.report` for every structure (default: ranked, best
        binding-site candidates first, cavities under 10 Å³ dropped; ``rank="none"``
        for every cavity in CASTp's order).  The summary counts the cavities listed.
        A done marker records them: ``resume`` recomputes a structure reported with
        other ranking options.

    Returns
    -------
    BatchSummary
        One row per input, in input order: ``path``, ``stem``, ``status`` (``ok``,
        ``failed``, ``skipped``), ``error``, ``atoms``, ``voids``, ``pockets``,
        ``largest_void_volume``, ``largest_pocket_volume`` (Å³, SA model),
        ``seconds``.  ``summary.to_pandas()`` gives a DataFrame where pandas is
        installed.

    Raises
    ------
    FileNotFoundError, PermissionError
        ``out`` is not an existing, writable directory (before any structure is read).
    ValueError, TypeError
        A bad ``probe``, ``jobs``, ``summary``, ``client`` or ``scheduler`` or entry of
        ``paths``; ``client`` and ``scheduler`` both, or either with ``jobs`` > 1.
    ImportError
        ``client`` or ``scheduler`` without dask.distributed installed, or a worker of
        the cluster without shapelab (or with another version of it), before anything
        is sent.
    OSError
        No scheduler answers at ``scheduler`` (Dask's connect timeout, 30 s by default,
        whatever answers there instead), or the cluster drops the batch's tasks (the
        scheduler lost mid-batch): the structures finished are complete, and
        ``resume=True`` finishes the batch.

    See Also
    --------
    shapelab.report
        The report of one structure.
    shapelab.cavity_report.CavityReport.write
        The files written per structure.
    expand_paths
        Which files a list of paths names.
    shapelab.tools.cli.main
        ``python -m shapelab report PATH PATH ...``: this function on the command line.

    Notes
    -----
    Two inputs with the same output stem (``a/x.pdb`` and ``b/x.pdb``) would write
    the same files: the first keeps the name and each later one fails, with an error
    naming the file that holds it.  Each structure's files are written atomically
    and its marker last, so a batch interrupted at any point leaves every structure
    either complete or without a marker; ``resume=True`` then finishes the batch.

    On a Dask cluster, a task whose worker dies is given to another worker by the
    scheduler, up to ``distributed.scheduler.allowed-failures`` times (3 by default);
    then its row says the worker died, as in a local run.  At most twice as many
    structures as the cluster has threads are in flight at once, so that the inputs
    and reports held in memory stay bounded whatever the size of the batch.  Dask's
    nanny starts workers with ``MALLOC_TRIM_THRESHOLD_=65536``, which about triples the
    CPU time of a report (glibc unmaps the many mid-sized arrays at once); set
    ``distributed.nanny.pre-spawn-environ.MALLOC_TRIM_THRESHOLD_`` to null in the
    workers' Dask configuration (README, "On a Dask cluster").

    References
    ----------
    .. [1] J. Liang, H. Edelsbrunner and C. Woodward, "Anatomy of protein pockets and
       cavities: measurement of binding site geometry and implications for ligand
       design", *Protein Science* 7 (1998) 1884–1897, doi:10.1002/pro.5560070905
    .. [2] M. Rocklin, "Dask: Parallel Computation with Blocked algorithms and Task
       Scheduling", *Proc. 14th Python in Science Conf.* (SciPy 2015), 126–132,
       doi:10.25080/Majora-7b98e3ed-013

    Examples
    --------
    >>> import tempfile
    >>> from shapelab.datasets import structure_path
    >>> data = structure_path("1hvr").parent
    >>> with tempfile.TemporaryDirectory() as d:
    ...     s = report_batch([data / "globule.pdb", data / "missing.pdb"], out=d, progress=False)
    ...     print(sorted(p.name for p in Path(d).iterdir() if p.suffix != ".parquet"))  # .parquet with pyarrow
    ['globule_cavities.cif', 'globule_cavities.csv', 'globule_cavities.done.json', 'globule_cavities.md', 'globule_cavities.pdb', 'shapelab_summary.csv']
    >>> s["status"], s.counts()["failed"], s[1]["error"]
    (['ok', 'failed'], 1, 'no such file or directory')
    """
    probe = as_finite_scalar(probe, "probe", nonnegative=True)
    jobs = as_positive_int(jobs, "jobs")
    if not isinstance(summary, str) or not summary or os.sep in summary or summary in (".", ".."):
        raise ValueError(f"summary must be a file name without directories or extension, got {summary!r}")
    for name, flag in (("resume", resume), ("progress", progress)):
        if not isinstance(flag, bool):
            raise TypeError(f"{name} must be True or False, got {flag!r}")
    options = dict(
        chain=chain, model=model, hetatm=hetatm, water=water, hydrogens=hydrogens, default_radius=default_radius
    )
    if rank not in ("score", "none"):
        raise ValueError(f"rank must be 'score' or 'none', got {rank!r}")
    if method not in ("growth", "flow"):
        raise ValueError(f"method must be 'growth' or 'flow', got {method!r}")
    ranking = dict(
        rank=rank,
        method=method,
        min_persistence=None
        if min_persistence is None
        else as_finite_scalar(min_persistence, "min_persistence", nonnegative=True),
        min_volume=None if min_volume is None else as_finite_scalar(min_volume, "min_volume", nonnegative=True),
        top=None if top is None else as_positive_int(top, "top"),
    )
    from .cluster import cluster_client

    with cluster_client(client, scheduler, jobs, "report_batch") as cluster:
        return _batch(paths, out, probe, jobs, resume, progress, summary, options, cluster, ranking)


def _batch(paths, out, probe, jobs, resume, progress, summary, options, cluster, ranking=None) -> BatchSummary:
    """The body of :func:`report_batch`, its arguments checked; ``cluster`` a Dask client or None."""
    inputs = expand_paths(paths)
    out = _check_out(out)

    rows: list = [None] * len(inputs)
    tasks, where, owner = [], [], {}
    for k, (label, path, err) in enumerate(inputs):
        stem = output_stem(path) if path is not None else None
        if err is None and stem in owner:
            err = f"its output name {stem}_cavities.* is already taken by {owner[stem]}"
        if err is not None:
            rows[k] = _empty_row(label, stem)
            rows[k].update(error=err, seconds=0.0)
            continue
        owner[stem] = label
        tasks.append(
            dict(
                label=label,
                path=os.fspath(path),
                stem=stem,
                out=os.fspath(out),
                probe=probe,
                options=options,
                report=dict(ranking or {}),
            )
        )
        where.append(k)

    bar = _Progress(len(inputs), progress)
    try:
        for r in rows:
            if r is not None:
                bar.update(r)
        todo = []
        for t, k in zip(tasks, where):
            done = _complete(t) if resume else None
            if done is not None:
                rows[k] = done
                bar.update(done)
            else:
                todo.append((t, k))
        if cluster is not None:
            got = _dask_rows([t for t, _ in todo], cluster, bar.update) if todo else {}
            for i, (_, k) in enumerate(todo):
                rows[k] = got[i]
        elif jobs == 1 or len(todo) <= 1:
            for t, k in todo:
                rows[k] = _run_one(t)
                bar.update(rows[k])
        else:
            got = _pool_rows([t for t, _ in todo], jobs, bar.update)
            for i, (_, k) in enumerate(todo):
                rows[k] = got[i]
    finally:
        bar.close()

    table = BatchSummary(rows=tuple(rows))
    csv_path = out / f"{summary}.csv"
    _write_atomic(csv_path, table.to_csv_text())
    files = [csv_path]
    pq_path = out / f"{summary}.parquet"
    if _write_parquet(rows, pq_path):
        files.append(pq_path)
    return BatchSummary(rows=table.rows, files=tuple(files))
