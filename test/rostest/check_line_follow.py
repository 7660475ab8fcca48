#!/usr/bin/env python3
"""rostest: line_follower keeps the base on a line world's line, scored from ground truth.

The base's distance to the course's centreline (evaluation.scoring.line_track,
the centreline the world's bitmap is drawn from: the course file beside
the world, or ~course) at every ground-truth pose. On a closed line, one
full lap (progress along the centreline, from where the robot starts, up
to the line's length): RMS and worst distance within ~max_rms and
~max_error, at a mean speed of at least ~min_speed (the issue's flat
rule, in every closed line world: each is drawn with bends that the
turn-rate limit lets a robot take at that mean, see
line_scoring.speed_bound). On an open line: the robot stops for good
within ~end_distance of the line's end, on the line all the way, and
does not move again for ~still simulated seconds. The drive guard holds every command to the limits.
Figures go to ~json when given (the benchmark reads them).
"""
import json
import sys

import numpy as np
import rospy
import rostest

from paused_world import GroundTruthRun
from waiting import wait_until
from wall_follower.evaluation.grading.line_record import still_from
from wall_follower.evaluation.scoring.line import cross_track, progress
from wall_follower.evaluation.scoring.line_track import load_centreline
from wall_follower.sim.stage_interface import world_path


class LineFollow(GroundTruthRun):

    def test_follows_the_line(self):
        self.line = load_centreline(rospy.get_param('~course', '')
                                    or world_path(rospy.get_param('~world')))
        self.wall_limit = rospy.get_param('~wall_limit', 60.0)
        self.still = rospy.get_param('~still', 3.0)
        if self.line.closed:
            figures = self._lap()
        else:
            figures = self._to_the_end()
        figures['world'] = rospy.get_param('~world')
        figures['max_linear'] = self.guard.max_linear
        figures['max_angular'] = self.guard.max_angular
        rospy.loginfo('line_follow: %s', figures)
        if rospy.get_param('~json', ''):
            with open(rospy.get_param('~json'), 'w') as out:
                json.dump(figures, out)
        self.guard.assert_safe(self)
        if self.line.closed:
            self.assertTrue(figures['lapped'], 'no full lap: %s' % figures)
        else:
            self.assertTrue(figures['stopped'], 'never stopped for %.1f s: %s' % (
                self.still, figures))
            self.assertLessEqual(figures['end_distance'], rospy.get_param('~end_distance', 0.35),
                                 figures)
        self.assertLessEqual(figures['rms'], rospy.get_param('~max_rms', 0.015), figures)
        self.assertLessEqual(figures['max'], rospy.get_param('~max_error', 0.05), figures)
        if self.line.closed:
            self.assertGreaterEqual(figures['mean_speed'], rospy.get_param('~min_speed', 0.15),
                                    figures)

    def _poses(self):
        with self.lock:
            return np.array(self.truth)

    def _lap(self):
        """Figures of the lap (or, for a robot that stopped for good short of one, of what it
        drove: the benchmark runs the lab's baseline too, which may lose the line)."""
        def lapped():
            poses = self._poses()
            return len(poses) > 1 and progress(self.line, poses[:, 1:3])[-1] >= self.line.length
        wait_until(lambda: lapped() or self._stopped_at() is not None, self.wall_limit)
        poses = self._poses()
        driven = progress(self.line, poses[:, 1:3])
        figures = {'lapped': bool(driven[-1] >= self.line.length)}
        if figures['lapped']:
            poses = poses[:int(np.argmax(driven >= self.line.length)) + 1]
        figures.update(self._scored(poses))
        figures['lap_time'] = figures['time']
        figures['mean_speed'] = min(driven[-1], self.line.length) / figures['time']
        figures['driven'] = float(driven[-1])
        return figures

    def _stopped_at(self):
        """Index of the pose from which the robot has neither moved nor turned for ~still
        simulated seconds up to the newest, or None (as the grader judges a stop)."""
        return still_from(self._poses(), self.still)

    def _to_the_end(self):
        wait_until(lambda: self._stopped_at() is not None, self.wall_limit)
        stop = self._stopped_at()
        poses = self._poses()
        figures = self._scored(poses[:(len(poses) if stop is None else stop + 1)])
        figures['stopped'] = stop is not None
        if stop is not None:
            figures['end_distance'] = self.line.distance_to_end(*poses[stop, 1:3])
            figures['stopped_for'] = poses[-1, 0] - poses[stop, 0]
        return figures

    def _scored(self, poses):
        rms, worst = cross_track(self.line, poses[:, 1:3])
        path = float(np.hypot(*np.diff(poses[:, 1:3], axis=0).T).sum())
        return {'rms': rms, 'max': worst, 'time': float(poses[-1, 0] - poses[0, 0]),
                'path_length': path}


if __name__ == '__main__':
    rospy.init_node('check_line_follow')
    rostest.rosrun('wall_follower', 'check_line_follow', LineFollow, sys.argv)
