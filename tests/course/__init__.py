"""Tests of the course tooling: the book, slides, student edition, portability, benchmarks' harness, stubs."""
