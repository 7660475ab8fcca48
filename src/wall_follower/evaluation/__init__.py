"""Evaluation: scoring from ground truth, course reports, plots and benchmarks."""
