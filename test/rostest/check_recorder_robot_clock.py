#!/usr/bin/env python3
"""rostest: record_odom on wall time with odometry from a robot on another clock.

A TurtleBot3's odometry is stamped by the robot's computer, whose clock may
be far off the machine that sends the goal. The recording must still start
at the goal: not wait for the robot's clock to reach the goal's stamp (a
clock behind), nor take odometry from before the goal (a clock ahead). This
test plays the robot: it publishes odometry, a pose further along x each
time, stamped off its own clock by a fixed amount. And a robot whose
stamps jump far ahead for a while, to 2100-01-01 before the goal and to
the largest stamp a header holds (2**32 - 1 s) during it: those poses are
skipped with a warning, and the recording starts at the goal and goes on
with the good poses after them.
"""
import sys
import threading
import unittest

import actionlib
import rospy
import rostest
from nav_msgs.msg import Odometry
from rosout_log import RosoutLog

from wall_follower.action_registration import action_server_registered
from wall_follower.msg import OdomRecordAction, OdomRecordGoal

from waiting import wait_until

# Seconds the robot's clock is off this machine's, per recorder namespace.
BEHIND = -100.0
AHEAD = 100.0
RATE = 10.0             # odometry messages per second
STEP = 0.05             # metres along x between two poses
BEFORE_GOAL = 3.0       # seconds of odometry before the goal is sent
AFTER_GOAL = 2.5        # and after it, before the goal is cancelled
# Wall seconds to wait for the recorder.
WAIT_LIMIT = 30.0
# Stamps far ahead, and the seconds during which the robot sends them: from the first pose
# (before the goal), and from the goal.
FAR_AHEAD = ((rospy.Time(4102444800), 1.0, 1.5), (rospy.Time(2 ** 32 - 1, 999999999), 1.0, 1.5))
FAR_AHEAD_AFTER_GOAL = 4.0   # s of odometry after the goal, before it is cancelled
FAR_NODE = '/far_ahead/odom_recorder'
FAR_AHEAD_WARNING = 'odometry on /far_ahead/odom skipped: it is stamped over'


class RobotOnAnotherClock(unittest.TestCase):

    def record_from(self, namespace, stamp_of, after_goal=AFTER_GOAL):
        """Publish odometry on namespace/odom, and record with a goal sent in between.

        stamp_of(now, elapsed, since_goal): the stamp of the pose published at now
        (a rospy.Time), elapsed seconds after the first and since_goal seconds after
        the goal was sent (None before). Returns the (time published, x, stamp) of
        every pose, the times just before and just after the goal was sent, and the
        recorded points.
        """
        odom = rospy.Publisher(namespace + '/odom', Odometry, queue_size=100)
        self.assertTrue(action_server_registered(namespace + '/record_odom', WAIT_LIMIT),
                        'no record_odom')
        client = actionlib.SimpleActionClient(namespace + '/record_odom', OdomRecordAction)
        self.assertTrue(client.wait_for_server(rospy.Duration(WAIT_LIMIT)), 'no record_odom')
        self.assertTrue(wait_until(lambda: odom.get_num_connections() > 0, WAIT_LIMIT),
                        'record_odom is not on odom')
        published = []
        sent = []   # when the goal was sent
        stop = threading.Event()

        def drive():
            rate = rospy.Rate(RATE)
            while not stop.is_set() and not rospy.is_shutdown():
                now = rospy.Time.now()
                msg = Odometry()
                msg.header.stamp = stamp_of(
                    now, now.to_sec() - (published[0][0] if published else now.to_sec()),
                    now.to_sec() - sent[0] if sent else None)
                msg.header.frame_id = 'odom'
                msg.pose.pose.position.x = STEP * len(published)
                msg.pose.pose.orientation.w = 1.0
                published.append((now.to_sec(), msg.pose.pose.position.x, msg.header.stamp))
                odom.publish(msg)
                rate.sleep()
        robot = threading.Thread(target=drive)
        robot.start()
        try:
            self.assertTrue(wait_until(lambda: published and
                                       published[-1][0] - published[0][0] >= BEFORE_GOAL,
                                       WAIT_LIMIT), 'no odometry published')
            before = rospy.get_time()
            client.send_goal(OdomRecordGoal())
            after = rospy.get_time()
            sent.append(after)
            self.assertTrue(wait_until(lambda: published[-1][0] >= after + after_goal,
                                       WAIT_LIMIT), 'odometry stopped')
            client.cancel_goal()
            self.assertTrue(client.wait_for_result(rospy.Duration(WAIT_LIMIT)))
        finally:
            stop.set()
            robot.join()
        return published, before, after, client.get_result().list_of_odoms

    def assert_recorded_from_the_goal(self, recording, after_goal=AFTER_GOAL):
        """recording: what record_from returned. Returns the index in it of the pose of
        each point recorded."""
        published, before, after, points = recording
        # A point a second, from the goal to the cancel.
        self.assertGreaterEqual(len(points), int(after_goal), 'recorded %d points' % len(points))
        poses = []
        for point in points:
            matching = [i for i, (_, x, _) in enumerate(published) if abs(x - point.x) < STEP / 2]
            self.assertEqual(len(matching), 1, 'the point at x %.2f is no pose published'
                             % point.x)
            poses.append(matching[0])
        # The first pose published once the goal was sent, or (delivery takes a moment)
        # the one before it.
        earliest = next(i for i, (t, _, _) in enumerate(published) if t >= before) - 1
        latest = next(i for i, (t, _, _) in enumerate(published) if t >= after)
        self.assertTrue(earliest <= poses[0] <= latest,
                        'the first point was published %+.2f s from the goal'
                        % (published[poses[0]][0] - before))
        return poses

    def test_a_robot_clock_behind_this_one(self):
        self.assert_recorded_from_the_goal(self.record_from(
            'behind', lambda now, _elapsed, _since_goal: now + rospy.Duration(BEHIND)))

    def test_a_robot_clock_ahead_of_this_one(self):
        self.assert_recorded_from_the_goal(self.record_from(
            'ahead', lambda now, _elapsed, _since_goal: now + rospy.Duration(AHEAD)))

    def test_stamps_far_ahead_for_a_while(self):
        log = RosoutLog(FAR_NODE)
        (early, early_from, early_to), (late, late_from, late_to) = FAR_AHEAD

        def stamp_of(now, elapsed, since_goal):
            if early_from <= elapsed < early_to:
                return early
            if since_goal is not None and late_from <= since_goal < late_to:
                return late
            return now
        recording = self.record_from('far_ahead', stamp_of, FAR_AHEAD_AFTER_GOAL)
        published = recording[0]
        poses = self.assert_recorded_from_the_goal(recording, FAR_AHEAD_AFTER_GOAL - late_to)
        taken = [published[i][2] for i in poses]
        self.assertFalse(any(stamp in (early, late) for stamp in taken),
                         'a pose stamped far ahead was recorded')
        last_bad = max(i for i, (_, _, stamp) in enumerate(published) if stamp == late)
        self.assertGreater(poses[-1], last_bad, 'nothing recorded after the stamps far ahead')
        self.assertTrue(wait_until(lambda: log.said(FAR_NODE, FAR_AHEAD_WARNING), WAIT_LIMIT),
                        'no warning saying "%s"' % FAR_AHEAD_WARNING)


if __name__ == '__main__':
    rospy.init_node('check_recorder_robot_clock')
    rostest.rosrun('wall_follower', 'check_recorder_robot_clock', RobotOnAnotherClock, sys.argv)
