"""simple_move_square: a square of ~side, ~laps times, closed-loop on odometry, then stop.

The square is laid out from the first odometry pose (wherever the robot
stands) and driven by exercises.move_square.SquareDriver, answered once per
scan through the DriveLoop every driving node shares: so the robot stops
while the laser is stale or unusable and never drives forward into a
sector ahead that it cannot see, even here where the laser does not steer.
Each scan is answered from the odometry of the same moment, waited for
briefly when it has not come yet (in lockstep simulation the scan may come
first), and the robot stands while odometry lags the scan by more than
~odom_timeout, while it cannot be trusted (control.course.odom_check: not finite,
no unit quaternion; control.stamps: stamped far ahead), and for good once
it has jumped further than ~max_speed allows or its time went back: the
square was laid out in a frame that no longer holds. Its parameters
(params/exercises/simple_move_square.py) are tuned live: a change is applied at the
next scan, to the square already laid out.
"""
import math
import threading
import time

import rospy
from nav_msgs.msg import Odometry

from wall_follower.cfg import SimpleMoveSquareConfig
from wall_follower.control.course.odom_check import OdomCheck
from wall_follower.control.motion import STOP
from wall_follower.control.stamps import ahead_problem
from wall_follower.exercises.move_square import SquareDriver
from wall_follower.nodes.shared.drive_loop import drive_loop, take_retuned
from wall_follower.nodes.shared.latest_scan import LatestScan
from wall_follower.nodes.shared.messages import pose_of
from wall_follower.nodes.shared.parameters import NodeParameters
from wall_follower.nodes.shared.startup import init_node
from wall_follower.params import names, odometry, pick
from wall_follower.params.exercises.simple_move_square import SQUARE, TABLE


# Stamps of one simulated step are identical; elsewhere odometry this much
# older than the scan counts as of the same moment.
SAME_MOMENT = 1e-3


class LatestOdom(object):
    """The newest odometry pose, its stamp and what is wrong with it (OdomCheck), and a wait
    for one as new as a given time. max_speed, jump_allowance: as OdomCheck's."""

    def __init__(self, topic, max_speed, jump_allowance):
        self._latest = (None, None, None)    # (pose, stamp in s, problem), replaced as one
        self._arrived = threading.Condition()
        self.check = OdomCheck(max_speed, jump_allowance)
        self._sub = rospy.Subscriber(topic, Odometry, self._on_odom, queue_size=1)
        self.name = self._sub.resolved_name

    def _on_odom(self, msg):
        now = rospy.get_time()
        stamp = msg.header.stamp.to_sec() or now
        p, q = msg.pose.pose.position, msg.pose.pose.orientation
        with self._arrived:
            # Stamped far ahead: stale, and kept from OdomCheck, which would take
            # the good odometry after it for time going back.
            problem = ahead_problem(stamp, now) or self.check.problem(
                stamp, p.x, p.y, q.x, q.y, q.z, q.w)
            self._latest = (pose_of(msg), stamp, problem)
            self._arrived.notify_all()

    def forget(self):
        with self._arrived:
            self._latest = (None, None, None)
            self.check.reset()

    def at(self, when, wait):
        """(pose, stamp, problem) of the newest odometry, after waiting up to wait wall s for
        one stamped at when or later."""
        deadline = time.monotonic() + wait
        with self._arrived:
            while (self._latest[1] is None or self._latest[1] < when - SAME_MOMENT) \
                    and time.monotonic() < deadline:
                self._arrived.wait(deadline - time.monotonic())
            return self._latest


class SimpleMoveSquareNode(object):

    def __init__(self):
        self.params = NodeParameters(TABLE, SimpleMoveSquareConfig,
                                     read_at_start=names((odometry.JUMPS,)))
        values = self.params.snapshot()
        self.odom_timeout, self.odom_wait = values['odom_timeout'], values['odom_wait']
        # max_linear and max_angular are the square's speeds and the clamp alike.
        self.loop = drive_loop('simple_move_square', values, LatestScan('scan'))
        self.driver = SquareDriver(**pick(values, SQUARE))
        self.odom = LatestOdom('odom', values['max_speed'], values['jump_allowance'])
        self._started = False

    def run(self):
        p = self.driver.p
        rospy.loginfo('simple_move_square: %d lap(s) of a %.2f m square', p['laps'], p['side'])
        outcome = self.loop.run(self._answer, self._finished, on_clock_reset=self._restart)
        if outcome == 'done':
            rospy.loginfo('simple_move_square: done; stopped')
        return 0

    def _answer(self, _view, taken):
        values = take_retuned(self.params, self.loop)
        if values is not None:
            self.odom_timeout, self.odom_wait = values['odom_timeout'], values['odom_wait']
            self.driver.reconfigure(**pick(values, SQUARE))
        pose, stamp, problem = self.odom.at(taken, self.odom_wait)
        if pose is None or taken - stamp > self.odom_timeout:
            rospy.logwarn_throttle(5.0, 'simple_move_square: no odometry on %s within %.1f s of '
                                   'the scan; standing' % (self.odom.name, self.odom_timeout))
            return STOP
        broken = self.odom.check.broken
        if broken is not None:
            self.loop.warn('odometry on %s cannot be trusted: %s; the square is given up, '
                           'standing' % (self.odom.name, broken))
            return STOP
        if problem is not None:
            self.loop.warn('odometry on %s cannot be trusted: %s; standing'
                           % (self.odom.name, problem))
            return STOP
        if not self._started:
            self.driver.start(pose)
            self._started = True
            rospy.loginfo('simple_move_square: starting at (%.2f, %.2f) heading %.0f deg'
                          % (pose[0], pose[1], math.degrees(pose[2])))
        state = self.driver.state
        command = self.driver.update(pose)
        if self.driver.state != state:
            rospy.loginfo('simple_move_square: %s -> %s (side %d)', state, self.driver.state,
                          self.driver.leg + 1)
        return command

    def _finished(self):
        return 'done' if self.driver.done else None

    def _restart(self):
        """ROS time moved back: start a new square from wherever the robot then stands."""
        self.odom.forget()
        self._started = False


def main():
    init_node('simple_move_square')
    return SimpleMoveSquareNode().run()
