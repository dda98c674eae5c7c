"""Accuracy of the α-filtration values: ours and GUDHI's default precision, both
against GUDHI's exact arithmetic, simplex by simplex, on the benchmark's data.

    python -m benchmarks.accuracy                 # 2D 30,000 and 3D 10,000 balls
    python -m benchmarks.accuracy --n 5000 --dim 3

Issue 4 asks for values identical to GUDHI's ``AlphaComplex(points, weights)`` to 1e-9
relative.  That is a statement about the exact values: GUDHI's default ("safe")
precision is itself off by more than that on large inputs, so both are measured
against ``precision="exact"``.  Relative error is |v - exact| / |exact|; near-zero
values are where floating point loses it (the power of an orthosphere is a difference
of nearly equal numbers).
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from benchmarks.cases.filtration import setup


def _values(st) -> dict:
    return {tuple(s): v for s, v in st.get_filtration()}


def compare(n: int, dim: int, seed: int = 0) -> list[dict]:
    import gudhi

    from shapelab import Balls, alpha_filtration

    centers, radii = setup(seed, n=n, dim=dim)
    t = time.perf_counter()
    F = alpha_filtration(Balls(centers, radii))
    t_ours = time.perf_counter() - t
    exact = _values(gudhi.AlphaComplex(points=centers, weights=radii**2, precision="exact").create_simplex_tree())
    safe = _values(gudhi.AlphaComplex(points=centers, weights=radii**2).create_simplex_tree())
    rows = []
    for k in range(F.dimension + 1):
        S = F.simplices(k)
        keys = [tuple(int(i) for i in s) for s in S]
        ex = np.array([exact[s] for s in keys])
        sf = np.array([safe[s] for s in keys])
        den = np.maximum(np.abs(ex), np.finfo(float).tiny)
        ours_rel = np.abs(F.values(k) - ex) / den
        safe_rel = np.abs(sf - ex) / den
        rows.append(
            {
                "dim": k,
                "n": len(keys),
                "ours_max": float(ours_rel.max()),
                "ours_over": int((ours_rel > 1e-9).sum()),
                "safe_max": float(safe_rel.max()),
                "safe_over": int((safe_rel > 1e-9).sum()),
                "seconds": t_ours,
            }
        )
    return rows


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument(
        "--n", type=int, nargs="*", default=None, help="numbers of balls (default 30000 in 2D, 10000 in 3D)"
    )
    ap.add_argument("--dim", type=int, choices=(2, 3), default=None)
    ap.add_argument("--seed", type=int, default=0)
    args = ap.parse_args(argv)
    runs = [(30_000, 2), (10_000, 3)] if args.dim is None else [(n, args.dim) for n in (args.n or [10_000])]
    print("| N | d | k | simplices | ours: max rel err | ours: > 1e-9 | GUDHI safe: max rel err | GUDHI safe: > 1e-9 |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|")
    for n, dim in runs:
        for r in compare(n, dim, args.seed):
            print(
                f"| {n} | {dim} | {r['dim']} | {r['n']} | {r['ours_max']:.1e} | {r['ours_over']} | "
                f"{r['safe_max']:.1e} | {r['safe_over']} |",
                flush=True,
            )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
