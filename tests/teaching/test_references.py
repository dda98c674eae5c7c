"""Every citation in the lessons and the book names an entry of book/references.bib.

The lessons cite as Markdown links, ``[Edelsbrunner 1995](#cite-edelsbrunner1995)``
(course/citations.py), which JupyterLab shows as text; a MyST role such as
``{cite}`key``` would show there as raw markup, so none is left in a lesson's Markdown.
The book's own pages (book/*.md) are MyST and keep ``{cite}``.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
MYST_CITE = re.compile(r"\{cite(?::[a-z]+)?\}`([^`]+)`")
LESSON_CITE = re.compile(r"\[([^\]\n]+)\]\(#cite-([A-Za-z0-9_:-]+)\)")
RAW_ROLE = re.compile(r"\{[a-z:-]+\}`")


def _bib_keys() -> set[str]:
    text = (ROOT / "book" / "references.bib").read_text(encoding="utf-8")
    return set(re.findall(r"^@\w+\{([^,\s]+),", text, flags=re.M))


def _markdown_cells():
    for path in sorted((ROOT / "lessons").glob("*.ipynb")):
        for i, cell in enumerate(json.loads(path.read_text(encoding="utf-8"))["cells"]):
            if cell["cell_type"] == "markdown":
                yield path.name, i, "".join(cell["source"])


def _citations():
    for name, _, text in _markdown_cells():
        for _label, key in LESSON_CITE.findall(text):
            yield name, key
    for path in sorted((ROOT / "book").glob("*.md")):
        for group in MYST_CITE.findall(path.read_text(encoding="utf-8")):
            for key in group.split(","):
                yield path.name, key.strip()


def test_every_citation_is_in_the_bibliography():
    keys = _bib_keys()
    cited = list(_citations())
    assert any(name.endswith(".ipynb") for name, _ in cited), "no citation found: the pattern no longer matches"
    missing = sorted({(name, key) for name, key in cited if key not in keys})
    assert not missing, f"cited but not in book/references.bib: {missing}"


def test_no_lesson_shows_a_raw_role_in_jupyterlab():
    raw = [f"{name} cell {i}: {m.group(0)}" for name, i, text in _markdown_cells() for m in RAW_ROLE.finditer(text)]
    assert not raw, "MyST roles show as raw text in JupyterLab; cite as [Author Year](#cite-key):\n" + "\n".join(raw)


def test_a_citations_text_is_its_author_and_year():
    """The link text names the work as the bibliography does (course.citations.label), or
    its year alone where the sentence already names the authors."""
    from course.citations import label

    wrong = []
    for name, i, text in _markdown_cells():
        for shown, key in LESSON_CITE.findall(text):
            expected = label(key)
            if shown not in (expected, expected.rsplit(" ", 1)[1]):
                wrong.append(f"{name} cell {i}: [{shown}] for {key} (the bibliography says {expected!r})")
    assert not wrong, "\n".join(wrong)


def test_bibliography_keys_are_unique():
    text = (ROOT / "book" / "references.bib").read_text(encoding="utf-8")
    keys = re.findall(r"^@\w+\{([^,\s]+),", text, flags=re.M)
    assert len(keys) == len(set(keys))
