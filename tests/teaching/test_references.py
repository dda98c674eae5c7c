"""Every citation in the lessons and the book names an entry of book/references.bib."""

from __future__ import annotations

import json
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
CITE = re.compile(r"\{cite(?::[a-z]+)?\}`([^`]+)`")


def _bib_keys() -> set[str]:
    text = (ROOT / "book" / "references.bib").read_text(encoding="utf-8")
    return set(re.findall(r"^@\w+\{([^,\s]+),", text, flags=re.M))


def _citations():
    for path in sorted((ROOT / "lessons").glob("*.ipynb")):
        for cell in json.loads(path.read_text(encoding="utf-8"))["cells"]:
            if cell["cell_type"] == "markdown":
                for group in CITE.findall("".join(cell["source"])):
                    for key in group.split(","):
                        yield path.name, key.strip()
    for path in sorted((ROOT / "book").glob("*.md")):
        for group in CITE.findall(path.read_text(encoding="utf-8")):
            for key in group.split(","):
                yield path.name, key.strip()


def test_every_citation_is_in_the_bibliography():
    keys = _bib_keys()
    cited = list(_citations())
    assert cited, "no citation found: the pattern no longer matches the lessons"
    missing = sorted({(name, key) for name, key in cited if key not in keys})
    assert not missing, f"cited but not in book/references.bib: {missing}"


def test_bibliography_keys_are_unique():
    text = (ROOT / "book" / "references.bib").read_text(encoding="utf-8")
    keys = re.findall(r"^@\w+\{([^,\s]+),", text, flags=re.M)
    assert len(keys) == len(set(keys))
