"""Parameters of the forward_stop node: its drive loop and clamp, then the behaviour's."""
import math

from wall_follower.params import Parameter as P, Section, driving

NODE = (
    driving.loop(scan_timeout=0.5),
    driving.LIMITS,
)
"""The node's own parameters (wall_follower.nodes.exercises.forward_stop)."""

FORWARD_STOP = (
    Section('forward_stop', (
        P('forward_period', 5.0, 'seconds of driving, from the first scan on, then ... '
          '(the lab\'s rospy.Rate(0.2)) [s]', 0.01, 3600.0),
        P('stop_period', 5.0, '... seconds of standing, and so on [s]', 0.0, 3600.0),
        P('speed', 0.2, 'forward speed (the lab\'s; the clamp holds it to max_linear) [m/s]',
          0.0, 1.0),
        P('stop_distance', 0.4, 'in a forward phase, stand while a valid reading within '
          'cone_half_width of straight ahead is nearer than this [m]', 0.0, 10.0),
        P('cone_half_width', math.radians(20.0), 'the cone ahead that stop_distance watches, '
          'either side of straight ahead [rad]', 0.0, math.pi),
    )),
)
"""The behaviour's parameters (wall_follower.exercises.forward_stop.ForwardStop)."""

TABLE = NODE + FORWARD_STOP
