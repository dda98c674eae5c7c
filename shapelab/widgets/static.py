"""Explorers that work without a kernel: precomputed frames swapped by plain JavaScript.

In JupyterLab an explorer is a live ipywidget: moving its slider asks the kernel for a new
frame.  On the static course site there is no kernel, so a live widget would look frozen
(its slider moves, its frame and status do not).  When the course is built, every explorer
therefore also renders a **static player**: its frames and status lines precomputed along
its main control, with a range input that swaps them in a few lines of inline JavaScript.
No network request, no widget manager, no kernel.

The player is added to an explorer's display data (``text/html`` beside the widget view)
only when the environment variable ``SHAPELAB_STATIC_EXPLORERS`` is ``1``: the course build
sets it when it executes the lessons; JupyterLab, nbval and the committed notebooks do not,
so they keep the live widget alone.  The book prefers ``text/html`` over the widget view
(``nb_mime_priority_overrides`` in ``book/_config.yml``), JupyterLab the other way round.

Where an explorer has several controls, the frames follow its main control (``.slider``,
else its first slider) with the others fixed at their initial values, and the page says so.
"""

from __future__ import annotations

import base64
import hashlib
import html
import json
import os
import re

import numpy as np

__all__ = ["StaticFallback", "static_enabled", "static_html", "control_values", "FRAMES"]

#: default number of precomputed frames along the main control
FRAMES = 21

_ENV = "SHAPELAB_STATIC_EXPLORERS"


def static_enabled() -> bool:
    """True when explorers should carry their static player (``SHAPELAB_STATIC_EXPLORERS=1``).

    See Also
    --------
    static_html
        The player.
    """
    return os.environ.get(_ENV, "") == "1"


def _sliders(widget):
    """The slider widgets under ``widget``, depth first, in display order."""
    import ipywidgets as W

    kinds = (W.FloatSlider, W.IntSlider, W.SelectionSlider, W.FloatLogSlider)
    out = []
    for child in getattr(widget, "children", ()):
        if isinstance(child, kinds):
            out.append(child)
        else:
            out.extend(_sliders(child))
    return out


def _main_control(explorer):
    control = getattr(explorer, "slider", None)
    if control is None:
        sliders = _sliders(explorer)
        if not sliders:
            raise TypeError(f"{type(explorer).__name__} has no slider to precompute frames along")
        control = sliders[0]
    return control


def control_values(control, frames: int = FRAMES) -> list:
    """The values of ``control`` at which frames are precomputed: every position of an
    integer or selection slider when there are at most ``frames`` of them, else ``frames``
    values evenly spaced between its ends and snapped to its step.  The current value is
    always one of them (it replaces the nearest), so the page opens on the frame the
    notebook shows.

    >>> import ipywidgets as W
    >>> control_values(W.IntSlider(value=3, min=0, max=5))
    [0, 1, 2, 3, 4, 5]
    >>> control_values(W.FloatSlider(value=0.3, min=0.0, max=1.0, step=0.1), frames=3)
    [0.0, 0.3, 1.0]

    See Also
    --------
    static_html
        Uses the values.
    """
    import ipywidgets as W

    if not isinstance(frames, (int, np.integer)) or isinstance(frames, bool) or frames < 2:
        raise ValueError(f"frames must be an integer >= 2, got {frames!r}")
    current = control.value
    if isinstance(control, W.SelectionSlider):
        options = list(control.options)
        labels = [o[1] if isinstance(o, tuple) else o for o in options]
        if len(labels) <= frames:
            return labels
        idx = np.unique(np.round(np.linspace(0, len(labels) - 1, frames)).astype(int))
        values = [labels[i] for i in idx]
        if current not in values:
            values[int(np.argmin([abs(int(i) - labels.index(current)) for i in idx]))] = current
        return values
    lo, hi = control.min, control.max
    if isinstance(control, W.IntSlider):
        step = max(int(control.step), 1)
        grid = list(range(int(lo), int(hi) + 1, step))
        if len(grid) > frames:
            picks = np.unique(np.round(np.linspace(0, len(grid) - 1, frames)).astype(int))
            grid = [grid[i] for i in picks]
    else:
        step = float(control.step) if control.step else (hi - lo) / (frames - 1)
        raw = np.linspace(lo, hi, frames)
        snapped = lo + np.round((raw - lo) / step) * step
        grid = [float(v) for v in np.unique(np.clip(snapped, lo, hi))]
    if current not in grid:
        nearest = int(np.argmin([abs(v - current) for v in grid]))
        grid[nearest] = current
        grid = sorted(set(grid))
    return grid


def _readout(control, value) -> str:
    import ipywidgets as W

    if isinstance(control, W.FloatSlider):
        fmt = getattr(control, "readout_format", ".2f") or ".2f"
        try:
            return format(value, fmt)
        except ValueError:
            return f"{value:.3g}"
    return str(value)


def static_html(explorer, *, frames: int = FRAMES) -> str:
    """The explorer as a self-contained HTML player: its frames along the main control
    (``frames`` of them at most), their status lines, and a range input that swaps them.

    The explorer is moved through the values and put back where it was.  The output is
    deterministic (the element id is a hash of the content) and names no URL.

    See Also
    --------
    StaticFallback
        The mixin that calls it.
    """
    control = _main_control(explorer)
    image = getattr(explorer, "image", None)
    status = getattr(explorer, "status", None)
    if image is None:
        raise TypeError(f"{type(explorer).__name__} has no .image frame to precompute")
    start_value = control.value
    values = control_values(control, frames)
    pngs, lines, alts = [], [], []
    try:
        for v in values:
            control.value = v  # the explorer's observer redraws the frame and status
            pngs.append(base64.b64encode(bytes(image.value)).decode("ascii"))
            lines.append(status.value if status is not None else "")
            alts.append(_frame_alt(explorer, control, v, lines[-1]))
    finally:
        control.value = start_value
    start = values.index(start_value) if start_value in values else 0
    name = html.escape(control.description or "value")
    readouts = [f"{control.description or 'value'} = {_readout(control, v)}" for v in values]
    others = [s for s in _sliders(explorer) if s is not control]
    note = (
        f"Static page: {len(values)} precomputed frames along {name}"
        + (
            f" ({', '.join(html.escape(s.description or 'slider') for s in others)} fixed at the values shown)"
            if others
            else ""
        )
        + ". Run the notebook for the live explorer."
    )
    payload = json.dumps({"frames": pngs, "status": lines, "readout": readouts, "alt": alts}, separators=(",", ":"))
    payload = payload.replace("</", "<\\/")  # never closes the script element early
    uid = "slx-" + hashlib.sha1(payload.encode()).hexdigest()[:12]
    # accessibility (issue 35, WCAG 2.1 AA): the range input is named by a visible label
    # and announces the value it stands for (aria-valuetext), not the frame's index; the
    # arrow keys move it (a native range input); the status line is a live region; every
    # frame has its own text alternative; the focus is visible
    return (
        f'<div class="shapelab-static-explorer" id="{uid}" style="max-width:100%" role="group" '
        f'aria-label="Explorer along {name}">'
        f"<style>#{uid} input:focus-visible{{outline:3px solid #0072B2;outline-offset:3px}}</style>"
        f'<div style="display:flex;gap:0.8em;align-items:center">'
        f'<label for="{uid}-in" class="slx-label">{name}</label>'
        f'<input id="{uid}-in" type="range" min="0" max="{len(values) - 1}" step="1" value="{start}" '
        f'aria-valuetext="{html.escape(readouts[start])}" style="flex:1 1 auto;max-width:70%">'
        f'<output for="{uid}-in" style="font-family:monospace">{html.escape(readouts[start])}</output></div>'
        f'<div class="slx-status" aria-live="polite">{lines[start]}</div>'
        f'<img alt="{html.escape(alts[start])}" src="data:image/png;base64,{pngs[start]}" '
        f'style="display:block;max-width:100%;height:auto">'
        f'<p class="slx-note" style="font-size:85%">{note}</p>'
        f'<script type="application/json" class="slx-data">{payload}</script>'
        "<script>(function(){"
        f'var r=document.getElementById("{uid}");if(!r)return;'
        'var d=JSON.parse(r.querySelector(".slx-data").textContent);'
        'var i=r.querySelector("input"),o=r.querySelector("output"),'
        's=r.querySelector(".slx-status"),m=r.querySelector("img");'
        'function show(){var k=+i.value;m.src="data:image/png;base64,"+d.frames[k];m.alt=d.alt[k];'
        's.innerHTML=d.status[k];o.textContent=d.readout[k];i.setAttribute("aria-valuetext",d.readout[k]);}'
        'i.addEventListener("input",show);})();</script></div>'
    )


def _frame_alt(explorer, control, value, status: str) -> str:
    """A frame's text alternative: what the explorer's figure says it shows
    (``explorer.alt``, from :func:`shapelab.plot.alt_text`), else the explorer, the
    control's value and the status line in words."""
    text = getattr(explorer, "alt", None)
    if text:
        return text
    plain = html.unescape(re.sub(r"<[^>]+>", " ", status or "")).replace("\xa0", " ")
    plain = " ".join(plain.split())
    what = f"{type(explorer).__name__} at {control.description or 'value'} = {_readout(control, value)}"
    return what + (f": {plain}" if plain else "") + "."


class StaticFallback:
    """Mixin for an explorer (an ipywidgets box with ``.image``, ``.status`` and a slider):
    adds the static player to its display data when :func:`static_enabled`.

    See Also
    --------
    static_html
        The player it embeds.
    """

    @property
    def alt(self) -> str | None:
        """What the current frame shows (:func:`shapelab.plot.alt_text` of its figure)."""
        return self.__dict__.get("_shapelab_alt")

    @alt.setter
    def alt(self, text: str | None) -> None:
        # not the live Image's tooltip: the offline widget manager of the decks
        # (@jupyter-widgets/html-manager 1.0.15) cannot draw an Image that has one (it shows
        # its error widget instead); the decks name a live frame by its status line
        self.__dict__["_shapelab_alt"] = text

    def _repr_mimebundle_(self, **kwargs):
        data = super()._repr_mimebundle_(**kwargs)
        if static_enabled() and isinstance(data, dict):
            data = dict(data)
            data["text/html"] = static_html(self)
        return data
