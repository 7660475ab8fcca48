#!/usr/bin/env python3
"""A test relay: forwards scan to gated_scan while open; ~set_open (std_srvs/SetBool) opens and
closes it, answering with the ROS time of the last scan it forwarded."""
import threading

import rospy
from sensor_msgs.msg import LaserScan
from std_srvs.srv import SetBool, SetBoolResponse


class ScanGate(object):

    def __init__(self):
        self.lock = threading.Lock()
        self.open = True
        self.last_forwarded = 0.0
        self.publisher = rospy.Publisher('gated_scan', LaserScan, queue_size=1)
        rospy.Subscriber('scan', LaserScan, self.on_scan, queue_size=1)
        rospy.Service('~set_open', SetBool, self.set_open)

    def on_scan(self, msg):
        with self.lock:
            if self.open:
                self.publisher.publish(msg)
                self.last_forwarded = rospy.get_time()

    def set_open(self, request):
        with self.lock:
            self.open = request.data
            return SetBoolResponse(True, repr(self.last_forwarded))


if __name__ == '__main__':
    rospy.init_node('scan_gate')
    ScanGate()
    rospy.spin()
