"""Parameters of the world_map node, read once at start.

No dynamic_reconfigure server: the node publishes one latched map of the
world the simulation was started with, which does not change mid-run.
"""
from wall_follower.params import Parameter as P, Section

TABLE = (
    Section('world', (
        P('world', 'arena', 'the world the simulation runs: a world of worlds/ by name, or a '
          '.world path'),
        P('pose', '', "'x y yaw_deg' start pose of the first robot when not the world file's "
          "(as stage_sim's ~pose); places the map in a robot's odometry frame that starts there"),
    )),
)
"""Every parameter of world_map."""
