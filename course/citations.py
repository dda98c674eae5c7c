"""Citations in the lessons: author–year text that every reader sees as text.

A lesson cites a work of ``book/references.bib`` with a Markdown link to its key::

    α-shapes ([Edelsbrunner and Mücke 1994](#cite-edelsbrunner1994))

JupyterLab (and GitHub) show the link text, "Edelsbrunner and Mücke 1994"; MyST's
``{cite}`key``` role would show as raw markup there.  The course's builds turn the link
into what each medium needs:

* the site (course/build.py): a link to the work's entry on the references page
  (``bibtex_cite_id`` in book/_config.yml gives the entries their ``cite-<key>`` ids);
* the decks (course/slides.py): the text alone, and a last slide, "Works cited", with
  the full references of what the deck cites, formatted from references.bib.

``label(key)`` is the link text the bibliography gives (first author's surname, "and"
the second's, "et al." for three or more, then the year).
"""

from __future__ import annotations

import functools
import html
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
BIB = ROOT / "book" / "references.bib"

#: a citation in a lesson's Markdown: [text](#cite-key)
CITE = re.compile(r"\[(?P<text>[^\]\n]+)\]\(#cite-(?P<key>[A-Za-z0-9_:-]+)\)")
#: a MyST role left as text, e.g. {cite}`key`, {cite:p}`key`, {ref}`label`
RAW_ROLE = re.compile(r"\{[a-z:-]+\}`")


@functools.cache
def _database(path: Path = BIB):
    from pybtex.database import parse_file

    return parse_file(str(path), bib_format="bibtex")


def _plain(latex: str) -> str:
    from pybtex.richtext import Text

    return Text.from_latex(latex).render_as("text")


def label(key: str, path: Path = BIB) -> str:
    """Author–year text for ``key``: "Edelsbrunner 1995", "Edelsbrunner and Mücke 1994",
    "Edelsbrunner et al. 2002"."""
    entry = _database(path).entries[key]
    names = [_plain(" ".join(p.last_names)) for p in entry.persons.get("author", [])]
    who = names[0] if len(names) == 1 else " and ".join(names) if len(names) == 2 else f"{names[0]} et al."
    return f"{who} {entry.fields.get('year', 'n.d.')}"


def anchor(key: str) -> str:
    """The id of ``key``'s entry on the site's references page (``bibtex_cite_id``)."""
    from docutils.nodes import make_id

    return make_id(f"cite-{key}")


def unknown(keys, path: Path = BIB) -> list[str]:
    """The keys among ``keys`` that ``path`` has no entry for."""
    entries = _database(path).entries
    return [k for k in dict.fromkeys(keys) if k not in entries]


def cited(markdown: str) -> list[str]:
    """The keys ``markdown`` cites, in order, each once."""
    return list(dict.fromkeys(m.group("key") for m in CITE.finditer(markdown)))


def for_site(markdown: str, references: str = "../references.html") -> str:
    """Each citation as a link to its entry on the references page."""
    return CITE.sub(
        lambda m: f'<a class="reference internal" href="{references}#{anchor(m.group("key"))}">{m.group("text")}</a>',
        markdown,
    )


def for_deck(markdown: str) -> str:
    """Each citation as its text (the deck's last slide lists the works)."""
    return CITE.sub(lambda m: m.group("text"), markdown)


@functools.cache
def _formatted(path: Path = BIB) -> dict[str, str]:
    from pybtex.plugin import find_plugin

    style = find_plugin("pybtex.style.formatting", "unsrt")()
    db = _database(path)
    return {e.key: " ".join(e.text.render_as("html").split()) for e in style.format_entries(db.entries.values())}


def reference(key: str, path: Path = BIB) -> str:
    """The full reference of ``key`` as HTML, as the site's references page gives it."""
    return _formatted(path)[key]


def works_cited(keys: list[str], path: Path = BIB) -> str:
    """A Markdown slide: "Works cited", each work as "label: full reference"."""
    rows = "\n".join(f"- **{html.escape(label(k, path))}**. {reference(k, path)}" for k in keys)
    return f"## Works cited\n\n{rows}"
