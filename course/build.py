"""Build the course: execute the lessons, then the book, slides, figures and student edition.

    python -m course.build                 # everything (make course)
    python -m course.build --only book     # one artefact: book | slides | figures | student
    python -m course.build --no-execute    # render the committed outputs as they are
    python -m course.build --instructor    # also the instructors' site (solutions shown)

The site (book/_build/html) is the students': no solution is on it (course.student.
site_notebook).  ``--instructor`` builds a second site with the solutions in
book/_build/html-instructor.  The decks are printed to PDF when Chromium is installed.

Progress is printed as it goes, and a summary at the end says what was built,
how long it took, how large it is and where it went.
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BOOK = ROOT / "book"
BUILD = BOOK / "_build"
VENDOR = BOOK / "_extra" / "vendor"
GALLERY = BOOK / "_gallery"  # the gallery page's figures (book/gallery.md), made before the book
SITE_SRC = BUILD / "site-src"  # the sites' sources: book/ with the site's lessons (site_source)
INSTRUCTOR_HTML = BUILD / "html-instructor"
NODE = BOOK / "node_modules"

# what the offline site needs from the npm packages, and where it goes under the site's
# root (the slides copy their own set, course/slides.py)
ASSETS = {
    "requirejs/require.js": "require.min.js",
    "@jupyter-widgets/html-manager/dist": "html-manager",
    "mathjax/es5": "mathjax",
    # shapelab.plot.view3d's pages load it from here (lazily: only pages with a view)
    "3dmol/build/3Dmol-min.js": "3dmol/3Dmol-min.js",
    "3dmol/build/3Dmol-min.js.LICENSE.txt": "3dmol/3Dmol-min.js.LICENSE.txt",
    "3dmol/LICENSE": "3dmol/LICENSE",
}


def size(path: Path) -> str:
    if not path.exists():
        return "missing"
    total = path.stat().st_size if path.is_file() else sum(p.stat().st_size for p in path.rglob("*") if p.is_file())
    return f"{total / 2**20:.1f} MiB"


def step(title: str):
    print(f"\n== {title}", flush=True)
    return time.perf_counter()


def vendor_assets(assets: dict[str, str] = ASSETS, dest: Path = VENDOR) -> Path:
    """Copy JavaScript from book/node_modules (installed by `npm ci`) to ``dest``."""
    missing = [src for src in assets if not (NODE / src).exists()]
    if missing:
        raise SystemExit(
            f"book/node_modules lacks {', '.join(missing)}: run `cd book && npm ci` (make does this for you)"
        )
    if dest == VENDOR and VENDOR.exists():
        shutil.rmtree(VENDOR)
    for src, dst in assets.items():
        target = dest / dst
        if target.exists():
            shutil.rmtree(target) if target.is_dir() else target.unlink()
        target.parent.mkdir(parents=True, exist_ok=True)
        if (NODE / src).is_dir():
            ignore = shutil.ignore_patterns("*.map", "sre", "*.md", "*.d.ts")
            shutil.copytree(NODE / src, target, ignore=ignore)
        else:
            shutil.copy2(NODE / src, target)
    return dest


def lessons_into_book(execute: bool, book: Path = BOOK) -> None:
    out = book / "lessons"
    out.mkdir(parents=True, exist_ok=True)
    for old in out.glob("*.ipynb"):
        old.unlink()
    if execute:
        rc = subprocess.call([sys.executable, "-m", "course.execute", "--out", str(out)], cwd=ROOT)
        if rc:
            raise SystemExit("some lessons failed to execute; see above")
    else:
        import nbformat

        for path in sorted((ROOT / "lessons").glob("[0-9][0-9]_*.ipynb")):
            nb = nbformat.read(path, as_version=4)
            # the site has no widget manager (book/_config.yml): the stored widget state
            # would only weigh the page down
            nb.metadata.pop("widgets", None)
            nbformat.write(nb, out / path.name)
            print(f"  copied {path.name} (committed outputs)")


def strip_inline_libraries(lessons: Path) -> int:
    """Drop the inline copies of 3Dmol.js from the lessons' outputs in ``lessons``.

    In JupyterLab the first ``shapelab.plot.view3d`` of a notebook carries the library
    inline (a kernel cannot serve a file to the page); the site serves it once from
    ``vendor/3dmol/`` (ASSETS) and each view loads it from there.  Returns how many
    notebooks changed."""
    import nbformat

    from shapelab.plot.viewer3d import without_library

    changed = 0
    for path in sorted(lessons.glob("*.ipynb")):
        if "data-shapelab-library" not in path.read_text(encoding="utf-8"):
            continue
        nb = nbformat.read(path, as_version=4)
        for cell in nb.cells:
            for out in cell.get("outputs", []):
                html = out.get("data", {}).get("text/html")
                if html is not None:
                    text = html if isinstance(html, str) else "".join(html)
                    out["data"]["text/html"] = without_library(text)
        nbformat.write(nb, path)
        changed += 1
    return changed


def build_gallery(out: Path = GALLERY) -> bool:
    """Draw the figures that book/gallery.md shows, as SVG (python -m course.figures).

    A figure that fails gets a labelled placeholder so that the site still builds;
    the failure is printed, and ``make figures`` / the figures step fail on it.
    """
    env = dict(os.environ, PYTHONPATH=str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    cmd = [sys.executable, "-m", "course.figures", "--out", str(out), "--format", "svg", "--gallery"]
    rc = subprocess.call(cmd, cwd=ROOT, env=env)
    if rc:
        print("  warning: some gallery figures failed (placeholders shown); see above", flush=True)
    return rc == 0


def book_copy(dest: Path) -> Path:
    """A copy of the book's sources (no build output, lessons or JavaScript) in ``dest``,
    for building somewhere else than the working tree (the tests do)."""
    skip = shutil.ignore_patterns("node_modules", "_build", "_extra", "_gallery", "lessons")
    shutil.copytree(BOOK, dest, ignore=skip, dirs_exist_ok=True)
    return dest


def site_lessons(lessons: Path, instructor: bool = False) -> dict:
    """Make the executed lessons in ``lessons`` (a copy: they are changed in place) the
    site's pages: citations become links to the references page (course/citations.py)
    and, unless ``instructor``, the solutions are left out (course.student.site_notebook:
    the exercise's code cell shows the placeholder, every other output is kept).  A
    "show solution" toggle would still publish the answer in the page's HTML; the
    instructors' site (``--instructor``) is a second build.  Returns counts."""
    import nbformat

    from course import citations
    from course.student import site_notebook

    totals = {"lessons": 0, "solutions left out": 0, "citations linked": 0}
    for path in sorted(lessons.glob("[0-9][0-9]_*.ipynb")):
        nb = nbformat.read(path, as_version=4)
        keys = [k for c in nb.cells if c.cell_type == "markdown" for k in citations.cited(c.source)]
        missing = citations.unknown(keys)
        if missing:  # the link would lead nowhere on the site
            raise SystemExit(f"{path.name} cites {', '.join(missing)}, not in {citations.BIB.relative_to(ROOT)}")
        for cell in nb.cells:
            if cell.cell_type == "markdown":
                totals["citations linked"] += len(citations.CITE.findall(cell.source))
                cell.source = citations.for_site(cell.source)
                # a lesson links the book's pages as ../book/page.md (right in JupyterLab);
                # on the site the lessons sit in book/lessons/
                cell.source = cell.source.replace("](../book/", "](../")
        if not instructor:
            nb, stats = site_notebook(nb)
            totals["solutions left out"] += stats["exercises"] + stats["markdown removed"]
        nbformat.write(nb, path)
        totals["lessons"] += 1
    return totals


def site_source(dest: Path, instructor: bool = False) -> Path:
    """The book's sources in ``dest`` with the site's lessons (see :func:`site_lessons`),
    made from the executed lessons in book/lessons and the gallery's figures."""
    if dest.exists():
        shutil.rmtree(dest)
    book_copy(dest)
    if GALLERY.exists():
        shutil.copytree(GALLERY, dest / "_gallery")
    (dest / "lessons").mkdir(exist_ok=True)
    for path in sorted((BOOK / "lessons").glob("[0-9][0-9]_*.ipynb")):
        shutil.copy2(path, dest / "lessons" / path.name)
    totals = site_lessons(dest / "lessons", instructor)
    who = "instructors (solutions shown)" if instructor else "students (solutions left out)"
    print(
        f"  site for {who}: {totals['lessons']} lessons, {totals['solutions left out']} solutions left out, "
        f"{totals['citations linked']} citations linked",
        flush=True,
    )
    return dest


def build_book(path_output: Path | None = None, gallery: bool = True, book: Path = BOOK) -> Path:
    """Build the site from the book sources in ``book`` (default ``book/``) into
    ``path_output/_build/html`` (default: inside ``book``); the offline JavaScript and
    the gallery's figures go into ``book`` too."""
    vendor_assets(dest=VENDOR if book == BOOK else book / "_extra" / "vendor")
    stripped = strip_inline_libraries(book / "lessons")
    if stripped:
        print(f"  3Dmol.js: inline copies dropped from {stripped} lesson(s); the site serves vendor/3dmol/", flush=True)
    if gallery:
        build_gallery(GALLERY if book == BOOK else book / "_gallery")
    cmd = [str(Path(sys.executable).parent / "jupyter-book"), "build", str(book), "--keep-going"]
    if path_output is not None:
        cmd += ["--path-output", str(path_output)]
    env = dict(os.environ, PYTHONPATH=str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    # Sphinx's routine output goes to a log file; the progress line says where, and how
    # many warnings it holds
    log = (path_output or book) / "_build" / "logs" / "book.log"
    log.parent.mkdir(parents=True, exist_ok=True)
    with open(log, "w", encoding="utf-8") as fh:
        rc = subprocess.call(cmd, cwd=ROOT, env=env, stdout=fh, stderr=subprocess.STDOUT)
    text = log.read_text(encoding="utf-8", errors="replace")
    warnings = sum("WARNING" in line for line in text.splitlines())
    html = (path_output or book) / "_build" / "html"
    if rc or not (html / "index.html").exists():
        print("\n".join(text.splitlines()[-40:]), flush=True)
        raise SystemExit(f"the book failed to build; the whole log: {log}")
    print(f"  built {html}: {warnings} warning{'s' if warnings != 1 else ''} (log: {log})", flush=True)
    return html


def run_optional(title: str, argv: list[str]) -> bool:
    """Run an artefact's builder (slides, figures, student edition)."""
    env = dict(os.environ, PYTHONPATH=str(ROOT) + os.pathsep + os.environ.get("PYTHONPATH", ""))
    rc = subprocess.call([sys.executable, *argv], cwd=ROOT, env=env)
    if rc:
        raise SystemExit(f"{title} failed; see above")
    return True


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--only", choices=["book", "slides", "figures", "student"], action="append")
    ap.add_argument("--no-execute", action="store_true", help="use the committed outputs")
    ap.add_argument(
        "--instructor",
        action="store_true",
        help=f"also build the instructors' site, solutions shown, in {INSTRUCTOR_HTML.relative_to(ROOT)}",
    )
    args = ap.parse_args(argv)
    want = set(args.only or ["book", "slides", "figures", "student"])
    summary = []
    t_all = time.perf_counter()

    if want & {"book", "slides"}:
        t = step("lessons: " + ("copying committed outputs" if args.no_execute else "executing every lesson"))
        lessons_into_book(execute=not args.no_execute)
        summary.append(("executed lessons", BOOK / "lessons", time.perf_counter() - t))
    if "figures" in want:
        t = step("figures for slides (python -m course.figures)")
        out = BUILD / "figures"
        run_optional("figure export", ["-m", "course.figures", "--out", str(out), "--format", "svg"])
        summary.append(("figures", out, time.perf_counter() - t))
    if "book" in want:
        t = step("figure gallery for the book (book/gallery.md)")
        drawn = BUILD / "figures"
        if "figures" in want and list(drawn.glob("*.svg")):  # just drawn, the same SVGs
            shutil.rmtree(GALLERY, ignore_errors=True)
            shutil.copytree(drawn, GALLERY, ignore=lambda d, names: [n for n in names if not n.endswith(".svg")])
            print(f"  copied {len(list(GALLERY.glob('*.svg')))} figures from {drawn.relative_to(ROOT)}")
        else:
            build_gallery()
        summary.append(("gallery figures", GALLERY, time.perf_counter() - t))
        t = step("book (Jupyter Book, offline): the students' site, no solutions")
        html = build_book(path_output=BOOK, gallery=False, book=site_source(SITE_SRC / "student"))
        summary.append(("course site", html, time.perf_counter() - t))
        if args.instructor:
            t = step("book for instructors: solutions shown")
            built = build_book(
                path_output=BUILD / "instructor",
                gallery=False,
                book=site_source(SITE_SRC / "instructor", instructor=True),
            )
            shutil.rmtree(INSTRUCTOR_HTML, ignore_errors=True)
            shutil.move(built, INSTRUCTOR_HTML)
            shutil.rmtree(BUILD / "instructor", ignore_errors=True)
            summary.append(("instructors' site", INSTRUCTOR_HTML, time.perf_counter() - t))
    if "slides" in want:
        t = step("slides (reveal.js, offline)")
        out = BUILD / "slides"
        # the lessons just executed (or copied) into book/lessons
        from course.slides import chromium

        pdf = ["--pdf"] if chromium() else []
        if not pdf:
            print("  Chromium is not installed (apt-get install chromium): the decks are built, their PDFs are not")
        run_optional("slides", ["-m", "course.slides", "--out", str(out), "--src", str(BOOK / "lessons"), *pdf])
        summary.append(("slides", out, time.perf_counter() - t))
    if "student" in want:
        t = step("student edition (solutions removed, outputs cleared)")
        out = ROOT / "dist" / "student"
        run_optional("student edition", ["-m", "course.student", "--out", str(out)])
        summary.append(("student edition", out, time.perf_counter() - t))

    print("\n== summary")
    for name, path, dt in summary:
        print(f"  {name:18s} {dt:7.1f} s  {size(path):>10s}  {path.relative_to(ROOT)}")
    print(f"  {'total':18s} {time.perf_counter() - t_all:7.1f} s")
    if "book" in want:
        print(f"\nOpen the course site: {BUILD / 'html' / 'index.html'}")
        if args.instructor:
            print(f"The instructors' site: {INSTRUCTOR_HTML / 'index.html'}")
    if "slides" in want:
        print(f"Open a lecture deck:  {BUILD / 'slides'}/<lesson>.slides.html")
    return 0


if __name__ == "__main__":
    sys.exit(main())
