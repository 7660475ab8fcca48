"""wander: drive about without touching anything (exercises.wander), for as long as it runs.

Answered once per scan through the DriveLoop every driving node shares:
clamped to ~max_linear and ~max_angular, stopped while the laser is stale
or unusable, never forward into a sector ahead that it cannot see. Its
parameters (params/wander.py) are tuned live: a change is applied at the
next scan.
"""

import rospy

from wall_follower.cfg import WanderConfig
from wall_follower.exercises.wander import TURN, Wanderer, nearest_in_cone
from wall_follower.nodes.common import init_node
from wall_follower.nodes.parameters import NodeParameters, drive_loop, take_retuned
from wall_follower.params import pick
from wall_follower.params.wander import RULES, TABLE, WANDER


class WanderNode(object):

    def __init__(self):
        self.params = NodeParameters(TABLE, WanderConfig, rules=RULES)
        values = self.params.snapshot()
        self.loop = drive_loop('wander', values)
        self.wanderer = Wanderer(**pick(values, WANDER))

    def run(self):
        rospy.loginfo('wander: driving about')
        self.loop.run(self._answer)
        return 0

    def _answer(self, view, _taken):
        values = take_retuned(self.params, self.loop)
        if values is not None:
            self.wanderer.reconfigure(**pick(values, WANDER))
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
