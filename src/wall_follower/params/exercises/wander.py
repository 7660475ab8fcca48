"""Parameters of the wander node: its drive loop and clamp, then the behaviour's."""
import math

from wall_follower.params import Parameter as P, Section, driving

NODE = (
    driving.loop(scan_timeout=0.5),
    driving.LIMITS,
)
"""The node's own parameters (wall_follower.nodes.exercises.wander)."""

WANDER = (
    Section('wander', (
        P('speed', 0.19, 'forward speed [m/s] (the clamp holds it to max_linear)', 0.0, 1.0),
        P('turn_rate', 0.49, 'pivot rate [rad/s] (the clamp holds it to max_angular)',
          0.0, 3.0),
        P('obstacle_distance', 0.4, 'turn once a valid reading in the cone ahead is nearer '
          'than this [m]', 0.0, 10.0),
        P('clear_distance', 0.55, 'stop turning once every valid reading in the cone is at '
          'least this far [m]; not below obstacle_distance, or the robot dithers', 0.0, 10.0),
        P('cone_half_width', math.radians(35.0), 'the cone ahead, either side of straight '
          'ahead [rad]', 0.0, math.pi),
        P('side_reach', 1.5, 'when choosing a side to turn to, ranges (and no-returns) count '
          'up to this far [m]', 0.01, 20.0),
    )),
)
"""The behaviour's parameters (wall_follower.exercises.wander.Wanderer)."""


def _clear_beyond_obstacle(values):
    if values['clear_distance'] < values['obstacle_distance']:
        return 'clear_distance (%r) must not be below obstacle_distance (%r)' % (
            values['clear_distance'], values['obstacle_distance'])
    return None


RULES = (_clear_beyond_obstacle,)
"""What the behaviour's values must satisfy together (params.checked's rules)."""

TABLE = NODE + WANDER
