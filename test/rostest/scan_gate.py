#!/usr/bin/env python3
"""A test relay: forwards scan to gated_scan while open; ~set_open (std_srvs/SetBool) opens and
closes it, answering with the ROS time of the last scan it forwarded. On opening it reads
~stamp (s, default 0): other than 0, every scan it forwards carries that stamp for its own."""
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
                if self.stamp is not None:
                    msg.header.stamp = self.stamp
                self.publisher.publish(msg)
                self.last_forwarded = rospy.get_time()

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
