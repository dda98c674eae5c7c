"""A tiny benchmark case used only by tests/test_harness.py."""
import numpy as np

from benchmarks.harness import Case

CASES = [
    Case(name="smoke_norm", module="tests.bench_smoke", peer_name="numpy.linalg.norm", target=1e6,
         params={"n": 2000}, check="check", description="harness self-test"),
]


def setup(seed, n):
    return np.random.default_rng(seed).normal(size=(n, 3))


def ours(x):
    return np.sqrt((x * x).sum(axis=1))


def peer(x):
    return np.linalg.norm(x, axis=1)


def check(a, b):
    return f"max diff {np.abs(a - b).max():.0e}"
