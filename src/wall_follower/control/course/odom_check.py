"""Whether odometry can be trusted, message by message, and what is wrong when it cannot.

Every node that reads odometry (simple_move_square, record_odom, slam)
passes each message through one OdomCheck. A message is not trusted when
its position is not finite, its orientation is no unit quaternion (an
all-zero one included: it holds no heading), its stamp is earlier than the
one before (time went back: a simulator restarted, a bag looped), or it
lies further from the one before than the robot can drive in the time
between them (a jump: an odometry reset, a glitch). A node stops the robot
and warns with the words given. After a jump or time going back the
odometry frame itself is in doubt: OdomCheck.broken keeps the first such
problem until reset(), for a node whose plan is laid out in that frame.
"""
import math

from wall_follower.params import defaults
from wall_follower.params.odometry import JUMPS

_DEFAULT = defaults((JUMPS,))

# How far a quaternion's norm may be from 1 (float32 rounding, say) for its yaw to be trusted.
QUATERNION_TOLERANCE = 0.01


def odometry_problem(x, y, qx, qy, qz, qw):
    """What makes an odometry pose unusable, in a few words; None when it is usable.

    The yaw is read from the orientation as from a unit quaternion; one
    that is far from unit length (a zero one, say) holds no trustworthy
    heading, and a position that is not finite would poison the path length.
    """
    if not (math.isfinite(x) and math.isfinite(y)):
        return 'position (%r, %r) is not finite' % (x, y)
    norm = math.sqrt(qx * qx + qy * qy + qz * qz + qw * qw)
    if not abs(norm - 1.0) <= QUATERNION_TOLERANCE:
        return 'orientation (%r, %r, %r, %r) is not a unit quaternion (norm %r)' % (
            qx, qy, qz, qw, norm)
    return None


class JumpDetector(object):
    """Tells a jump of the odometry (a reset, a teleport) from travel.

    max_speed: the fastest (m/s) the robot can really move, with a margin.
    allowance: metres allowed on top of max_speed times the time between two
        poses, for jitter in the odometry's stamps.
    """

    def __init__(self, max_speed=_DEFAULT['max_speed'], allowance=_DEFAULT['jump_allowance']):
        if not max_speed > 0.0 or not allowance >= 0.0:
            raise ValueError('max_speed must be positive and allowance not negative, '
                             'got %r and %r' % (max_speed, allowance))
        self.max_speed = float(max_speed)
        self.allowance = float(allowance)
        self._last = None

    def jump(self, stamp, x, y):
        """Feed the next pose; the distance (m) it jumped from the last one, or None."""
        last, self._last = self._last, (stamp, x, y)
        if last is None:
            return None
        distance = math.hypot(x - last[1], y - last[2])
        reach = self.max_speed * max(0.0, stamp - last[0]) + self.allowance
        return distance if distance > reach else None

    def forget(self):
        """Take the next pose as the first."""
        self._last = None


class OdomCheck(object):
    """Checks each odometry message against the ones before.

    max_speed, allowance: as JumpDetector's. A message that jumped or went
    back in time becomes the one the next is checked against, so that each
    such problem is told once; `broken` keeps the first of them.
    """

    def __init__(self, max_speed=_DEFAULT['max_speed'], allowance=_DEFAULT['jump_allowance']):
        self.jumps = JumpDetector(max_speed, allowance)
        self._last_stamp = None
        self.broken = None

    def problem(self, stamp, x, y, qx, qy, qz, qw):
        """What is wrong with a message (stamp in s, position, orientation quaternion), in
        words; None when it can be trusted."""
        problem = odometry_problem(x, y, qx, qy, qz, qw)
        if problem is None and not math.isfinite(stamp):
            problem = 'its stamp %r is not finite' % stamp
        if problem is not None:
            return problem
        last, self._last_stamp = self._last_stamp, stamp
        if last is not None and stamp < last:
            self.jumps.forget()
            self.jumps.jump(stamp, x, y)
            problem = 'its time went back %.2f s (from %.2f s to %.2f s)' % (
                last - stamp, last, stamp)
        else:
            distance = self.jumps.jump(stamp, x, y)
            if distance is None:
                return None
            problem = ('it jumped %.2f m, further than the robot can drive at %.2f m/s '
                       '(~max_speed) in the time since the last pose' % (
                           distance, self.jumps.max_speed))
        if self.broken is None:
            self.broken = problem
        return problem

    def reset(self):
        """Start afresh: the next message is the first, and nothing is broken."""
        self.jumps.forget()
        self._last_stamp = None
        self.broken = None
