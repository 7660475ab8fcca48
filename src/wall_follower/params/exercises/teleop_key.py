"""Parameters of the teleop_key node: the node's own, then the keys'."""
from wall_follower.params import Parameter as P, Section, driving

NODE = (
    driving.loop(scan_timeout=0.5),
    Section('node', (
        P('tick', 0.1, 'commands go out this often, pressed key or not [s] (ROBOTIS\'s idle '
          'loop sends at 10 Hz)', 0.01, 1.0),
    )),
)
"""The node's own parameters (wall_follower.nodes.exercises.teleop_key)."""

TELEOP = (
    driving.LIMITS,
    Section('keys', (
        P('linear_step', 0.01, 'change of the target speed per key press (w, x) [m/s]; the '
          'command ramps toward the target by half of it per tick', 0.001, 0.19),
        P('angular_step', 0.1, 'change of the target turn rate per key press (a, d) [rad/s]; '
          'the same ramp', 0.001, 0.49),
    )),
)
"""The keys' parameters (wall_follower.exercises.teleop.Teleop); its targets are held to the
clamp's limits."""

TABLE = NODE + TELEOP
