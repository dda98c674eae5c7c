"""ipywidgets explorers, built on :mod:`shapelab.plot`.

Each explorer returns an ``ipywidgets`` widget.  In a running notebook it recomputes
and redraws; on the static course site the widget state is embedded so the controls
still show and move.

================  ==========================================================
``balls``         :func:`alpha_explorer`: the growth model, a slider in τ;
                  :func:`power_explorer`: one disk's radius, its cell, hidden disks;
                  :func:`complex3d_explorer`: the growth model in 3D
``matching``      :func:`critical_points_explorer`: move the viewpoint S
``rotation``      :func:`icp_explorer`: step through ICP
``topology``      :func:`pocket_explorer`: voids and pockets as the balls grow;
                  :func:`persistence_explorer`: topological simplification
================  ==========================================================
"""

from __future__ import annotations

from .._toolkit.lazy import attach

_EXPORTS = {
    "alpha_explorer": "balls",
    "complex3d_explorer": "balls",
    "power_explorer": "balls",
    "persistence_explorer": "topology",
    "critical_points_explorer": "matching",
    "icp_explorer": "rotation",
    "pocket_explorer": "topology",
}
__all__ = sorted(_EXPORTS)


__getattr__, __dir__ = attach(__name__, _EXPORTS, eager=__all__)
