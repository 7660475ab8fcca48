"""Benchmarks behind scripts/benchmark: each module measures one part and prints a table."""
