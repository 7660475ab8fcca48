"""Forward, stop, forward, ...: the lab's experiment 1, timed on ROS time, stopping for obstacles.

The lab's loop publishes once per rospy.Rate(0.2) sleep: one Twist drives
for 5 s and one stops for 5 s, and Stage's 0.2 s cmd_vel watchdog stops the
robot long before the 5 s are up. Here the phase is read from the clock at
every scan, so the command is re-sent all through its phase, and a forward
phase stops early (and says why) while something is nearer straight ahead
than `stop_distance`.
"""
import math

from wall_follower.control.motion import STOP, Command

FORWARD = 'FORWARD'
STOPPED = 'STOPPED'
BLOCKED = 'BLOCKED'

DEFAULTS = {
    'forward_period': 5.0,
    'stop_period': 5.0,
    'speed': 0.2,
    'stop_distance': 0.4,
    'cone_half_width': math.radians(20.0),
}
"""forward_period, stop_period: seconds of driving and of standing, alternately
    (the lab's rospy.Rate(0.2): 5 s each), from the first scan on.
speed: forward speed [m/s] (the lab's 0.2; the node's clamp holds it to ~max_linear).
stop_distance: in a forward phase, stand while a valid reading within
    cone_half_width [rad] of straight ahead is nearer than this [m].
"""


class ForwardStop(object):
    """The phase at each time, and the command for it given the scan."""

    def __init__(self, **params):
        unknown = set(params) - set(DEFAULTS)
        if unknown:
            raise ValueError('unknown parameters: %s' % ', '.join(sorted(unknown)))
        self.p = dict(DEFAULTS, **params)
        if self.p['forward_period'] <= 0.0 or self.p['stop_period'] < 0.0:
            raise ValueError('forward_period must be positive and stop_period not negative')
        self.started = None
        self.state = None

    def restart(self):
        """Begin a new forward phase at the next update (e.g. after ROS time moved back)."""
        self.started = None

    def phase(self, now):
        """FORWARD or STOPPED at time now [s] by the schedule alone."""
        if self.started is None:
            self.started = now
        cycle = self.p['forward_period'] + self.p['stop_period']
        return FORWARD if (now - self.started) % cycle < self.p['forward_period'] else STOPPED

    def update(self, view, now):
        """The command for a ScanView taken at time now [s]; sets self.state."""
        self.state = self.phase(now)
        if self.state == STOPPED:
            return STOP
        nearest = nearest_ahead(view, self.p['cone_half_width'])
        if nearest < self.p['stop_distance']:
            self.state = BLOCKED
            return STOP
        return Command(self.p['speed'], 0.0)


def nearest_ahead(view, half_width):
    """The nearest valid reading within half_width of straight ahead (inf if none)."""
    mask = view.in_sector(0.0, half_width) & view.valid
    return float(view.ranges[mask].min()) if mask.any() else math.inf
