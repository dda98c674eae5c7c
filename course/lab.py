"""Start JupyterLab on 127.0.0.1 with a fresh random token, and print the URL.

    python -m course lab               # the student edition, in student/ (made on first use)
    python -m course lab --instructor  # the lessons with their solutions, in lessons/

A student opens the **student edition**: the lessons without solutions, their
self-checks kept (:mod:`course.student`).  It is the student's working copy, in
``student/`` at the repository's root, and it is never overwritten: a lesson missing
from it is written on first use, and a lesson changed since the copy was made (after a
``git pull``) is named, with the command that replaces it.  JupyterLab serves
``student/`` only.  ``--instructor`` serves the repository and opens ``lessons/``,
where the solutions are.

The token is never empty; ``--allow-root`` is added only when running as root.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import secrets
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
LESSONS = ROOT / "lessons"
STUDENT = ROOT / "student"


def build_command(token: str, port: str, as_root: bool, root_dir: Path = ROOT, open_path: str = "") -> list[str]:
    """The JupyterLab command line: loopback only, a non-empty token, root only if needed."""
    if not token:
        raise ValueError("token must not be empty: JupyterLab would accept anyone")
    cmd = [
        sys.executable,
        "-m",
        "jupyterlab",
        "--ServerApp.ip=127.0.0.1",
        f"--ServerApp.port={port}",
        f"--IdentityProvider.token={token}",
        "--ServerApp.open_browser=False",
        f"--ServerApp.root_dir={root_dir}",
        f"--LabApp.default_url=/lab/tree/{open_path}",
    ]
    if as_root:
        cmd.append("--allow-root")
    return cmd


def lessons() -> list[Path]:
    return sorted(p for p in LESSONS.glob("[0-9][0-9]_*.ipynb") if not p.name.endswith(".failed.ipynb"))


def lesson_digest(nb) -> str:
    """SHA-256 of a lesson's cells (type and source; not outputs or metadata): what the
    student edition is made from, so re-executing a lesson does not change it."""
    h = hashlib.sha256()
    for cell in nb["cells"]:
        source = cell["source"]
        h.update(json.dumps([cell["cell_type"], "".join(source) if isinstance(source, list) else source]).encode())
    return h.hexdigest()


def _recorded_digest(target: Path) -> str | None:
    """The lesson digest a student copy was made from (its metadata), or None."""
    try:
        meta = json.loads(target.read_text(encoding="utf-8")).get("metadata", {})
        return meta.get("shapelab", {}).get("lesson_sha256")
    except (OSError, ValueError, AttributeError):
        return None


def student_copy(dest: Path | None = None, sources: list[Path] | None = None) -> tuple[list[str], list[str]]:
    """Write the student edition of every lesson missing from ``dest``; never touch one
    that is there.  Returns (written, stale): the names written now, and the names whose
    lesson changed since the student's copy was made.

    A copy records the digest of its lesson's cells (``metadata.shapelab.lesson_sha256``,
    which JupyterLab keeps when the student saves), so a lesson changed by a ``git pull``
    is named even after the student has saved the copy again; a copy without it (made
    by an earlier version) is stale when the lesson is newer than the copy."""
    import nbformat

    from course.student import README, student_notebook

    dest = STUDENT if dest is None else dest
    dest.mkdir(parents=True, exist_ok=True)
    written, stale = [], []
    for path in lessons() if sources is None else sources:
        target = dest / path.name
        lesson = nbformat.read(path, as_version=4)
        digest = lesson_digest(lesson)
        if target.exists():
            recorded = _recorded_digest(target)
            if recorded is not None:
                changed = recorded != digest
            else:
                changed = path.stat().st_mtime > target.stat().st_mtime + 1
            if changed:
                stale.append(path.name)
            continue
        nb, _ = student_notebook(lesson)
        nb.metadata["shapelab"] = {"lesson": path.name, "lesson_sha256": digest}
        tmp = target.with_suffix(".tmp")
        nbformat.write(nb, tmp)
        os.replace(tmp, target)  # nothing half-written
        written.append(path.name)
    readme = dest / "README.md"
    if not readme.exists():
        readme.write_text(README, encoding="utf-8")
    return written, stale


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(prog="python -m course lab", description=__doc__.split("\n\n")[0])
    ap.add_argument(
        "--instructor", action="store_true", help="open the lessons with their solutions (lessons/), not student/"
    )
    ap.add_argument("--port", default=os.environ.get("PORT", "8888"))
    ap.add_argument("--dry-run", action="store_true", help="prepare and print the command, do not start JupyterLab")
    ap.add_argument(
        "--check",
        action="store_true",
        help="start JupyterLab, check that it serves the first lesson with the token and refuses without it, stop",
    )
    args = ap.parse_args(argv)
    if args.instructor:
        root, first = ROOT, "lessons/00_start_here.ipynb"
        print("JupyterLab for the shapelab course: the INSTRUCTOR's lessons, with their solutions (lessons/).")
    else:
        written, stale = student_copy()
        root, first = STUDENT, "00_start_here.ipynb"
        print("JupyterLab for the shapelab course: the student edition (student/, no solutions).")
        if written:
            print(f"  wrote {len(written)} lesson(s) into student/ (your working copy: edit freely)")
        for name in stale:
            print(
                f"  note: lessons/{name} changed after your copy was made; your copy is kept. To start "
                f"it afresh, move student/{name} aside and run this command again."
            )
    token = secrets.token_hex(24)
    cmd = build_command(
        token, args.port, as_root=hasattr(os, "geteuid") and os.geteuid() == 0, root_dir=root, open_path=first
    )
    print("On this machine only (127.0.0.1).")
    print(f"Open: http://127.0.0.1:{args.port}/lab/tree/{first}?token={token}")
    print("(If the port is taken, JupyterLab picks the next one and prints its own URL below.)")
    sys.stdout.flush()
    if args.dry_run:
        return 0
    env = dict(os.environ, PYTHONPATH=str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    if args.check:
        # on this port or not at all: on another one the check would ask whatever listens here
        return check_server([*cmd, "--ServerApp.port_retries=0"], root, env, args.port, token, first)
    return subprocess.call(cmd, cwd=root, env=env)


def check_server(cmd, root: Path, env: dict, port: str, token: str, first: str, wait: float = 120.0) -> int:
    """Start JupyterLab, ask it for the first lesson with the token and without it, stop it.

    Returns 0 when the lesson is served with the token and refused (403) without it."""
    import time
    import urllib.error
    import urllib.request

    proc = subprocess.Popen(cmd, cwd=root, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    url = f"http://127.0.0.1:{port}/api/contents/{first}"

    def status(with_token: bool) -> int:
        req = urllib.request.Request(url, headers={"Authorization": f"token {token}"} if with_token else {})
        try:
            with urllib.request.urlopen(req, timeout=5) as r:
                return r.status
        except urllib.error.HTTPError as e:
            return e.code

    try:
        deadline = time.monotonic() + wait
        while True:
            try:
                ok = status(True)
                break
            except OSError:
                if proc.poll() is not None or time.monotonic() > deadline:
                    print(f"check: JupyterLab did not answer on {url}", file=sys.stderr)
                    return 1
                time.sleep(0.5)
        refused = status(False)
        print(f"check: {first} with the token: HTTP {ok}; without it: HTTP {refused}")
        return 0 if ok == 200 and refused == 403 else 1
    finally:
        proc.terminate()
        try:
            proc.wait(timeout=20)
        except subprocess.TimeoutExpired:
            proc.kill()


if __name__ == "__main__":
    sys.exit(main())
