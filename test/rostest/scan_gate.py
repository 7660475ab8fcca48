#!/usr/bin/env python3
"""A test relay: forwards scan to gated_scan while open; ~set_open (std_srvs/SetBool) opens and
closes it, answering with the time the last scan it forwarded was taken (its stamp as it came).
On opening it reads ~stamp (s, default 0): other than 0, every scan it forwards carries that
stamp for its own.

The stamp, not this node's clock at forwarding: on a busy machine its /clock comes in on
another connection than the scans, and lags the scan it forwards by up to a few world steps,
which would date the last scan early and have a check wait for a stop that soon."""
import threading

import rospy
from sensor_msgs.msg import LaserScan
from std_srvs.srv import SetBool, SetBoolResponse


class ScanGate(object):

    def __init__(self):
        self.lock = threading.Lock()
        self.open = True
        self.stamp = None
        self.last_forwarded = 0.0
        self.publisher = rospy.Publisher('gated_scan', LaserScan, queue_size=1)
        rospy.Subscriber('scan', LaserScan, self.on_scan, queue_size=1)
        rospy.Service('~set_open', SetBool, self.set_open)

    def on_scan(self, msg):
        with self.lock:
            if self.open:
                taken = msg.header.stamp.to_sec()
                if self.stamp is not None:
                    msg.header.stamp = self.stamp
                self.publisher.publish(msg)
                self.last_forwarded = taken

    def set_open(self, request):
        with self.lock:
            self.open = request.data
            if self.open:
                stamp = rospy.get_param('~stamp', 0.0)
                self.stamp = rospy.Time.from_sec(stamp) if stamp else None
            return SetBoolResponse(True, repr(self.last_forwarded))


if __name__ == '__main__':
    rospy.init_node('scan_gate')
    ScanGate()
    rospy.spin()
