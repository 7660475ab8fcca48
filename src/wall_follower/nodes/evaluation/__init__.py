"""Nodes that watch a run from outside the robot: the course report, a graded case, trials."""
