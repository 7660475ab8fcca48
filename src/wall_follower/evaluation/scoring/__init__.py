"""Scoring from ground truth: a lap against the band, a map against its world, a line follower."""
