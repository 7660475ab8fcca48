#!/usr/bin/env python3
"""rostest: forward_stop's periods set through dynamic_reconfigure mid-run are the robot's.

Two cycles into the run, this node holds the world (pause_physics), puts the robot back
at its start (reset_positions), sets ~forward_period and ~stop_period on /forward_stop
with dynamic_reconfigure's client (what `dynparam set` does) and lets the world go on.
Scored from ground truth (check_forward_stop.moving_stretches), split at the reset (the
one step longer than a drive can make): the first two cycles before it must last the
periods of the launch file, and every whole stretch after it the new ones, each to within
one scan period. The first stretch after the reset is not scored: the change takes
effect at the node's next scan, and starts a new cycle there. The very first may be
shorter: it starts with the node's first command, which the world does not wait for.

Why the world is held for the change: in lockstep at speedup 0 the world steps as soon
as the node has answered, tens of times faster than real time, and waits for nobody
else. A change made while it runs lands as late as this node is slow to see the cycles
and to call the node: on a busy machine, many simulated seconds late, by when the robot
stood at the wall ahead, and the "new cycles" were a robot blocked by it ("moved for
0.2 s, not 1.5 s"). Held, the change lands at the step where the world stopped, and the
reset gives the new cycles the same room however late that step came.
"""
import math
import sys

import rospy
import rostest
from dynamic_reconfigure.client import Client
from std_srvs.srv import Empty

from check_forward_stop import assert_periods, moving_stretches
from paused_world import GroundTruthRun
from waiting import wait_until

NEW_FORWARD = 1.5       # s
NEW_STOP = 0.5          # s
SCORED_CYCLES = 2       # at least, before the change and after it
RUN_AFTER = 9.0         # simulated s after the reset: four new cycles and a half
WALL_LIMIT = 60.0       # wall s, for any one wait
JUMP = 0.1              # m in one step: the reset (a drive makes 0.026 m at most)


def split_at_reset(truth):
    """(before, after): the ground truth up to the reset's jump, and from it on; after is
    empty while no step has jumped."""
    for index in range(1, len(truth)):
        (_, xa, ya, _), (_, xb, yb, _) = truth[index - 1], truth[index]
        if math.hypot(xb - xa, yb - ya) > JUMP:
            return truth[:index], truth[index:]
    return truth, []


def cycling(truth):
    """moving_stretches of truth, without the standing before the first command."""
    stretches = moving_stretches(truth)
    while stretches and not stretches[0][0]:
        stretches.pop(0)
    return stretches


class ForwardStopTuning(GroundTruthRun):

    def _truth(self):
        with self.lock:
            return list(self.truth)

    def _run_after_reset(self):
        """Simulated seconds of ground truth since the reset (0 before it)."""
        after = split_at_reset(self._truth())[1]
        return after[-1][0] - after[0][0] if after else 0.0

    def test_new_periods_set_live_are_the_robots(self):
        forward = rospy.get_param('~forward_period')
        stop = rospy.get_param('~stop_period')
        client = Client('forward_stop', timeout=WALL_LIMIT)
        world = {}
        for name in ('pause_physics', 'reset_positions', 'unpause_physics'):
            rospy.wait_for_service(name, timeout=WALL_LIMIT)
            world[name] = rospy.ServiceProxy(name, Empty)
        self.assertTrue(wait_until(lambda: len(cycling(self._truth())) > 2 * SCORED_CYCLES,
                                   WALL_LIMIT), 'fewer than %d cycles' % SCORED_CYCLES)
        world['pause_physics']()
        world['reset_positions']()
        applied = client.update_configuration({'forward_period': NEW_FORWARD,
                                               'stop_period': NEW_STOP})
        self.assertEqual((applied['forward_period'], applied['stop_period']),
                         (NEW_FORWARD, NEW_STOP))
        world['unpause_physics']()
        self.assertTrue(wait_until(lambda: self._run_after_reset() >= RUN_AFTER, WALL_LIMIT),
                        'ground truth stopped, or the reset never showed on it')
        before, after = split_at_reset(self._truth())
        old, new = cycling(before), moving_stretches(after)
        rospy.loginfo('forward_stop tuning: (moving, duration) stretches %s before the change '
                      'at %.1f s, %s after it', old, after[0][0], new)
        assert_periods(self, old[:2 * SCORED_CYCLES], forward, stop, first_command=True)
        # the first stretch began with the change; the last is still going on
        scored = new[1:-1]
        self.assertGreaterEqual(len(scored), 2 * SCORED_CYCLES, 'stretches %s' % new)
        assert_periods(self, scored, NEW_FORWARD, NEW_STOP)
        self.guard.assert_safe(self)


if __name__ == '__main__':
    rospy.init_node('check_forward_stop_tuning')
    rostest.rosrun('wall_follower', 'check_forward_stop_tuning', ForwardStopTuning, sys.argv)
