"""forward_stop: drive forward for ~forward_period, stand for ~stop_period, and so on.

The lab's experiment 1 (exercises.forward_stop), answered once per scan
through the DriveLoop every driving node shares: its phases are timed on
the scans' stamps, the command is re-sent all through a phase (Stage's
0.2 s watchdog would otherwise end a forward phase at once), and a forward
phase stands while something is nearer straight ahead than ~stop_distance.
Scan stamps that go back (a laser's clock reset, a bag looped) are warned
of and start the cycle afresh.
Its parameters (params/exercises/forward_stop.py) are tuned live: a change is
applied at the next scan, and new periods start a new cycle there.
"""
import rospy

from wall_follower.cfg import ForwardStopConfig
from wall_follower.exercises.forward_stop import BLOCKED, ForwardStop, nearest_ahead
from wall_follower.nodes.shared.drive_loop import drive_loop, take_retuned
from wall_follower.nodes.shared.latest_scan import LatestScan
from wall_follower.nodes.shared.parameters import NodeParameters
from wall_follower.nodes.shared.startup import init_node
from wall_follower.params import pick
from wall_follower.params.exercises.forward_stop import FORWARD_STOP, TABLE


class ForwardStopNode(object):

    def __init__(self):
        self.params = NodeParameters(TABLE, ForwardStopConfig)
        values = self.params.snapshot()
        self.loop = drive_loop('forward_stop', values, LatestScan('scan'))
        self.behaviour = ForwardStop(**pick(values, FORWARD_STOP))
        self.state = None
        self.taken = None   # stamp of the last scan answered [s]

    def run(self):
        self.loop.run(self._answer, on_clock_reset=self.behaviour.restart)
        return 0

    def _answer(self, view, taken):
        values = take_retuned(self.params, self.loop)
        if values is not None:
            self.behaviour.reconfigure(**pick(values, FORWARD_STOP))
        if self.taken is not None and taken < self.taken:
            rospy.logwarn('forward_stop: scan stamps went back from %.2f s to %.2f s; the '
                          'cycle starts afresh', self.taken, taken)
            self.behaviour.restart()
        self.taken = taken
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
