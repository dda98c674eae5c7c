"""The acceleration behind :func:`shapelab.icp.icp`'s ``accelerate=True`` (the engine, not
required reading): type-II Anderson acceleration of a fixed-point map."""

from __future__ import annotations

import numpy as np

from .._toolkit.tolerances import ANDERSON_RCOND

__all__ = ["Anderson"]


class Anderson:
    """Type-II Anderson acceleration of a fixed-point map x ↦ g(x) in R^6 (depth m)."""

    def __init__(self, m: int = 5):
        self.m = m
        self.g: list[np.ndarray] = []
        self.f: list[np.ndarray] = []

    def reset(self) -> None:
        self.g.clear()
        self.f.clear()

    def __call__(self, x: np.ndarray, g: np.ndarray) -> np.ndarray | None:
        self.g.append(g)
        self.f.append(g - x)
        if len(self.g) > self.m + 1:
            del self.g[0], self.f[0]
        if len(self.g) < 2:
            return None
        F = np.array(self.f)
        Gm = np.array(self.g)
        dF = np.diff(F, axis=0).T  # (6, k)
        dG = np.diff(Gm, axis=0).T
        gamma, *_ = np.linalg.lstsq(dF, F[-1], rcond=ANDERSON_RCOND)
        out = Gm[-1] - dG @ gamma
        return out if np.all(np.isfinite(out)) else None
