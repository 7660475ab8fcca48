#!/usr/bin/env python3
"""rostest: record_odom on wall time with odometry from a robot on another clock.

A TurtleBot3's odometry is stamped by the robot's computer, whose clock may
be far off the machine that sends the goal. The recording must still start
at the goal: not wait for the robot's clock to reach the goal's stamp (a
clock behind), nor take odometry from before the goal (a clock ahead). This
test plays the robot: it publishes odometry, a pose further along x each
time, stamped off its own clock by a fixed amount.
"""
import sys
import threading
import unittest

import actionlib
import rospy
import rostest
from nav_msgs.msg import Odometry

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


class RobotOnAnotherClock(unittest.TestCase):

    def record_from(self, namespace, clock_offset):
        """Publish odometry on namespace/odom, and record with a goal sent in between.

        Returns the (time published, x) of every pose, the times just before
        and just after the goal was sent, and the recorded points.
        """
        odom = rospy.Publisher(namespace + '/odom', Odometry, queue_size=100)
        client = actionlib.SimpleActionClient(namespace + '/record_odom', OdomRecordAction)
        self.assertTrue(client.wait_for_server(rospy.Duration(WAIT_LIMIT)), 'no record_odom')
        self.assertTrue(wait_until(lambda: odom.get_num_connections() > 0, WAIT_LIMIT),
                        'record_odom is not on odom')
        published = []
        stop = threading.Event()

        def drive():
            rate = rospy.Rate(RATE)
            while not stop.is_set() and not rospy.is_shutdown():
                now = rospy.Time.now()
                msg = Odometry()
                msg.header.stamp = now + rospy.Duration(clock_offset)
                msg.header.frame_id = 'odom'
                msg.pose.pose.position.x = STEP * len(published)
                msg.pose.pose.orientation.w = 1.0
                published.append((now.to_sec(), msg.pose.pose.position.x))
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
            self.assertTrue(wait_until(lambda: published[-1][0] >= after + AFTER_GOAL,
                                       WAIT_LIMIT), 'odometry stopped')
            client.cancel_goal()
            self.assertTrue(client.wait_for_result(rospy.Duration(WAIT_LIMIT)))
        finally:
            stop.set()
            robot.join()
        return published, before, after, client.get_result().list_of_odoms

    def assert_recorded_from_the_goal(self, namespace, clock_offset):
        published, before, after, points = self.record_from(namespace, clock_offset)
        # A point a second, from the goal to the cancel.
        self.assertGreaterEqual(len(points), int(AFTER_GOAL), 'recorded %d points' % len(points))
        first = [i for i, (_, x) in enumerate(published) if abs(x - points[0].x) < STEP / 2.0]
        self.assertEqual(len(first), 1, 'the first point is no pose published')
        # The first pose published once the goal was sent, or (delivery takes a moment)
        # the one before it.
        earliest = next(i for i, (t, _) in enumerate(published) if t >= before) - 1
        latest = next(i for i, (t, _) in enumerate(published) if t >= after)
        self.assertTrue(earliest <= first[0] <= latest,
                        'the first point was published %+.2f s from the goal'
                        % (published[first[0]][0] - before))

    def test_a_robot_clock_behind_this_one(self):
        self.assert_recorded_from_the_goal('behind', BEHIND)

    def test_a_robot_clock_ahead_of_this_one(self):
        self.assert_recorded_from_the_goal('ahead', AHEAD)


if __name__ == '__main__':
    rospy.init_node('check_recorder_robot_clock')
    rostest.rosrun('wall_follower', 'check_recorder_robot_clock', RobotOnAnotherClock, sys.argv)
