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


# peak memory: the setup's 400 MB transient must not count; the timed calls hold 40 and 160 MB
CASES.append(
    Case(name="smoke_memory", module="tests.bench_smoke", peer_name="a larger allocation", setup="setup_big",
         ours="ours_40mb", peer="peer_160mb", params={}, description="harness self-test: peak memory"),
)


def setup_big(seed):
    transient = np.ones(50_000_000)  # 400 MB, freed before the timed call
    return float(transient[seed])


def ours_40mb(_):
    return float(np.ones(5_000_000).sum())


def peer_160mb(_):
    return float(np.ones(20_000_000).sum())
