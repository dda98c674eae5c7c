"""What every image-based explorer shares: a PNG ``ipywidgets.Image`` and the
rendering of a matplotlib figure into it.

An Image (not an Output widget) renders the same in a live kernel, under
nbclient/nbval and from the widget state stored in the static course site.
"""
from __future__ import annotations

import io

import ipywidgets as W

DPI = 90


def image(size_inches, dpi: int = DPI) -> W.Image:
    """An empty PNG image widget sized for a figure of ``size_inches`` at ``dpi``."""
    w, h = size_inches
    return W.Image(format="png", layout=W.Layout(width=f"{int(w * dpi)}px", height=f"{int(h * dpi)}px"))


def png(fig, dpi: int = DPI) -> bytes:
    """The figure as PNG bytes, at a fixed size (no tight bounding box, so the frame
    does not jump while a slider moves)."""
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi, bbox_inches=None)
    return buf.getvalue()
