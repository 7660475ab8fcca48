"""simple_move_square done closed-loop: a square of a given side, from odometry, not timing.

The lab's version switches between "forward" and "turn" on a timer, so its
square depends on the speeds reaching their set values at once and never
closes. Here each side is driven until odometry shows the robot at the
side's end and each corner pivoted until odometry shows the heading turned,
so the square closes however the robot accelerates:

    SIDE (toward corner k+1) -> CORNER (pivot left to the next side's heading)
         -> SIDE ... -> DONE after laps x 4 sides

The corners are those of the ideal square laid out from the start pose
(side k heads start yaw + k * 90 deg), so small errors of one side are not
carried into the next: each side steers back onto its line and ends level
with its corner. Sides run at the linear limit (`max_linear`) and slow
down linearly over the last `slow_down` metres; corners pivot at the
angular limit (`max_angular`) and slow down over the last `turn_slow_down`
radians, so that the last step before the end overshoots by no more than a
minimum speed allows.
"""
import math

from wall_follower.control.motion import STOP, Command
from wall_follower.params import checked
from wall_follower.params.exercises.simple_move_square import SQUARE
from wall_follower.rotation import wrap_angle

SIDE = 'SIDE'
CORNER = 'CORNER'
DONE = 'DONE'


class SquareDriver(object):
    """Steps through the square, one odometry pose (x, y, yaw) at a time.

    Its parameters (keyword arguments; their defaults, ranges and meanings
    are the SQUARE table) are the defaults overridden by those given.
    """

    def __init__(self, **params):
        self.reconfigure(**params)
        self.state = None
        self.start_pose = None
        self.leg = 0

    def reconfigure(self, **params):
        """Go on under these parameters (the defaults, overridden) from the next update on:
        the square laid out keeps its start pose, its corners move with a new side."""
        self.p = checked(SQUARE, params)
        self.sides = 4 * self.p['laps']

    def start(self, pose):
        """Lay the square out from pose: the first side runs straight ahead."""
        self.start_pose = pose
        self.leg = 0
        self.state = SIDE

    def corner(self, k):
        """The ideal square's k-th corner (0 = the start), world frame."""
        x, y, yaw = self.start_pose
        points = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
        px, py = points[k % 4]
        side = self.p['side']
        return (x + side * (px * math.cos(yaw) - py * math.sin(yaw)),
                y + side * (px * math.sin(yaw) + py * math.cos(yaw)))

    def heading(self, k):
        """The heading of side k (rad)."""
        return self.start_pose[2] + k * math.pi / 2.0

    @property
    def done(self):
        return self.state == DONE

    def update(self, pose):
        """The command for the robot at pose (x, y, yaw)."""
        if self.state == SIDE:
            return self._side(pose)
        if self.state == CORNER:
            return self._corner(pose)
        return STOP

    def _side(self, pose):
        p = self.p
        x, y, yaw = pose
        heading = self.heading(self.leg)
        ux, uy = math.cos(heading), math.sin(heading)
        ex, ey = self.corner(self.leg + 1)
        left = (ex - x) * ux + (ey - y) * uy              # distance still to go along the side
        sx, sy = self.corner(self.leg)
        off = -(x - sx) * uy + (y - sy) * ux               # metres left of the side's line
        if left <= p['distance_tolerance']:
            self.state = CORNER
            return self._corner(pose)
        speed = max(p['min_linear'], min(p['max_linear'], p['max_linear'] * left / p['slow_down']))
        turn = -p['heading_gain'] * float(wrap_angle(yaw - heading)) - p['cross_track_gain'] * off
        return Command(speed, max(-p['max_angular'], min(p['max_angular'], turn)))

    def _corner(self, pose):
        p = self.p
        error = float(wrap_angle(self.heading(self.leg + 1) - pose[2]))
        if abs(error) <= p['heading_tolerance']:
            self.leg += 1
            if self.leg >= self.sides:
                self.state = DONE
                return STOP
            self.state = SIDE
            return self._side(pose)
        rate = max(p['min_angular'], min(p['max_angular'],
                                         p['max_angular'] * abs(error) / p['turn_slow_down']))
        return Command(0.0, math.copysign(rate, error))
