"""The course site's accessibility fixes (issue 35, WCAG 2.1 AA), as a Sphinx extension
(``book/_config.yml`` lists ``course.sphinx_a11y``; the build puts the repository on the
path).  It also brings the templates and the stylesheet of ``book/_a11y/`` by absolute
path, so that a book built from a copy of ``_config.yml`` alone gets them too.

- A figure's text alternative, from where the figure was made (``shapelab.plot``'s
  descriptions, :func:`shapelab.plot.alt_text`):

  - a notebook output's ``metadata["image/png"]["alt"]`` (written when a figure is shown
    in a kernel) becomes the image's ``alt``.  myst-nb 1.x reads only ``width`` and
    ``height`` from an output's metadata (``alt`` only from a cell's ``mystnb.image``
    options) and otherwise leaves the alt to Sphinx, which writes the file's name;
  - a gallery figure (``book/gallery.md``, SVGs drawn by ``python -m course.figures``)
    gets the ``<title>`` its SVG carries.

- Markup of the theme and of docutils that axe-core flags as serious or critical:
  the citation list's ``role="list"`` holds ``role="doc-biblioentry"`` entries, which
  are no list items (aria-required-children): each entry becomes ``role="listitem"``
  (``doc-biblioentry`` is deprecated in DPUB-ARIA 1.1).  The search and colour-mode
  buttons' names (label-content-name-mismatch) are in ``book/_a11y/templates/``; the
  visible focus in ``book/_a11y/static/shapelab-a11y.css``.
"""

from __future__ import annotations

import html
import re
from pathlib import Path

ALT = "alt"
HERE = Path(__file__).resolve().parent.parent / "book" / "_a11y"
SVG_TITLE = re.compile(r'<title id="shapelab-alt">(.*?)</title>', re.S)


def _patch_myst_nb() -> None:
    from myst_nb.core.render import NbElementRenderer

    if getattr(NbElementRenderer.render_image, "_shapelab_alt", False):
        return
    original = NbElementRenderer.render_image

    def render_image(self, data):
        nodes = original(self, data)
        alt = ((data.output_metadata or {}).get(data.mime_type) or {}).get(ALT)
        if alt:
            for node in nodes:
                if node.tagname == "image" and not node.get("alt"):
                    node["alt"] = " ".join(str(alt).split())
        return nodes

    render_image._shapelab_alt = True
    NbElementRenderer.render_image = render_image


def svg_alt(path: Path) -> str | None:
    """The text alternative that ``course.figures`` wrote into an SVG, if any."""
    try:
        head = path.read_text(encoding="utf-8", errors="replace")[:20000]
    except OSError:
        return None
    m = SVG_TITLE.search(head)
    return html.unescape(m.group(1)).strip() if m else None


def _gallery_alts(app, doctree) -> None:
    from docutils import nodes

    src = Path(app.env.doc2path(app.env.docname)).parent
    for node in doctree.findall(nodes.image):
        uri = node.get("uri", "")
        if node.get("alt") or not uri.endswith(".svg"):
            continue
        alt = svg_alt(src / uri) or svg_alt(Path(app.srcdir) / uri)
        if alt:
            node["alt"] = alt


_BIBLIOENTRY = re.compile(r'(<div class="citation" id="[^"]*") role="doc-biblioentry"')


def _page(app, pagename, templatename, context, doctree) -> None:
    body = context.get("body")
    if body and 'role="doc-biblioentry"' in body:
        context["body"] = _BIBLIOENTRY.sub(r'\1 role="listitem"', body)


def _paths(app, config) -> None:
    # first in templates_path: ours replace the theme's components of the same name
    config.templates_path.insert(0, str(HERE / "templates"))
    config.html_static_path.append(str(HERE / "static"))


def setup(app):
    _patch_myst_nb()
    app.connect("config-inited", _paths)
    app.add_css_file("shapelab-a11y.css")
    app.connect("doctree-read", _gallery_alts)
    app.connect("html-page-context", _page)
    return {"parallel_read_safe": True, "parallel_write_safe": True, "version": "1"}
