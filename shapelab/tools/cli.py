"""The command line: ``python -m shapelab report FILE [--probe 1.4] [--out DIR] [options]``.

One program, ``python -m shapelab`` (or the ``shapelab`` script), with one subcommand
per task:

``report``
    The CASTp-style report of the voids and pockets of a structure
    (:func:`shapelab.report`, Notes §23.1): reads ``FILE``, PDB, mmCIF or BinaryCIF, with
    :func:`shapelab.read_structure` and its defaults (HETATM records kept, water and
    hydrogens dropped; each flag changes one of them), so that it prints exactly the
    table of ``report(read_structure(FILE), 1.4)`` (ranked by default: best binding-site
    candidates first, cavities under 10 Å³ dropped and counted; ``--rank none`` for
    CASTp's unfiltered table), and writes ``<stem>_cavities.csv``,
    ``.md``, ``.cif`` and, when the PDB format can hold the marked structure,
    ``.pdb`` to ``DIR`` (:meth:`shapelab.cavity_report.CavityReport.write`).  An
    unreadable, malformed or empty file, or an output directory that cannot be
    written, exits with status 2 and one line on stderr before any cavity is
    computed, and writes nothing.

``report PATH PATH ...``
    Many structures at once (:func:`shapelab.tools.batch.report_batch`): with more than
    one ``PATH``, a folder (searched recursively for ``*.pdb``, ``*.ent``,
    ``*.cif``, ``*.mmcif``, ``*.bcif`` and their ``.gz``), a glob pattern, or
    ``--resume``, each
    structure's files are written as above, in ``--jobs N`` worker processes, with
    progress on stderr, and a summary table ``shapelab_summary.csv`` (and
    ``.parquet`` when pyarrow is installed) in ``DIR``.  Nothing goes to stdout.  A
    file that fails is named with its error on stderr and in the summary, and the
    batch carries on; the exit status is then 1.  Status 2 stays for a bad option or
    an output directory that cannot be written.  ``--scheduler tcp://HOST:PORT`` runs
    the same batch on a Dask cluster (``pip install "shapelab[dask]"``), with the same
    files, summary, progress and exit status; ``--figure PATH`` also draws the summary
    (:func:`shapelab.plot.batch_summary`).

The library modules read no arguments and change no global state when imported; only
this module is a program.
"""

from __future__ import annotations

import argparse
import glob
import sys
from pathlib import Path

from .. import cavity_report

__all__ = ["main", "parser"]


def parser() -> argparse.ArgumentParser:
    """The argument parser of ``python -m shapelab`` and its subcommands.

    See Also
    --------
    main
        Parses and runs.
    """
    top = argparse.ArgumentParser(
        prog="python -m shapelab",
        description="shapelab on the command line: biogeometric shape analysis (Lecture 23).",
    )
    sub = top.add_subparsers(dest="command", metavar="COMMAND", required=True)
    ap = sub.add_parser(
        "report",
        description="CASTp-style report of the voids and pockets of a PDB, mmCIF or BinaryCIF file (Notes §23.1). "
        "The file is read as shapelab.read_structure reads it by default: HETATM records (ligands, ions) "
        "kept, water and hydrogens dropped.",
    )
    ap.add_argument(
        "file",
        nargs="+",
        metavar="FILE",
        help="PDB, mmCIF or BinaryCIF file (plain or gzip); several files, folders (searched for *.pdb, *.ent, *.cif, "
        "*.bcif and their .gz) or glob patterns report on many structures at once",
    )
    ap.add_argument("--probe", type=float, default=1.4, help="probe radius in Å (default 1.4)")
    ap.add_argument("--out", default=".", help="output directory, which must exist (default: current directory)")
    ap.add_argument("--chain", action="append", metavar="ID", help="keep only this chain (repeatable)")
    ap.add_argument(
        "--model",
        type=int,
        metavar="N",
        help="read model N (PDB MODEL serial or mmCIF pdbx_PDB_model_num; default: the first)",
    )
    het = ap.add_mutually_exclusive_group()
    het.add_argument("--no-hetatm", action="store_true", help="drop every HETATM record")
    het.add_argument(
        "--hetatm",
        action="append",
        nargs="?",
        const=True,
        metavar="NAME",
        help="keep only the HETATM residues named NAME (repeatable); without NAME, all (the default)",
    )
    ap.add_argument("--water", action="store_true", help="keep water molecules")
    ap.add_argument("--hydrogens", action="store_true", help="keep hydrogen atoms")
    ap.add_argument(
        "--default-radius",
        type=float,
        metavar="R",
        help="van der Waals radius (Å) of the elements no table lists (Pm, past Es, unknown symbols such as X); "
        "the others take Bondi's (1964), Mantina et al.'s (2009) or, for the transition metals, lanthanides "
        "and actinides those two lack, Alvarez's (2013) radius, which the report's notes name",
    )
    rank = ap.add_argument_group(
        "which pockets, in which order (shapelab.report)",
        "By default the best binding-site candidates come first and cavities under 10 Å³ are dropped: "
        "the default maximises top-(N+2) DCA recall (a cavity's lining centroid within 4 Å of a ligand "
        "among the first N+2, N = ligand sites) with a median of fewer than 20 listed per structure, and "
        "was chosen on the development split of the pocket benchmark only (75.4 %, median 14 listed; "
        "python -m benchmarks.pocket_ranking).  On the held-out test split: 68.6 % top-(N+2), median 16 "
        "listed (python -m benchmarks.pocket_sites).  --rank none lists every cavity, unfiltered.",
    )
    rank.add_argument(
        "--rank",
        choices=("score", "none"),
        default="score",
        help="score (the default): best binding-site candidates first (shapelab.ranking.rank_score, "
        "buriedness^2 * ln(1 + SA volume)), cavities under 10 Å³ dropped, the number dropped stated; "
        "none: every void and pocket, voids first, by volume (CASTp's table)",
    )
    rank.add_argument(
        "--method",
        choices=("growth", "flow"),
        default="growth",
        help="pocket definition: the notes' growth model (default) or CASTp's discrete flow",
    )
    rank.add_argument(
        "--min-persistence",
        type=float,
        metavar="P",
        help="keep features with death - birth >= P (τ, Å²); default 0 (the ranking's default too)",
    )
    rank.add_argument(
        "--min-volume",
        type=float,
        metavar="V",
        help="keep features with SA volume >= V (Å³); default 10 (the ranking's), 0 with --rank none",
    )
    rank.add_argument("--top", type=int, metavar="K", help="keep the first K features only")
    many = ap.add_argument_group("many structures (shapelab.batch.report_batch)")
    many.add_argument(
        "-j",
        "--jobs",
        type=int,
        default=1,
        metavar="N",
        help="worker processes (default 1); results do not depend on N",
    )
    many.add_argument(
        "--resume",
        action="store_true",
        help="skip structures whose files are complete and current (done marker with the input's SHA-256, "
        "probe and options); also for one file",
    )
    many.add_argument("--no-progress", action="store_true", help="no progress on stderr")
    many.add_argument(
        "--summary",
        default="shapelab_summary",
        metavar="NAME",
        help="summary file name in DIR, without extension (default shapelab_summary): NAME.csv, and "
        "NAME.parquet when pyarrow is installed",
    )
    many.add_argument(
        "--scheduler",
        metavar="ADDRESS",
        help="run the structures on the Dask cluster whose scheduler is at ADDRESS (tcp://HOST:PORT) instead of "
        "local processes; the same files, summary and exit status (pip install shapelab[dask])",
    )
    many.add_argument(
        "--figure",
        metavar="PATH",
        help="also draw the summary (largest pocket and void per structure, failed files named) to PATH "
        "(.png, .svg or .pdf; shapelab.plot.batch_summary)",
    )
    return top


def main(argv=None) -> int:
    """``python -m shapelab report FILE [--probe 1.4] [--out DIR] [options]``.

    Runs the subcommand named first in ``argv`` (default: ``sys.argv[1:]``) and returns
    the exit status.  ``report`` reads ``FILE`` with :func:`shapelab.read_structure` and its
    defaults, changed only by the flags ``--chain``, ``--model``,
    ``--no-hetatm``/``--hetatm NAME``, ``--water``, ``--hydrogens`` and
    ``--default-radius``; checks the output directory
    (:func:`shapelab.cavity_report.check_output`); then computes
    ``report(structure, probe)`` (with ``--rank none``, ``--method flow``,
    ``--min-persistence P``, ``--min-volume V`` or ``--top K``: those arguments of
    :func:`shapelab.report`), writes its files (the PDB file when the format can
    hold it) and prints the Markdown table.  By default the cavities are ranked
    (``rank="score"``: best binding-site candidates first, those under 10 Å³
    dropped and counted in a line above the table): the default maximises top-(N + 2)
    DCA recall with a median of fewer than 20 cavities listed, was chosen on the
    development split of the pocket benchmark only, and finds 68.6 % of the test
    split's sites among the top N + 2 with a median of 16 listed
    (``python -m benchmarks.pocket_sites``; :func:`shapelab.report`, Notes).
    ``--rank none`` prints the unfiltered table in CASTp's order.  Exit status 2
    with a one-line message on
    stderr, and no files, for an unreadable, malformed or empty file, an output
    directory that cannot be written, or a bad option -- all found before any cavity
    is computed.  If no PDB file is written, one line on stderr says why.

    With several paths, a folder, a glob pattern, ``--resume``, ``--scheduler`` or
    ``--figure``, ``report`` runs :func:`shapelab.tools.batch.report_batch` (``--jobs``,
    ``--resume``, ``--no-progress``, ``--summary``, ``--scheduler`` for a Dask
    cluster; the ranking options pass through to each structure's report) and,
    with ``--figure PATH``, draws its summary
    (:func:`shapelab.plot.batch_summary`): nothing on stdout, progress and each
    failure on stderr, exit status 1 if any input failed, 2 for a bad option or an
    output directory that cannot be written, 130 when interrupted (Ctrl-C; the
    structures finished are complete, and ``--resume`` finishes the batch).

    See Also
    --------
    shapelab.report
        The function behind ``report``.
    shapelab.tools.batch.report_batch
        The function behind ``report`` on many structures.
    parser
        The options.
    """
    args = parser().parse_args(argv)
    if _is_batch(args):
        return _run_batch(args)
    args.file = args.file[0]
    return _run_report(args)


def _is_batch(args) -> bool:
    """More than one FILE, a folder, a glob pattern that is not a file's name, --resume,
    --scheduler or --figure."""
    if len(args.file) > 1 or args.resume or args.scheduler is not None or args.figure is not None:
        return True
    p = Path(args.file[0])
    return p.is_dir() or (not p.exists() and glob.has_magic(args.file[0]))


def _run_batch(args) -> int:
    from .batch import report_batch

    names = [h for h in (args.hetatm or []) if h is not True]
    if args.jobs != 1 and args.scheduler is not None:
        print(
            "error: --jobs is for local worker processes; with --scheduler the cluster's workers run the structures",
            file=sys.stderr,
        )
        return 2
    if args.figure is not None:
        problem = _figure_problem(args.figure)
        if problem:
            print(f"error: --figure {args.figure}: {problem}", file=sys.stderr)
            return 2
    try:
        summary = report_batch(
            args.file,
            probe=args.probe,
            out=args.out,
            jobs=args.jobs,
            resume=args.resume,
            progress=not args.no_progress,
            summary=args.summary,
            chain=args.chain,
            model=args.model,
            hetatm=False if args.no_hetatm else (set(names) if names else True),
            water=args.water,
            hydrogens=args.hydrogens,
            default_radius=args.default_radius,
            scheduler=args.scheduler,
            rank=args.rank,
            method=args.method,
            min_persistence=args.min_persistence,
            min_volume=args.min_volume,
            top=args.top,
        )
    except (ValueError, TypeError, OSError, ImportError) as e:
        print(f"error: {str(e).splitlines()[0] if str(e) else type(e).__name__}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:  # Ctrl-C: the finished structures are complete, the others have no marker
        print("interrupted: the structures finished are kept; run again with --resume to finish", file=sys.stderr)
        return 130
    files = [str(p) for p in summary.files]
    if args.figure is not None:
        from ..plot import batch_summary

        try:
            batch_summary(summary).savefig(args.figure)
            files.append(args.figure)
        except OSError as e:  # the batch's files are written; only the figure is missing
            print(f"error: --figure {args.figure}: {e}", file=sys.stderr)
            return 2
    for row in summary.failed:
        hint = " (on the command line: --default-radius R)" if "default_radius=" in row["error"] else ""
        print(f"error: {row['path']}: {row['error']}{hint}", file=sys.stderr)
    n = summary.counts()
    print(
        f"{len(summary)} structures: {n['ok']} ok, {n['skipped']} skipped, {n['failed']} failed; "
        f"summary: {', '.join(files)}",
        file=sys.stderr,
    )
    return 1 if n["failed"] else 0


def _figure_problem(path) -> str | None:
    """Why the summary figure cannot be written to ``path`` (checked before the batch runs), or None."""
    from matplotlib.figure import Figure

    kinds = Figure().canvas.get_supported_filetypes()
    suffix = Path(path).suffix.lower().lstrip(".")
    if suffix not in kinds:
        return f"the name must end in one of .png, .svg, .pdf (or {', '.join('.' + k for k in sorted(kinds))})"
    parent = Path(path).parent
    if not parent.is_dir():
        return f"folder {str(parent)!r} does not exist"
    return None


def _run_report(args) -> int:
    from ..io import read_structure

    def fail(e) -> int:
        msg = str(e).splitlines()[0] if str(e) else type(e).__name__
        if "default_radius=" in msg:
            msg += " (on the command line: --default-radius R)"
        print(f"error: {msg}", file=sys.stderr)
        return 2

    names = [h for h in (args.hetatm or []) if h is not True]
    hetatm = False if args.no_hetatm else (set(names) if names else True)
    from .batch import output_stem

    stem = output_stem(args.file)  # the batch's names: "..pdb" gives "structure", 1abc.bcif.gz "1abc"
    try:
        s = read_structure(
            args.file,
            chain=args.chain,
            model=args.model,
            hetatm=hetatm,
            water=args.water,
            hydrogens=args.hydrogens,
            default_radius=args.default_radius,
        )
        cavity_report.check_output(s, args.out, stem)  # before the expensive part
    except (ValueError, TypeError, OSError) as e:
        return fail(e)
    try:
        rep = cavity_report.report(
            s,
            args.probe,
            name=stem,
            rank=args.rank,
            method=args.method,
            min_persistence=args.min_persistence,
            min_volume=args.min_volume,
            top=args.top,
        )
        paths = rep.write(args.out, stem)
    except (ValueError, TypeError, OSError) as e:
        return fail(e)
    sys.stdout.write(rep.to_markdown())
    if not any(p.suffix == ".pdb" for p in paths):
        print(
            f"note: no {stem}_cavities.pdb ({rep.pdb_problem()}); the marked structure is in {paths[2].name}",
            file=sys.stderr,
        )
    return 0


if __name__ == "__main__":  # python -m shapelab.cli ..., the same as python -m shapelab ...
    sys.exit(main())
