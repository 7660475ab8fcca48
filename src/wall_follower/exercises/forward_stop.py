"""Forward, stop, forward, ...: the lab's experiment 1, timed on ROS time, stopping for obstacles.

The lab's loop publishes once per rospy.Rate(0.2) sleep: one Twist drives
for one period and one stops for the next, and Stage's 0.2 s cmd_vel
watchdog stops the robot long before a period is up. Here the phase
(`forward_period`, then `stop_period`) is read from the clock at every
scan, so the command is re-sent all through its phase, and a forward phase
stops early (and says why) while something is nearer straight ahead than
`stop_distance`.
"""
import math

from wall_follower.control.motion import STOP, Command
from wall_follower.params import checked
from wall_follower.params.exercises.forward_stop import FORWARD_STOP

FORWARD = 'FORWARD'
STOPPED = 'STOPPED'
BLOCKED = 'BLOCKED'
PERIODS = ('forward_period', 'stop_period')


class ForwardStop(object):
    """The phase at each time, and the command for it given the scan.

    Its parameters (keyword arguments; their defaults, ranges and meanings
    are the FORWARD_STOP table) are the defaults overridden by those given.
    """

    def __init__(self, **params):
        self.p = checked(FORWARD_STOP, params)
        self.started = None
        self.state = None

    def reconfigure(self, **params):
        """Go on under these parameters (the defaults, overridden) from the next update on.

        New periods start a new cycle there, with a forward phase: the
        phase in progress was timed for the old ones.
        """
        old, self.p = self.p, checked(FORWARD_STOP, params)
        if any(old[name] != self.p[name] for name in PERIODS):
            self.restart()

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
