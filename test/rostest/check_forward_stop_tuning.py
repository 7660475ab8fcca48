#!/usr/bin/env python3
"""rostest: forward_stop's periods set through dynamic_reconfigure mid-run are the robot's.

Two cycles into the run, this node sets ~forward_period and ~stop_period on
/forward_stop with dynamic_reconfigure's client (what `dynparam set` does).
Scored from ground truth (check_forward_stop.moving_stretches): the first
two cycles must last the periods of the launch file, and the last whole
cycles of the run the new ones, each stretch to within one scan period.
The stretches around the change are not scored: the change takes effect
at the node's next scan, and starts a new cycle there.
"""
import sys

import rospy
import rostest
from dynamic_reconfigure.client import Client

from check_forward_stop import SCAN_PERIOD, SLACK, moving_stretches
from paused_world import GroundTruthRun
from waiting import wait_until

NEW_FORWARD = 1.5       # s
NEW_STOP = 0.5          # s
SCORED_CYCLES = 2       # at each end of the run
RUN_AFTER = 9.0         # simulated s after the change: four new cycles and a half
WALL_LIMIT = 60.0       # wall s, for any one wait


class ForwardStopTuning(GroundTruthRun):

    def _latest(self):
        with self.lock:
            return self.truth[-1][0] if self.truth else -1.0

    def _stretches(self):
        with self.lock:
            stretches = moving_stretches(self.truth)
        while stretches and not stretches[0][0]:
            stretches.pop(0)           # standing before the first command
        return stretches

    def assert_periods(self, stretches, forward, stop):
        for moving, duration in stretches:
            expected = forward if moving else stop
            self.assertLessEqual(abs(duration - expected), SCAN_PERIOD + SLACK,
                                 '%s for %.1f s, not %.1f s (stretches %s)' % (
                                     'moved' if moving else 'stood', duration, expected,
                                     stretches))

    def test_new_periods_set_live_are_the_robots(self):
        forward = rospy.get_param('~forward_period')
        stop = rospy.get_param('~stop_period')
        client = Client('forward_stop', timeout=WALL_LIMIT)
        self.assertTrue(wait_until(lambda: len(self._stretches()) > 2 * SCORED_CYCLES,
                                   WALL_LIMIT), 'fewer than %d cycles' % SCORED_CYCLES)
        applied = client.update_configuration({'forward_period': NEW_FORWARD,
                                               'stop_period': NEW_STOP})
        self.assertEqual((applied['forward_period'], applied['stop_period']),
                         (NEW_FORWARD, NEW_STOP))
        changed = self._latest()
        self.assertTrue(wait_until(lambda: self._latest() >= changed + RUN_AFTER, WALL_LIMIT),
                        'ground truth stopped')
        stretches = self._stretches()
        rospy.loginfo('forward_stop tuning: (moving, duration) stretches %s, periods changed '
                      'at %.1f s', stretches, changed)
        self.assert_periods(stretches[:2 * SCORED_CYCLES], forward, stop)
        # the last stretch is still going on when the run is scored
        self.assert_periods(stretches[-1 - 2 * SCORED_CYCLES:-1], NEW_FORWARD, NEW_STOP)
        self.guard.assert_safe(self)


if __name__ == '__main__':
    rospy.init_node('check_forward_stop_tuning')
    rostest.rosrun('wall_follower', 'check_forward_stop_tuning', ForwardStopTuning, sys.argv)
