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
    """An empty PNG image widget for a figure of ``size_inches`` at ``dpi``.

    Only the width is bounded (the figure's own width in pixels, or the page's if that is
    narrower); the height follows the frame's own aspect ratio, so a frame is never
    squashed, whatever the page width or the figure's actual size."""
    w, _ = size_inches
    return W.Image(
        format="png",
        layout=W.Layout(width="100%", max_width=f"{int(round(w * dpi))}px", height="auto", object_fit="contain"),
    )


def png(fig, dpi: int = DPI) -> bytes:
    """The figure as PNG bytes, at a fixed size (no tight bounding box, so the frame
    does not jump while a slider moves)."""
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi, bbox_inches=None)
    return buf.getvalue()


def check_balls(balls, *, dim: int | None, who: str, minimum: int = 1, what: str = "ball"):
    """Validate an explorer's ``balls``: a shapelab.Balls, of dimension ``dim`` (any if
    None), holding at least ``minimum`` of them."""
    from .._toolkit.validate import check_balls as check_type

    check_type(balls)
    if dim is not None and balls.dim != dim:
        raise ValueError(f"{who} draws {what}s in {dim}D: balls must be {dim}D, got {balls.dim}D")
    if len(balls) < minimum:
        count = {1: "one", 2: "two"}.get(minimum, str(minimum))
        raise ValueError(f"balls must hold at least {count} {what}{'' if minimum == 1 else 's'}, got {len(balls)}")
    return balls


def value_range(pair, name: str, *, nonnegative: bool = False) -> tuple[float, float]:
    """A slider's ``(low, high)`` argument, validated: finite numbers (>= 0 where asked)
    with low < high."""
    from .._toolkit.validate import as_finite_scalar

    try:
        lo, hi = (as_finite_scalar(v, name, nonnegative=nonnegative) for v in pair)
    except TypeError:
        kind = "numbers >= 0" if nonnegative else "finite numbers"
        raise TypeError(f"{name} must be a pair (low, high) of {kind}") from None
    if not lo < hi:
        raise ValueError(f"{name} must have low < high, got {tuple(pair)!r}")
    return lo, hi
