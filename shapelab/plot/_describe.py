"""What a figure shows, in words: its text alternative (WCAG 2.1, 1.1.1), made where the
figure is made.

Every plotting function of :mod:`shapelab.plot` describes what it drew on the axes it
drew into (what is drawn, the parameter values, the counts); a lesson may refine or
replace that with :func:`describe`.  :func:`alt_text` reads it back: the figure's own
description if it has one, else its axes' descriptions, panel by panel.

The same text reaches every place the figure is shown:

- a notebook: when :mod:`shapelab.plot` is imported in an IPython kernel, a figure's
  PNG output carries it as ``metadata["image/png"]["alt"]`` (:func:`register`);
- the book (``book/_ext/shapelab_a11y.py``: myst-nb's image gets that ``alt``), the decks
  (``course/templates/reveal_offline``), the static explorers' frames
  (:mod:`shapelab.widgets.static`) and the figure export (``course/figures.py``).

>>> from shapelab import plot
>>> fig, ax = plot.new_figure()
>>> _ = plot.describe(ax, "Three points on a line")
>>> plot.alt_text(fig)
'Three points on a line.'
>>> _ = plot.describe(fig, "A line through three points", append=False)
>>> plot.alt_text(fig)
'A line through three points.'
"""

from __future__ import annotations

import sys
from typing import TYPE_CHECKING, TypeVar

if TYPE_CHECKING:
    from typing import Any

    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

__all__ = ["describe", "alt_text", "register"]

_ATTR = "_shapelab_alt"


_TEX = {
    r"\tau": "τ",
    r"\alpha": "α",
    r"\sigma": "σ",
    r"\theta": "θ",
    r"\pi": "π",
    r"\Pi": "Π",
    r"\cap": "∩",
    r"\cup": "∪",
    r"\infty": "∞",
    r"\leq": "≤",
    r"\geq": "≥",
    r"\mathbb{R}": "ℝ",
}


#: a Figure or an Axes: :func:`describe` returns what it is given
_Target = TypeVar("_Target", bound="Figure | Axes")


def _plain(text: str) -> str:
    """Text without matplotlib's mathtext: ``$K_\\tau$`` reads "K_τ"."""
    if "$" not in text:
        return text
    for tex, plain in _TEX.items():
        text = text.replace(tex, plain)
    return text.replace("$", "").replace("\\", "").replace("{", "").replace("}", "")


def _sentence(text: str) -> str:
    text = _plain(" ".join(str(text).split()))
    return text if not text or text[-1] in ".!?" else text + "."


def describe(target: _Target, text: str, *, append: bool = False) -> _Target:
    """Set what ``target`` (a matplotlib Figure or Axes) shows to ``text``; with
    ``append``, add ``text`` after what it already says.  Returns ``target``.

    A description on the figure takes precedence over its axes' ones
    (:func:`alt_text`).

    Examples
    --------
    >>> from shapelab.plot import alt_text, new_figure
    >>> fig, ax = new_figure()
    >>> describe(ax, "A line through the origin") is ax
    True
    >>> alt_text(fig)
    'A line through the origin.'
    >>> _ = describe(ax, "Its slope is 1", append=True)
    >>> alt_text(fig)
    'A line through the origin. Its slope is 1.'
    """
    if not isinstance(text, str) or not text.strip():
        raise ValueError("a figure's description must be a non-empty string")
    old = getattr(target, _ATTR, None) if append else None
    setattr(target, _ATTR, _sentence(text) if not old else old + " " + _sentence(text))
    return target


def alt_text(fig: Figure | Axes) -> str | None:
    """What ``fig`` shows: its own description, else its axes' descriptions (one axes:
    its text; several: "2 panels. Left: ...; right: ..." in reading order), else None."""
    own = getattr(fig, _ATTR, None)
    if own:
        return own
    axes = [ax for ax in getattr(fig, "axes", []) if getattr(ax, _ATTR, None)]
    if not axes:
        return None
    if len(axes) == 1:
        return getattr(axes[0], _ATTR)
    names = _panel_names(axes)
    parts = [f"{name}: {getattr(ax, _ATTR)}" for name, ax in zip(names, axes)]
    return f"{len(axes)} panels. " + " ".join(parts)


def _panel_names(axes) -> list[str]:
    """Left / right for one row of two, else "Panel 1", "Panel 2", ... in reading order."""
    try:
        pos = [ax.get_subplotspec().get_geometry() for ax in axes]
    except AttributeError:
        pos = None
    if pos and len(axes) == 2 and all(p[:2] == (1, 2) for p in pos):
        return ["Left", "Right"]
    if pos and len(axes) == 2 and all(p[:2] == (2, 1) for p in pos):
        return ["Top", "Bottom"]
    return [f"Panel {i}" for i in range(1, len(axes) + 1)]


def _bundle(fig):
    """The metadata of a figure's PNG output: its description as ``alt``."""
    text = alt_text(fig)
    if not text:
        return None
    return {}, {"image/png": {"alt": text}}


def _with_alt(png):
    """matplotlib-inline's PNG formatter ``png``, with the figure's description added to
    the metadata it returns (``retina`` returns ``{"width", "height"}``, which would
    otherwise replace the mime-bundle formatter's ``alt``)."""

    def formatter(fig):
        out = png(fig)
        text = alt_text(fig)
        if out is None or not text:
            return out
        data, md = out if isinstance(out, tuple) and len(out) == 2 else (out, None)
        return data, {**(md or {}), "alt": text}

    formatter._shapelab_alt = True
    return formatter


def _wrap_png(ip) -> None:
    """Wrap the PNG formatter registered for figures, if any and not wrapped yet."""
    from matplotlib.figure import Figure

    fmt = ip.display_formatter.formatters.get("image/png")
    if fmt is None:
        return
    try:
        png = fmt.lookup_by_type(Figure)
    except KeyError:
        return
    if not getattr(png, "_shapelab_alt", False):
        fmt.for_type(Figure, _with_alt(png))


def register(ip: Any | None = None) -> bool:
    """Make a figure's PNG output in the IPython kernel ``ip`` (default: the running one,
    if any) carry :func:`alt_text` as ``metadata["image/png"]["alt"]``.  True if done.

    The PNG itself is still made by the kernel's own formatter (matplotlib-inline's).
    Two routes add the description, so that the order of imports and of
    ``%matplotlib inline`` / ``%config InlineBackend.figure_formats`` does not matter:
    IPython's mime-bundle formatter, which matplotlib never registers into, gives it for
    plain PNG; and matplotlib-inline's PNG formatter, wrapped now and again before each
    cell if the backend has replaced it, keeps it beside the ``width`` and ``height``
    that ``retina`` figures carry."""
    if ip is None:
        if "IPython" not in sys.modules:
            return False
        from IPython import get_ipython

        ip = get_ipython()
    if ip is None or not hasattr(ip, "display_formatter"):
        return False
    from matplotlib.figure import Figure

    ip.display_formatter.mimebundle_formatter.for_type(Figure, _bundle)
    _wrap_png(ip)
    if hasattr(ip, "events") and not getattr(ip, "_shapelab_alt_hook", False):
        ip.events.register("pre_run_cell", lambda *args, **kwargs: _wrap_png(ip))
        ip._shapelab_alt_hook = True
    return True
