#!/usr/bin/env python3
"""rostest: wander and forward_stop do not drive forward on a scan with one valid beam.

A scan whose only valid reading is 3.0 m at 29 deg left (the other 359
NaN) is no view of the way ahead: each node must send commands without
forward motion for WATCH wall seconds and warn naming what is wrong. The
follower gets the same scan in bad_scans.test. In wall time, with
synthetic scans.
"""
import sys
import threading
import time
import unittest

import rospy
import rostest
from geometry_msgs.msg import Twist
from rosout_log import RosoutLog
from sensor_msgs.msg import LaserScan
from synthetic_scans import one_valid_beam

from waiting import assert_soon

SCAN_PERIOD = 0.1
WATCH = 3.0          # wall s of commands to look at
WAIT_LIMIT = 10.0
NODES = ('/wander/wander', '/forward_stop/forward_stop')


class OneBeam(unittest.TestCase):

    def test_no_forward_motion_and_a_warning(self):
        log = RosoutLog(*NODES)
        lock, commands = threading.Lock(), dict((node, []) for node in NODES)
        publishers = []
        for node in NODES:
            namespace = node.rsplit('/', 1)[0]

            def on_cmd(msg, node=node):
                with lock:
                    commands[node].append((msg.linear.x, msg.angular.z))
            rospy.Subscriber(namespace + '/cmd_vel', Twist, on_cmd, queue_size=1000)
            publishers.append(rospy.Publisher(namespace + '/scan', LaserScan, queue_size=1))
        assert_soon(self, WAIT_LIMIT, lambda: all(p.get_num_connections() for p in publishers),
                    'the nodes to subscribe')
        scan = one_valid_beam()
        end = time.monotonic() + WATCH
        while time.monotonic() < end:
            scan.header.stamp = rospy.Time.now()
            for publisher in publishers:
                publisher.publish(scan)
            time.sleep(SCAN_PERIOD)
        for node in NODES:
            with lock:
                sent = list(commands[node])
            self.assertTrue(sent, '%s sent nothing' % node)
            self.assertEqual([v for v, _ in sent if v > 0.0], [], '%s drove forward' % node)
            assert_soon(self, WAIT_LIMIT, lambda: log.said(
                node, 'only 1 of its 360 readings is usable (359 NaN)'),
                '%s to warn of the scan' % node)


if __name__ == '__main__':
    rospy.init_node('check_one_beam')
    rostest.rosrun('wall_follower', 'check_one_beam', OneBeam, sys.argv)
