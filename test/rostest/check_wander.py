#!/usr/bin/env python3
"""rostest: wander drives about a world for ~duration simulated seconds without touching anything.

Scored from ground truth: no stalled step and a positive clearance from the
world's exact geometry at every pose, no command above the real robot's
limits, and at least ~min_path metres driven (a robot that spins or stands
is not wandering). The share of the free floor visited is reported (a
benchmark figure, not a threshold) and written to ~json when given.
"""
import json
import math
import sys

import numpy as np
import rospy
import rostest

from paused_world import GroundTruthRun
from waiting import wait_until
from wall_follower.evaluation.scoring.coverage import visited_share
from wall_follower.control.motion import MAX_ANGULAR, MAX_LINEAR
from wall_follower.evaluation.scoring.course import CourseMap
from wall_follower.sim.stage_interface import world_path
from wall_follower.sim.grid import footprint_corners

STEP = 0.1          # simulated s per step
MARGIN = 0.01       # m: clearance proven above this between the poses measured


class Wander(GroundTruthRun):

    def test_wanders_without_contact_within_the_limits(self):
        world = rospy.get_param('~world')
        duration = rospy.get_param('~duration', 300.0)
        min_path = rospy.get_param('~min_path')
        self.assertTrue(wait_until(lambda: self.truth and self.truth[-1][0] >= duration,
                                   rospy.get_param('~wall_limit', 240.0)),
                        'the simulation did not reach %.0f s' % duration)
        with self.lock:
            truth = [t for t in self.truth if t[0] <= duration]
        course = CourseMap(world_path(world))
        poses = [t[1:] for t in truth]
        clearance = min_clearance(course, poses)
        xy = np.asarray([p[:2] for p in poses])
        path = float(np.hypot(*np.diff(xy, axis=0).T).sum())
        share = visited_share(course, poses)
        figures = {'world': world, 'duration': truth[-1][0] - truth[0][0], 'path_length': path,
                   'visited_share': share, 'min_clearance': clearance,
                   'max_linear': self.guard.max_linear, 'max_angular': self.guard.max_angular,
                   'contact': self.guard.touched_at is not None or clearance <= 0.0}
        rospy.loginfo('wander %s: %s', world, figures)
        if rospy.get_param('~json', ''):
            with open(rospy.get_param('~json'), 'w') as out:
                json.dump(figures, out)
        self.guard.assert_safe(self)
        self.assertGreater(clearance, 0.0, 'touched an obstacle')
        self.assertGreater(path, min_path, 'drove only %.1f m' % path)


def min_clearance(course, poses):
    """The smallest clearance measured along the poses, measuring only where it could be small.

    Within the limits (which the guard holds), a footprint corner moves at
    most CORNER_STEP per step, and the clearance changes no faster: after a
    pose with clearance c, the next (c - MARGIN) / CORNER_STEP poses are
    proven clear by more than MARGIN without casting them (casting every one
    of 3000 poses against a bitmap's edges takes seconds).
    """
    reach = max(math.hypot(x, y) for x, y in footprint_corners(course.robot, (0.0, 0.0, 0.0)))
    corner_step = (MAX_LINEAR + MAX_ANGULAR * reach) * STEP
    lowest, index = math.inf, 0
    while index < len(poses):
        clearance = course.clearance(poses[index])
        lowest = min(lowest, clearance)
        index += max(1, int((clearance - MARGIN) / corner_step))
    return lowest


if __name__ == '__main__':
    rospy.init_node('check_wander')
    rostest.rosrun('wall_follower', 'check_wander', Wander, sys.argv)
