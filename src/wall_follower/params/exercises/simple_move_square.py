"""Parameters of the simple_move_square node: the node's own, then the square's."""
import math

from wall_follower.params import Parameter as P, Section, driving, odometry

NODE = (
    driving.loop(scan_timeout=0.5),
    Section('odometry', (
        P('odom_timeout', 0.5, 'stand while the newest odometry is older than the scan by more '
          'than this [s]', 0.01, 10.0),
        P('odom_wait', 0.05, 'how long to wait for odometry as new as the scan [wall s]',
          0.0, 1.0),
    )),
    odometry.JUMPS,
)
"""The node's own parameters (wall_follower.nodes.exercises.simple_move_square)."""

SQUARE = (
    driving.LIMITS,
    Section('square', (
        P('side', 0.5, 'length of each side [m]', 0.05, 10.0),
        P('laps', 1, 'times round the square', 1, 100),
    )),
    Section('driving', (
        P('slow_down', 0.1, 'over the last this many metres of a side, the speed (max_linear '
          'before) falls in proportion to the distance left [m] ...', 0.001, 10.0),
        P('min_linear', 0.02, '... down to this [m/s]', 0.0, 0.19),
        P('turn_slow_down', 0.25, 'over the last this many radians of a corner, the turn rate '
          '(max_angular before) falls in proportion to the angle left [rad] ...',
          0.001, math.pi),
        P('min_angular', 0.04, '... down to this [rad/s]', 0.0, 0.49),
        P('distance_tolerance', 0.003, 'a side is done this near its end [m]', 0.0001, 0.5),
        P('heading_tolerance', 0.005, 'a corner is done this near the next side\'s heading '
          '[rad]', 0.0001, 0.5),
        P('heading_gain', 2.0, 'steering back onto a side\'s line per radian of heading error '
          '[1/s] ...', 0.0, 100.0),
        P('cross_track_gain', 4.0, '... and per metre off the line [rad/(m s)]', 0.0, 100.0),
    )),
)
"""The square's parameters (wall_follower.exercises.move_square.SquareDriver): it drives
the sides at max_linear and turns the corners at max_angular, the clamp's limits."""

TABLE = NODE + SQUARE
