"""Scaling curves of a benchmark case: time and peak memory against N, ours and the peer's.

:func:`benchmarks.harness.run_ladder` measures each rung of a case's ``ladder`` in
one fresh process per side (warm and cold time, peak memory of the warm call);
:func:`draw` fits ``log y = a + k log N`` by least squares over the rungs and
writes a two-panel log-log figure, ``<case>_scaling.png``, beside the results
table.  Rungs whose value is below the clock's or the allocator's resolution
(< 1 ms, < 1 MiB) are drawn but left out of the fit.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

__all__ = ["fit_exponent", "draw"]

_MIN_SECONDS = 1e-3
_MIN_KIB = 1024.0


def fit_exponent(n, y, floor: float = 0.0) -> float | None:
    """Least-squares slope of ``log y`` against ``log n`` over the points with
    ``y > floor`` (None with fewer than two such points at distinct n).

    >>> fit_exponent([1e3, 1e4, 1e5], [2e-3, 2e-2, 2e-1])
    1.0
    """
    n, y = np.asarray(n, float), np.asarray(y, float)
    ok = y > floor
    if np.unique(n[ok]).size < 2:
        return None
    k = np.polyfit(np.log(n[ok]), np.log(y[ok]), 1)[0]
    return float(round(k, 6))


def draw(case, points: list[dict], outdir: Path) -> tuple[dict, str]:
    """Fit the exponents of ``points`` (from ``run_ladder``) and draw the figure.

    Returns ``({"ours_time", "peer_time", "ours_memory", "peer_memory"}, file name)``.
    """
    import matplotlib

    matplotlib.use("Agg", force=False)
    from shapelab.plot._style import PALETTE, new_figure

    fig, (ax_t, ax_m) = new_figure(1, 2, size=(10.0, 4.2))
    exps = {}
    for side, color, label in (("ours", PALETTE[0], "shapelab"), ("peer", PALETTE[1], case.peer_name)):
        pts = [p for p in points if p["side"] == side]
        n = np.array([p["n"] for p in pts], float)
        t = np.array([p["seconds"] for p in pts])
        tc = np.array([p["cold_seconds"] for p in pts])
        m = np.array([p["peak_kib"] for p in pts], float)
        kt = fit_exponent(n, t, _MIN_SECONDS)
        km = fit_exponent(n, m, _MIN_KIB)
        exps[f"{side}_time"], exps[f"{side}_memory"] = kt, km
        short = label if len(label) <= 40 else label[:38] + "…"
        ax_t.loglog(n, t, "o-", color=color, label=f"{short} (warm, N^{kt:.2f})" if kt is not None else short)
        ax_t.loglog(n, tc, "x:", color=color, alpha=0.7, label=f"{short} (cold, first call)")
        mm = np.maximum(m, 1.0) / 1024.0
        ax_m.loglog(n, mm, "o-", color=color, label=f"{short} (N^{km:.2f})" if km is not None else short)
    ax_t.set(xlabel="N", ylabel="wall time (s)", title="time")
    ax_m.set(xlabel="N", ylabel="peak memory of the call (MiB)", title="peak memory")
    ax_t.legend(fontsize=8)
    ax_m.legend(fontsize=8)
    fig.suptitle(f"{case.name}: {case.description}", fontsize=10)
    name = f"{case.name}_scaling.png"
    fig.savefig(Path(outdir) / name)
    return exps, name
