"""Pictures of runs: a lap over its map, a map beside its world, the arm's joints, rviz's screen."""
