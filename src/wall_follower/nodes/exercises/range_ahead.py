"""range_ahead: print the distance straight ahead, found by angle, or say plainly why there is none.

The lab's experiment 2 (exercises.range_ahead). Scans come through the
LatestScan reader and check_scan validator that every node uses; a stale or
unusable scan is reported as such rather than read. Lines are logged (to the
screen and /rosout) at most once per ~period of ROS time: a warning when it
is new, then again at that period while it lasts (with no scan coming, once
per ~scan_timeout). Its parameters
(params/exercises/range_ahead.py) are tuned live, from the next pass on.
"""
import math

import rospy

from wall_follower.cfg import RangeAheadConfig
from wall_follower.exercises.range_ahead import describe, range_ahead
from wall_follower.nodes.shared.latest_scan import LatestScan
from wall_follower.nodes.shared.parameters import NodeParameters
from wall_follower.nodes.shared.startup import init_node
from wall_follower.params.exercises.range_ahead import TABLE

WAIT = 0.1   # wall s between looks at the clock while no scan comes


def main():
    init_node('range_ahead')
    params = NodeParameters(TABLE, RangeAheadConfig)
    values = params.snapshot()
    scan = LatestScan('scan')
    seen, printed, warned, problem = None, -math.inf, rospy.get_time(), None
    while not rospy.is_shutdown():
        values = params.take_update() or values
        reading = scan.latest(values['scan_timeout'])
        now = rospy.get_time()
        if now < printed or now < warned:
            printed, warned = -math.inf, now      # ROS time moved back
        fresh, seen = reading.check is not seen, reading.check
        if reading.view is not None and fresh and now - printed >= values['period']:
            printed = now
            rospy.loginfo(describe(range_ahead(reading.view, values['half_width']),
                                   values['half_width'], reading.view.range_max))
        elif reading.view is None and (reading.problem != problem or (
                now - warned >= values['period']
                and (fresh or now - warned >= values['scan_timeout']))):
            warned, problem = now, reading.problem
            rospy.logwarn('range_ahead: %s', reading.problem)
        scan.wait_for_newer(seen, WAIT)
    return 0
