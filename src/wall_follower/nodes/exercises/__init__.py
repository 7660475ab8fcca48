"""The lab sheets' exercises as nodes: teleop, move square, forward/stop, range ahead, wander."""
