"""Benchmark cases, one module per topic; each defines ``CASES``, a list of
:class:`benchmarks.harness.Case`."""
