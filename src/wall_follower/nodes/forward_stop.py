"""forward_stop: drive forward for ~forward_period, stand for ~stop_period, and so on.

The lab's experiment 1 (exercises.forward_stop), answered once per scan
through the DriveLoop every driving node shares: its phases are timed on
the scans' stamps, the command is re-sent all through a phase (Stage's
0.2 s watchdog would otherwise end a forward phase at once), and a forward
phase stands while something is nearer straight ahead than ~stop_distance.
"""
import rospy

from wall_follower.exercises.forward_stop import BLOCKED
from wall_follower.exercises.forward_stop import DEFAULTS as BEHAVIOUR_DEFAULTS
from wall_follower.exercises.forward_stop import ForwardStop, nearest_ahead
from wall_follower.nodes.common import init_node, private_params
from wall_follower.nodes.exercise_loop import (LOOP_DEFAULTS, behaviour_or_exit, drive_loop,
                                               split_params)

NODE_DEFAULTS = dict(LOOP_DEFAULTS)
"""The loop's parameters (exercise_loop.LOOP_DEFAULTS); the behaviour's
(~forward_period, ~stop_period, ~speed, ~stop_distance, ~cone_half_width)
are exercises.forward_stop.DEFAULTS. ~speed is held to ~max_linear.
"""


class ForwardStopNode(object):

    def __init__(self):
        params = private_params(dict(BEHAVIOUR_DEFAULTS, **NODE_DEFAULTS))
        self.loop = drive_loop('forward_stop', split_params(params, LOOP_DEFAULTS))
        self.behaviour = behaviour_or_exit('forward_stop', ForwardStop, params)
        self.state = None

    def run(self):
        if self.behaviour is None:
            return 2
        self.loop.run(self._answer, on_clock_reset=self.behaviour.restart)
        return 0

    def _answer(self, view, taken):
        command = self.behaviour.update(view, taken)
        state = self.behaviour.state
        if state != self.state:
            if state == BLOCKED:
                rospy.logwarn('forward_stop: something %.2f m ahead (~stop_distance %.2f); '
                              'standing', nearest_ahead(view, self.behaviour.p['cone_half_width']),
                              self.behaviour.p['stop_distance'])
            else:
                rospy.loginfo('forward_stop: %s at %.1f s', state.lower(), taken)
            self.state = state
        return command


def main():
    init_node('forward_stop')
    return ForwardStopNode().run()
