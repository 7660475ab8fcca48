#!/usr/bin/env python3
"""rostest: scans stop mid-lap; the robot stands still within 0.5 s and drives on when they return.

Judged from ground truth: no pose stamped from 0.5 s after the last scan
the gate passed on (plus the step its stop takes to act, and the steps the
scan may take to reach the follower) differs from the next, and the robot
moves again once the gate reopens.
"""
import math
import sys
import unittest

import rospy
import rostest
from drive_guard import DriveGuard
from sim_probe import SimProbe, pose_of
from std_srvs.srv import SetBool

STEP = 0.1          # the world's interval_sim [s]
STOP_WITHIN = 0.5   # [simulated s]
# The gate's scan reaches the follower on another connection: on a busy machine the
# world may step (on the follower's keepalive commands) before it is heard.
DELIVERY = 2 * STEP
PAUSE = 3.0         # [simulated s]


def moved(truths):
    """Largest distance between consecutive poses of a list of ground truth messages."""
    poses = [pose_of(msg) for msg in truths]
    return max([math.hypot(b[0] - a[0], b[1] - a[1]) for a, b in zip(poses, poses[1:])] or [0.0])


class ScanPause(unittest.TestCase):

    def test_stops_without_scans_and_resumes(self):
        guard = DriveGuard()
        probe = SimProbe()
        gate = rospy.ServiceProxy('scan_gate/set_open', SetBool)
        gate.wait_for_service(30.0)
        probe.wait_ready()
        probe.wait_for(lambda: len(probe.truths) > 30, 'the lap to start')
        start = rospy.get_time()
        probe.wait_for(lambda: moved(probe.truths_since(start)) > 0.01, 'the robot to drive')
        last_scan = float(gate(False).message)
        rospy.sleep(PAUSE)
        still = probe.truths_since(last_scan + STOP_WITHIN + STEP + DELIVERY)
        self.assertGreater(len(still), 10)
        self.assertLess(moved(still), 1e-4, 'moved while blind')
        gate(True)
        reopened = rospy.get_time()
        probe.wait_for(lambda: moved(probe.truths_since(reopened)) > 0.01,
                       'the robot to drive again')
        guard.assert_safe(self)


if __name__ == '__main__':
    rospy.init_node('check_scan_pause')
    rostest.rosrun('wall_follower', 'check_scan_pause', ScanPause, sys.argv)
