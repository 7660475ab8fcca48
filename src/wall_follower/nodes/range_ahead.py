"""range_ahead: print the distance straight ahead, found by angle, or say plainly why there is none.

The lab's experiment 2 (exercises.range_ahead). Scans come through the
LatestScan reader and check_scan validator that every node uses; a stale or
unusable scan is reported as such rather than read. Lines are logged (to the
screen and /rosout) at most once per ~period of ROS time.
"""
import math

import rospy

from wall_follower.exercises.range_ahead import describe, range_ahead
from wall_follower.nodes.common import LatestScan, init_node, private_params

NODE_DEFAULTS = {
    'half_width': math.radians(5.0),
    'period': 0.5,
    'scan_timeout': 1.0,
}
"""half_width: the window either side of straight ahead [rad] whose valid
    readings' median is the answer.
period: print at most once per this many ROS seconds (0: every scan).
scan_timeout: say so when no scan has come for this long (ROS s).
"""

WAIT = 0.1   # wall s between looks at the clock while no scan comes


def main():
    init_node('range_ahead')
    params = private_params(NODE_DEFAULTS)
    scan = LatestScan('scan')
    seen, printed, warned = None, -math.inf, rospy.get_time()
    while not rospy.is_shutdown():
        reading = scan.latest(params['scan_timeout'])
        now = rospy.get_time()
        if now < printed or now < warned:
            printed, warned = -math.inf, now      # ROS time moved back
        fresh, seen = reading.check is not seen, reading.check
        if reading.view is not None and fresh and now - printed >= params['period']:
            printed = now
            rospy.loginfo(describe(range_ahead(reading.view, params['half_width']),
                                   params['half_width'], reading.view.range_max))
        elif reading.view is None and (fresh or now - warned >= params['scan_timeout']):
            warned = now
            rospy.logwarn('range_ahead: %s', reading.problem)
        scan.wait_for_newer(seen, WAIT)
    return 0
