"""wander: drive about without touching anything (exercises.wander), for as long as it runs.

Answered once per scan through the DriveLoop every driving node shares:
clamped to ~max_linear and ~max_angular, stopped while the laser is stale
or unusable, never forward into a sector ahead that it cannot see.
"""

import rospy

from wall_follower.exercises.wander import DEFAULTS as BEHAVIOUR_DEFAULTS
from wall_follower.exercises.wander import TURN, Wanderer, nearest_in_cone
from wall_follower.nodes.common import init_node, private_params
from wall_follower.nodes.exercise_loop import (LOOP_DEFAULTS, behaviour_or_exit, drive_loop,
                                               split_params)

NODE_DEFAULTS = dict(LOOP_DEFAULTS)
"""The loop's parameters (exercise_loop.LOOP_DEFAULTS); the behaviour's
(~speed, ~turn_rate, ~obstacle_distance, ~clear_distance, ~cone_half_width,
~side_reach) are exercises.wander.DEFAULTS, held to ~max_linear and ~max_angular.
"""


class WanderNode(object):

    def __init__(self):
        params = private_params(dict(BEHAVIOUR_DEFAULTS, **NODE_DEFAULTS))
        self.loop = drive_loop('wander', split_params(params, LOOP_DEFAULTS))
        self.wanderer = behaviour_or_exit('wander', Wanderer, params)

    def run(self):
        if self.wanderer is None:
            return 2
        rospy.loginfo('wander: driving about')
        self.loop.run(self._answer)
        return 0

    def _answer(self, view, _taken):
        before = self.wanderer.state
        command = self.wanderer.update(view)
        if self.wanderer.state != before:
            if self.wanderer.state == TURN:
                rospy.logdebug('wander: %.2f m ahead; turning %s', nearest_in_cone(
                    view, self.wanderer.p['cone_half_width']),
                    'left' if command.angular > 0 else 'right')
            else:
                rospy.logdebug('wander: clear ahead; forward')
        return command


def main():
    init_node('wander')
    return WanderNode().run()
