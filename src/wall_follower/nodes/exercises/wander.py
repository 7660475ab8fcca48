"""wander: drive about without touching anything (exercises.wander), for as long as it runs.

Answered once per scan through the DriveLoop every driving node shares:
clamped to ~max_linear and ~max_angular, stopped while the laser is stale
or unusable, never forward into a sector ahead that it cannot see. It
warns while it turns because nothing ahead reads valid. Its
parameters (params/exercises/wander.py) are tuned live: a change is applied at the
next scan.
"""
import math

import rospy

from wall_follower.cfg import WanderConfig
from wall_follower.exercises.wander import TURN, Wanderer, nearest_in_cone
from wall_follower.nodes.shared.drive_loop import drive_loop, take_retuned
from wall_follower.nodes.shared.latest_scan import LatestScan
from wall_follower.nodes.shared.parameters import NodeParameters
from wall_follower.nodes.shared.startup import init_node
from wall_follower.params import pick
from wall_follower.params.exercises.wander import RULES, TABLE, WANDER


class WanderNode(object):

    def __init__(self):
        self.params = NodeParameters(TABLE, WanderConfig, rules=RULES)
        values = self.params.snapshot()
        self.loop = drive_loop('wander', values, LatestScan('scan'))
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
        half_width = self.wanderer.p['cone_half_width']
        nearest = nearest_in_cone(view, half_width)
        turning = 'left' if command.angular > 0 else 'right'
        if self.wanderer.state == TURN and nearest == 0.0:
            self.loop.warn('no valid reading within %.0f deg ahead; turning %s until there is'
                           % (math.degrees(half_width), turning))
        elif self.wanderer.state != before:
            if self.wanderer.state == TURN:
                rospy.logdebug('wander: %.2f m ahead; turning %s', nearest, turning)
            else:
                rospy.logdebug('wander: clear ahead; forward')
        return command


def main():
    init_node('wander')
    return WanderNode().run()
