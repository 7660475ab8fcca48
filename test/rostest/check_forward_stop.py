#!/usr/bin/env python3
"""rostest: forward_stop moves and stands for its periods, and stands short of a wall ahead.

Scored from ground truth: a step in which the robot moved counts as moving.
The first ~cycles moving and standing stretches must last ~forward_period
and ~stop_period to within one scan period (the first may be shorter: it
starts with the node's first command, which the world does not wait for);
the robot then comes up to a wall and must stand, with the laser no nearer
to the wall ahead than ~stop_distance less one step of travel (the command
answering a scan acts on the next step) and two grid cells (Stage's
cell-stepping raytrace reads a wall up to a cell nearer, and the cells of
the wall itself), without touching it.
"""
import math
import sys

import rospy
import rostest

from paused_world import GroundTruthRun
from waiting import wait_until
from wall_follower.evaluation.scoring.geometry import cast_rays
from wall_follower.evaluation.scoring.course import CourseMap
from wall_follower.sim.stage_interface import world_path

STILL = 1e-5          # m per step: below this the robot stands
SCAN_PERIOD = 0.1     # s, one simulated step
SLACK = 1e-6
WALL_LIMIT = 120.0
CELL = 0.02           # the simulator's grid


class ForwardStopRun(GroundTruthRun):

    def test_periods_and_the_stop_before_the_wall(self):
        forward = rospy.get_param('~forward_period')
        stop = rospy.get_param('~stop_period')
        cycles = rospy.get_param('~cycles')
        stop_distance = rospy.get_param('~stop_distance')
        run_time = rospy.get_param('~run_time')
        self.assertTrue(wait_until(lambda: self.truth and self.truth[-1][0] >= run_time,
                                   WALL_LIMIT), 'the simulation did not reach %.0f s' % run_time)
        with self.lock:
            truth = list(self.truth)
        stretches = moving_stretches(truth)
        rospy.loginfo('forward_stop: (moving, duration) stretches %s', stretches)
        while stretches and not stretches[0][0]:
            stretches.pop(0)           # standing before the first command
        assert_periods(self, stretches[:2 * cycles], forward, stop, first_command=True)
        self.assertGreater(len(stretches), 2 * cycles, 'fewer than %d cycles' % cycles)
        course = CourseMap(world_path(rospy.get_param('~world')))
        lx, ly, lyaw = course.laser_pose(truth[-1][1:])
        ahead = cast_rays(course.edges, lx, ly, [lyaw])[0]
        self.assertFalse(stretches[-1][0], 'still moving at the end')
        self.assertGreaterEqual(ahead, stop_distance - 0.19 * SCAN_PERIOD - 2 * CELL)
        self.assertLess(ahead, stop_distance + 0.19 * SCAN_PERIOD + CELL,
                        'stood %.2f m from the wall: not stopped by it' % ahead)
        self.guard.assert_safe(self)


def assert_periods(test, stretches, forward, stop, first_command=False):
    """Fail test (a unittest.TestCase) unless each (moving, duration) of stretches lasts
    forward (moving) or stop (standing) to within one scan period.

    first_command: the first stretch began with the node's first command, which lockstep
    does not wait for (a robot not yet driven is given only the simulator's grace), so on
    a busy machine the world steps on before it comes: that stretch may be shorter.
    """
    for index, (moving, duration) in enumerate(stretches):
        expected = forward if moving else stop
        error = duration - expected
        if first_command and index == 0:
            error = max(0.0, error)
        test.assertLessEqual(abs(error), SCAN_PERIOD + SLACK, '%s for %.1f s, not %.1f s '
                             '(stretches %s)' % ('moved' if moving else 'stood', duration,
                                                 expected, stretches))


def moving_stretches(truth):
    """[(moving, duration s)] of the runs of ground-truth steps with and without motion."""
    stretches = []
    for (ta, xa, ya, _), (tb, xb, yb, _) in zip(truth, truth[1:]):
        moving = math.hypot(xb - xa, yb - ya) > STILL
        if stretches and stretches[-1][0] == moving:
            stretches[-1][1] += tb - ta
        else:
            stretches.append([moving, tb - ta])
    return [(moving, round(duration, 6)) for moving, duration in stretches]


if __name__ == '__main__':
    rospy.init_node('check_forward_stop')
    rostest.rosrun('wall_follower', 'check_forward_stop', ForwardStopRun, sys.argv)
