"""Words of prose per lesson: the measure of a lesson's length (issue 34).

    python -m course.wordcount            # a Markdown table: lesson, core words, going deeper, total
    python -m course.wordcount --check    # fails when a lesson is over LIMIT words outside Going deeper

A word is what ``wc -w`` counts: a run of characters between white space, so a
formula counts by its pieces and a Markdown link as its text and address; only Markdown
cells count.  A section whose heading starts with "Going deeper"
(``## Going deeper: cohomology``) runs to the next heading of the same or a higher level;
its words are counted apart, since a class may skip it.  The References section is
counted apart too, but it counts toward the limit: a lesson's length is every word
outside its "Going deeper" sections (the measure issue 34 used: lesson 08 had 3,637).
"""

from __future__ import annotations

import json
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
LIMIT = 3000

_HEADING = re.compile(r"^(#{1,6})\s+(.*)$", re.M)


def words(text: str) -> int:
    """The number of words in Markdown ``text``, as ``wc -w`` counts them."""
    return len(text.split())


def count(path: Path) -> dict:
    """``{"core": n, "deeper": n, "references": n}`` for the lesson notebook at ``path``."""
    cells = json.loads(Path(path).read_text(encoding="utf-8"))["cells"]
    out = {"core": 0, "deeper": 0, "references": 0}
    mode, level = "core", 0
    for cell in cells:
        if cell["cell_type"] != "markdown":
            continue
        text = "".join(cell["source"])
        pieces, last = [], 0
        for m in _HEADING.finditer(text):
            pieces.append((None, text[last : m.start()]))
            pieces.append((m, m.group(0)))
            last = m.end()
        pieces.append((None, text[last:]))
        for m, piece in pieces:
            if m is not None:
                depth, title = len(m.group(1)), m.group(2).strip().lower()
                if mode != "core" and depth <= level:
                    mode = "core"
                if title.startswith("going deeper"):
                    mode, level = "deeper", depth
                elif title.startswith("references"):
                    mode, level = "references", depth
            out[mode] += words(piece)
    return out


def length(c: dict) -> int:
    """A lesson's length: its words outside the "Going deeper" sections."""
    return c["core"] + c["references"]


def table() -> str:
    rows = [f"| lesson | words (limit {LIMIT}) | of them references | going deeper |", "|---|---:|---:|---:|"]
    for path in sorted((ROOT / "lessons").glob("[0-9][0-9]_*.ipynb")):
        c = count(path)
        rows.append(f"| {path.stem} | {length(c):,} | {c['references']:,} | {c['deeper']:,} |")
    return "\n".join(rows)


def main(argv=None) -> int:
    argv = sys.argv[1:] if argv is None else argv
    print(table())
    if "--check" in argv:
        over = [p.stem for p in sorted((ROOT / "lessons").glob("[0-9][0-9]_*.ipynb")) if length(count(p)) > LIMIT]
        if over:
            print(f"over {LIMIT} words: {', '.join(over)}", file=sys.stderr)
            return 1
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
