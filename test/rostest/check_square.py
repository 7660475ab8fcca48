#!/usr/bin/env python3
"""rostest: simple_move_square drives a true square, scored from ground truth.

The corners are where the robot stands and pivots (ground truth); each must
lie within ~tolerance of the ideal square laid out from the start pose
~start ("x y yaw_deg", where the simulator puts the robot): side ~side,
first side straight ahead, turning left. The final heading must be within
~heading_tolerance_deg of the start. The square has ended when the
robot has pivoted at laps x 4 corners and then stood still for SETTLE
simulated seconds.
"""
import math
import sys

import rospy
import rostest

from paused_world import GroundTruthRun
from waiting import wait_until
from wall_follower.rotation import wrap_angle

STILL = 1e-5          # m per step: below this the robot stands
TURNING = 1e-4        # rad per step: above this it turns
WALL_LIMIT = 120.0    # wall s for the whole square
SETTLE = 2.0          # simulated s standing after the last corner


class Square(GroundTruthRun):

    def ended(self, corners):
        """The truth so far once laps x 4 corners are turned and the robot has stood SETTLE s."""
        with self.lock:
            truth = list(self.truth)
        if len(pivots(truth)) < corners or not truth:
            return None
        last = truth[-1]
        settled = [t for t in truth if t[0] >= last[0] - SETTLE]
        if last[0] - truth[0][0] < SETTLE or any(
                math.hypot(t[1] - last[1], t[2] - last[2]) > STILL or abs(t[3] - last[3]) > TURNING
                for t in settled):
            return None
        return truth

    def test_corners_on_the_true_square_and_heading_back_at_the_start(self):
        side = rospy.get_param('~side', 0.5)
        laps = rospy.get_param('~laps', 1)
        tolerance = rospy.get_param('~tolerance', 0.03)
        heading_tolerance = math.radians(rospy.get_param('~heading_tolerance_deg', 3.0))
        truth = wait_until(lambda: self.ended(4 * laps), WALL_LIMIT)
        if not truth:
            with self.lock:
                truth = list(self.truth)
            self.fail('the square never ended: %d pivots in %d poses, the last %r'
                      % (len(pivots(truth)), len(truth), truth[-3:]))
        x0, y0, yaw0 = (float(v) for v in rospy.get_param('~start').split())
        yaw0 = math.radians(yaw0)
        corners = pivots(truth)
        rospy.loginfo('square: start (%.3f, %.3f, %.1f deg); pivots at %s', x0, y0,
                      math.degrees(yaw0), ['(%.3f, %.3f)' % c for c in corners])
        self.assertEqual(len(corners), 4 * laps)
        ideal = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
        for k, (cx, cy) in enumerate(corners):
            px, py = ideal[(k + 1) % 4]
            ix = x0 + side * (px * math.cos(yaw0) - py * math.sin(yaw0))
            iy = y0 + side * (px * math.sin(yaw0) + py * math.cos(yaw0))
            error = math.hypot(cx - ix, cy - iy)
            self.assertLess(error, tolerance,
                            'corner %d is %.3f m off the true square' % (k + 1, error))
        heading_error = abs(float(wrap_angle(truth[-1][3] - yaw0)))
        self.assertLess(heading_error, heading_tolerance,
                        'final heading %.2f deg off the start' % math.degrees(heading_error))
        self.guard.assert_safe(self)


def pivots(truth):
    """The mean position of each run of ground-truth steps where the robot turned on the spot."""
    runs, current = [], []
    for (_, xa, ya, ta), (_, xb, yb, tb) in zip(truth, truth[1:]):
        turning = math.hypot(xb - xa, yb - ya) < STILL and abs(float(wrap_angle(tb - ta))) > TURNING
        if turning:
            current.append((xb, yb))
        elif current:
            runs.append(current)
            current = []
    if current:
        runs.append(current)
    return [(sum(p[0] for p in run) / len(run), sum(p[1] for p in run) / len(run)) for run in runs]


if __name__ == '__main__':
    rospy.init_node('check_square')
    rostest.rosrun('wall_follower', 'check_square', Square, sys.argv)
