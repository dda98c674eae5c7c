"""A tiny benchmark case used only by tests/course/test_harness.py."""

import numpy as np

from benchmarks.harness import Case

CASES = [
    Case(
        name="smoke_norm",
        module="tests.course.bench_smoke",
        peer_name="numpy.linalg.norm",
        target=1e6,
        params={"n": 2000},
        check="check",
        description="harness self-test",
        ladder=(100_000, 300_000, 1_000_000),
    ),
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
    Case(
        name="smoke_memory",
        module="tests.course.bench_smoke",
        peer_name="a larger allocation",
        setup="setup_big",
        ours="ours_40mb",
        peer="peer_160mb",
        params={},
        description="harness self-test: peak memory",
    ),
)


def setup_big(seed):
    transient = np.ones(50_000_000)  # 400 MB, freed before the timed call
    return float(transient[seed])


def ours_40mb(_):
    return float(np.ones(5_000_000).sum())


def peer_160mb(_):
    return float(np.ones(20_000_000).sum())


# peak memory of a heap allocator: the warm-up's freed malloc chunks must not be reused
# unseen by the timed call (they would be, were they left resident)
CASES.append(
    Case(
        name="smoke_heap",
        module="tests.course.bench_smoke",
        peer_name="100 MB of small malloc chunks",
        ours="ours_40mb",
        peer="peer_heap_100mb",
        params={"n": 1},
        description="harness self-test: heap peak",
    ),
)

_PINNED = []


def peer_heap_100mb(_):
    """Allocate 25,000 chunks of 4 kB (system malloc, below the mmap threshold), keep
    every 50th alive so that the heap cannot shrink from its top, and free the rest."""
    chunks = [bytearray(4000) for _ in range(25_000)]
    _PINNED.extend(chunks[::50])
    return len(chunks)


# a check that reports a disagreement: the case is not met, however fast ours is
CASES.append(
    Case(
        name="smoke_mismatch",
        module="tests.course.bench_smoke",
        peer_name="a different function",
        target=1e6,
        params={"n": 2000},
        peer="peer_wrong",
        check="check_mismatch",
        description="harness self-test: mismatch",
    ),
)


def peer_wrong(x):
    return np.abs(x).sum(axis=1)


def check_mismatch(a, b):
    from benchmarks.harness import MISMATCH

    diff = float(np.abs(a - b).max())
    return f"{MISMATCH}: max diff {diff:.1e}" if diff > 1e-12 else f"max diff {diff:.0e}"


# a peer that cannot be imported here (as open3d without libusb): the run goes on
CASES.append(
    Case(
        name="smoke_unavailable",
        module="tests.course.bench_smoke",
        peer_name="a library that is not installed",
        target=1.0,
        params={"n": 10},
        peer="peer_unavailable",
        description="harness self-test: a peer that will not import",
    ),
)


def peer_unavailable(x):
    import shapelab_no_such_peer  # noqa: F401

    return x
