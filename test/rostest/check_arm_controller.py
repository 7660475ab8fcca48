#!/usr/bin/env python3
"""rostest: arm_controller follows trajectories on arm_controller/command as ros_control's
JointTrajectoryController does.

In simulated time that the test drives (the controller's own /clock is move_arm.test's),
held still while a trajectory stamped ahead is sent, until the controller has logged it: so
it arrives before its stamp however loaded the machine. A trajectory is followed (the joints
within 0.01 rad of each point at its time, with splines through points with velocities
and straight lines through points without); a replacing trajectory takes over mid-way
without a jump; every bad trajectory is rejected with a warning naming the problem and
no motion (a single point due now among them, as JointTrajectoryController rejects it),
one wholly in the past leaves the current one going on, and one stamped an hour ahead waits
for its time. An empty trajectory (no joints named, as JointTrajectoryController's own
tests send it) stops the arm from where it actually is, braking within the acceleration
limits to rest, and holds it there. No joint_states heard breaks a limit or puts a link
into the floor or into another.
"""
import unittest

import numpy as np
import rospy
import rostest
from rosgraph_msgs.msg import Log
from trajectory_msgs.msg import JointTrajectory, JointTrajectoryPoint

from arm_watch import ArmWatch
from driven_clock import DrivenClock
from rosout_log import RosoutLog
from waiting import wait_until
from wall_follower.arm.model import read_acceleration_limits
from wall_follower.params import defaults
from wall_follower.params.arm.arm_controller import TABLE

STEP = 1.0 / defaults(TABLE)['rate']    # s: the controller's step, as arm.launch runs it

SPEEDUP = 2.0   # simulated seconds per wall second while the clock runs
CONTROLLER = '/arm_controller'
NAMES = ['hip', 'shoulder', 'elbow', 'wrist']
TOLERANCE = 0.01   # rad
LEAD = 0.5   # simulated s between now and the stamp of a trajectory sent ahead
# Wall seconds a trajectory sent ahead waits to be logged before it is sent again, and how
# long in all: see send_ahead.
RESEND_AFTER = 5.0
LOG_LIMIT = 30.0


def trajectory(stamp, points, names=NAMES):
    """A JointTrajectory stamped stamp [s] (0: now) through (time, positions[, velocities[,
    accelerations]]) points."""
    msg = JointTrajectory(joint_names=list(names))
    msg.header.stamp = rospy.Time.from_sec(stamp)
    for point in points:
        msg.points.append(JointTrajectoryPoint(
            positions=list(point[1]), velocities=list(point[2]) if len(point) > 2 else [],
            accelerations=list(point[3]) if len(point) > 3 else [],
            time_from_start=rospy.Duration.from_sec(point[0])))
    return msg


class ArmControllerTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        rospy.init_node('check_arm_controller')
        cls.log = RosoutLog(CONTROLLER)
        cls.watch = ArmWatch(wait=False)
        cls.clock = DrivenClock(STEP, SPEEDUP, cls.watch.reached)
        cls.watch.wait_for_first_state()
        cls.command = rospy.Publisher('arm_controller/command', JointTrajectory, queue_size=10)
        if not wait_until(lambda: cls.command.get_num_connections() > 0, 30.0):
            raise AssertionError('arm_controller does not subscribe arm_controller/command')

    def send_ahead(self, points, names=NAMES, lead=LEAD):
        """Send a trajectory through points (as trajectory() takes them) stamped lead [s]
        ahead of now, holding the clock until the controller has logged it; its stamp and
        the message.

        The first one goes out just after the command topic's connection is up,
        and rospy can connect a subscriber twice and close one of the two (a
        CI run's log: two connections to arm_controller, one of them closed 3
        ms later): a message sent on the one closed is lost. With the clock
        held, the same message sent again asks the same of the controller, so
        it is sent again every RESEND_AFTER wall seconds until it is logged.
        """
        words = 'is stamped %.3f s ahead' % lead
        logged = len(self.log.lines(CONTROLLER, words, Log.INFO))

        def heard():
            return len(self.log.lines(CONTROLLER, words, Log.INFO)) > logged
        with self.clock.held() as now:
            # the controller at the clock's time, so that its "ahead" is the lead
            self.assertTrue(self.watch.wait_for_time(now), 'the arm\'s clock stopped')
            msg = trajectory(now + lead, points, names)
            sent = 0.0
            while sent < LOG_LIMIT and not heard():
                self.command.publish(msg)
                wait_until(heard, RESEND_AFTER)
                sent += RESEND_AFTER
            self.assertTrue(heard(), 'the controller never logged a trajectory that %s' % words)
        return now + lead, msg

    def follow(self, points, names=NAMES):
        """Send a trajectory ahead, wait past its last point and check each point was met at
        its time; its stamp."""
        start, msg = self.send_ahead(points, names)
        self.assert_points_met(msg, start)
        return start

    def assert_points_met(self, msg, start):
        """Wait past msg's last point and check each point was met at its time (start [s]:
        when the trajectory began)."""
        end = start + msg.points[-1].time_from_start.to_sec()
        self.assertTrue(self.watch.wait_for_time(end + 0.1), 'the arm\'s clock stopped')
        for number, point in enumerate(msg.points):
            due = start + point.time_from_start.to_sec()
            reached = self.watch.at(due)
            wanted = [point.positions[msg.joint_names.index(n)] for n in NAMES]
            self.assertTrue(np.all(np.abs(reached - wanted) < TOLERANCE),
                            'point %d due at %.2f s: joints at %s, not %s' % (
                                number, due, reached, wanted))

    def test_1_follows_a_trajectory_through_its_points_at_their_times(self):
        # cubic: positions and velocities; joints named in another order than the URDF's
        self.follow([(1.0, [0.4, 0.5, 0.3, 0.4], [0.4, 0.3, 0.2, 0.3]),
                     (2.0, [0.9, 0.8, 0.5, 0.7], [0.3, 0.2, 0.1, 0.2]),
                     (3.0, [1.2, 0.6, 0.0, 0.9], [0.0, 0.0, 0.0, 0.0])],
                    ['elbow', 'hip', 'wrist', 'shoulder'])
        # linear: positions only, from a zero stamp (now)
        start = self.watch.latest()[0]
        msg = trajectory(0.0, [(1.0, [0.2, 0.7, 0.8, 0.2]), (2.0, [-0.3, 0.3, 0.4, 0.0])])
        self.command.publish(msg)

        def moved():
            return [s for s in self.watch.since(start) if np.any(np.abs(s[2]) > 0)]
        self.assertTrue(wait_until(moved, 30.0), 'the arm never moved')
        begun = moved()[0][0] - STEP     # the stamp's "now": the controller's step before
        self.assertTrue(self.watch.wait_for_time(begun + 2.1), 'the arm\'s clock stopped')
        for point in msg.points:
            reached = self.watch.at(begun + point.time_from_start.to_sec())
            self.assertTrue(np.all(np.abs(reached - point.positions) < TOLERANCE),
                            '%s, not %s' % (reached, point.positions))

    def test_2_a_replacing_trajectory_takes_over_mid_way(self):
        start, _ = self.send_ahead([(2.0, [1.0, 1.0, 1.0, 1.0]), (4.0, [1.5, 0.5, 0.5, 0.5])])
        self.assertTrue(self.watch.wait_for_time(start + 1.1 - LEAD))
        takeover = self.follow([
            (1.5, [0.0, 0.3, 0.2, 0.0], [0, 0, 0, 0], [0, 0, 0, 0]),
            (2.0, [0.0, 0.2, 0.1, 0.0], [0, 0, 0, 0], [0, 0, 0, 0])])
        # the first trajectory was followed until the takeover...
        initial = self.watch.at(start)
        for time in np.arange(start, takeover, 0.1):
            expected = initial + (np.array([1.0] * 4) - initial) * (time - start) / 2.0
            self.assertTrue(np.all(np.abs(self.watch.at(time) - expected) < TOLERANCE))
        # ... and never after it: the arm turned back before the first's next point
        self.assertTrue(np.all(self.watch.at(takeover + 2.0) < 0.5))
        self.watch.assert_safe(self)

    def test_3_bad_trajectories_are_rejected_with_a_warning_and_no_motion(self):
        now = self.watch.latest()[0]
        bad = [
            (trajectory(0.0, [(1.0, [0, 0, 0, 0])], ['hip', 'shoulder', 'elbow', 'thumb']),
             'unknown joint(s) thumb'),
            (trajectory(0.0, [(1.0, [0, 0, 0])], ['hip', 'shoulder', 'elbow']),
             'joint(s) wrist missing'),
            (trajectory(0.0, [(1.0, [0.5, 0, 0, 0]), (1.0, [0.6, 0, 0, 0])]),
             'time_from_start must increase'),
            (trajectory(0.0, [(2.0, [0.5, 0, 0, 0]), (1.0, [0.6, 0, 0, 0])]),
             'time_from_start must increase'),
            (trajectory(0.0, [(1.0, [0, 0, 3.0, 0])]), 'elbow at 3.0000 rad is outside'),
            (trajectory(max(now - 5.0, 0.001), [(1.0, [0.5, 0, 0, 0])]),
             'every point is in the past'),
            (trajectory(0.0, [(0.0, [0.5, 0, 0, 0])]),
             'its last point is due now (time_from_start 0.000 s from a zero stamp, which'),
        ]
        for msg, words in bad:
            before = self.watch.latest()
            self.command.publish(msg)
            self.assertTrue(wait_until(lambda: self.log.said(CONTROLLER, words, Log.WARN),
                                       30.0), 'no warning saying %r' % words)
            self.assertTrue(self.watch.wait_for_time(before[0] + 0.5))
            for state in self.watch.since(before[0]):
                self.assertTrue(np.allclose(state[1], before[1], atol=1e-12), words)
            self.log._lines[:] = []

    def test_4_a_trajectory_in_the_past_leaves_the_current_one_going_on(self):
        start, current = self.send_ahead([(1.0, [0.3, 0.3, 0.3, 0.3]),
                                          (2.0, [0.6, 0.2, 0.5, 0.1])])
        self.assertTrue(self.watch.wait_for_time(start + 0.5))
        self.command.publish(trajectory(start - 3.0, [(1.0, [0.0, 0.0, 0.0, 0.0])]))
        self.assertTrue(wait_until(lambda: self.log.said(
            CONTROLLER, 'every point is in the past', Log.WARN), 30.0))
        self.assert_points_met(current, start)
        self.watch.assert_safe(self)

    def test_5_a_trajectory_stamped_ahead_is_logged_and_waits_for_its_time(self):
        before = self.watch.latest()
        self.send_ahead([(1.0, [0.5, 0.5, 0.5, 0.5])], lead=3600.0)
        self.assertTrue(self.watch.wait_for_time(before[0] + 1.0))
        for state in self.watch.since(before[0]):
            self.assertTrue(np.allclose(state[1], before[1], atol=1e-12))

    def test_6_an_empty_trajectory_brakes_the_arm_from_where_it_is_to_rest(self):
        """The hip is sent far faster than it can go: it runs at its speed limit, far behind
        what is desired of it. The stop brakes it from where it actually is (holding what
        was desired would run it on at full speed to 3 rad and halt it at once), within
        its acceleration limit, to rest where such a brake ends, and holds it there."""
        acceleration = read_acceleration_limits(
            rospy.get_param('robot_description_planning'), self.watch.model)
        limit = self.watch.model.velocity[0]
        self.follow([(4.0, [-3.0, 0.0, 0.0, 0.0])])
        start, _ = self.send_ahead([(0.5, [3.0, 0.0, 0.0, 0.0])])   # 6 s at its limit to 3 rad
        self.assertTrue(self.watch.wait_for_time(start + 0.6))
        asked = self.watch.latest()[0]
        self.assertAlmostEqual(self.watch.latest()[2][0], limit)     # held back
        self.command.publish(JointTrajectory())
        duration = 1.5 * limit / acceleration[0]    # the other joints are at rest
        self.assertTrue(wait_until(lambda: any(
            s[2][0] < limit for s in self.watch.since(asked)), 30.0), 'the hip never braked')
        states = self.watch.since(asked)
        braked = next(i for i, s in enumerate(states) if s[2][0] < limit)
        self.assertTrue(self.watch.wait_for_time(states[braked][0] + duration + 1.0))
        states = self.watch.since(asked)
        for previous, state in zip(states, states[1:]):
            change = np.abs(state[2] - previous[2]) / (state[0] - previous[0])
            self.assertTrue((change <= acceleration * 1.001).all(),
                            'at %.2f s: %s rad/s^2' % (state[0], change))
        rest = self.watch.since(states[braked - 1][0] + duration + STEP / 2)
        self.assertTrue(all(np.allclose(s[2], 0.0) for s in rest), 'still moving')
        self.assertTrue(all(np.allclose(s[1], rest[0][1], atol=1e-9) for s in rest))
        self.assertAlmostEqual(rest[0][1][0], states[braked - 1][1][0] + limit * duration / 2,
                               places=6)
        self.watch.assert_safe(self)


if __name__ == '__main__':
    rostest.rosrun('wall_follower', 'check_arm_controller', ArmControllerTest)
