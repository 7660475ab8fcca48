#!/usr/bin/env python3
"""rostest: ROS time moving back leaves the follower and the finder working.

The test is the clock: it publishes /clock and a scan of a wall on the
right every simulated 0.1 s, for the follower and (in its own namespace)
for the finder, lets the follower drive, then sets the clock back. Both
nodes must warn once that time moved back, the follower must drive on the
scans of the new clock, and the finder must still answer a call.
"""
import sys
import threading
import time
import unittest

import rosgraph
import rospy
import rostest
from geometry_msgs.msg import Twist
from rosgraph_msgs.msg import Clock
from rosout_log import RosoutLog
from sensor_msgs.msg import LaserScan
from synthetic_scans import wall_on_the_right

from wall_follower.params import defaults
from wall_follower.params.course.wall_finder import FINDER
from wall_follower.srv import FindWall
from waiting import assert_soon, wait_until

STEP = 0.1         # simulated s per tick
TICK = 0.02        # wall s per tick
START = 100.0      # simulated s
JUMP_BACK = 40.0   # simulated s
WAIT_LIMIT = 30.0  # wall s


class TestClock(object):
    """Publishes /clock and scans, one tick at a time, until shut down."""

    def __init__(self):
        self.now = START
        self.ticks = 0
        self.lock = threading.Lock()
        self.clock = rospy.Publisher('/clock', Clock, queue_size=10)
        self.scans = [(rospy.Publisher('scan', LaserScan, queue_size=1), wall_on_the_right()),
                      (rospy.Publisher('finder/scan', LaserScan, queue_size=1),
                       wall_on_the_right(defaults(FINDER)['wall_distance']))]
        threading.Thread(target=self._run, daemon=True).start()

    def jump_to(self, when):
        with self.lock:
            self.now = when

    def heard_by_all(self):
        """Whether every node that subscribes /clock is connected, and a tick has gone
        out since: each then has this clock's time before any jump (one connection
        delivers in order), not the 0 of a clock it has not heard yet."""
        _, subscribers, _ = rosgraph.Master(rospy.get_name()).getSystemState()
        listeners = next((len(nodes) for topic, nodes in subscribers if topic == '/clock'), 0)
        if self.clock.get_num_connections() < listeners:
            return False
        ticks = self.ticks
        return wait_until(lambda: self.ticks > ticks, WAIT_LIMIT)

    def _run(self):
        while not rospy.core.is_shutdown():
            with self.lock:
                self.now += STEP
                stamp = rospy.Time.from_sec(self.now)
            self.clock.publish(Clock(clock=stamp))
            self.ticks += 1
            for publisher, scan in self.scans:
                scan.header.stamp = stamp
                publisher.publish(scan)
            time.sleep(TICK)


class ClockJump(unittest.TestCase):

    def test_both_nodes_carry_on_after_time_moves_back(self):
        log, commands = RosoutLog('/wall_following', '/finder/wall_finder'), []
        rospy.Subscriber('cmd_vel', Twist, lambda msg: commands.append(msg.linear.x),
                         queue_size=1000)
        clock = TestClock()
        assert_soon(self, WAIT_LIMIT, clock.heard_by_all, 'every node to hear the clock')
        after = len(commands)
        assert_soon(self, WAIT_LIMIT, lambda: any(v > 0.1 for v in commands[after:]),
                    'the follower to drive')
        clock.jump_to(START - JUMP_BACK)
        assert_soon(self, WAIT_LIMIT, lambda: log.said('/wall_following', 'ROS time moved back'),
                    'the follower to warn')
        after = len(commands)
        assert_soon(self, WAIT_LIMIT, lambda: sum(v > 0.1 for v in commands[after:]) >= 10,
                    'the follower to drive on the new clock')
        rospy.wait_for_service('finder/find_wall', WAIT_LIMIT)
        self.assertTrue(rospy.ServiceProxy('finder/find_wall', FindWall)().wallfound)
        clock.jump_to(START - 2.0 * JUMP_BACK)
        self.assertTrue(rospy.ServiceProxy('finder/find_wall', FindWall)().wallfound)
        warnings = log.lines('/wall_following', 'ROS time moved back')
        self.assertLessEqual(len(warnings), 2, 'one warning per jump')


if __name__ == '__main__':
    rospy.init_node('check_clock_jump')
    rostest.rosrun('wall_follower', 'check_clock_jump', ClockJump, sys.argv)
