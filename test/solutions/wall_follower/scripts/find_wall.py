#!/usr/bin/env python3
"""find_wall: turn to the nearest wall, go up to it, and turn until it is on the right."""
import math

import rospy
from geometry_msgs.msg import Twist
from sensor_msgs.msg import LaserScan

from sectors import clamp, nearest
from wall_follower.srv import FindWall, FindWallResponse

STOP_AT = 0.28
ALIGNED = math.radians(2.0)


class Finder(object):

    def __init__(self):
        self.scan = None
        self.pub = rospy.Publisher('cmd_vel', Twist, queue_size=1)
        rospy.Subscriber('scan', LaserScan, self.on_scan, queue_size=1)
        rospy.Service('find_wall', FindWall, self.find)

    def on_scan(self, msg):
        self.scan = msg

    def drive(self, linear, angular):
        command = Twist()
        command.linear.x = linear
        command.angular.z = clamp(angular, 0.4)
        self.pub.publish(command)

    def turn_to(self, target):
        """Turn on the spot until the nearest reading is at target (rad)."""
        rate = rospy.Rate(10)
        while not rospy.is_shutdown():
            angle, _ = nearest(self.scan)
            error = math.remainder(angle - target, 2.0 * math.pi)
            if abs(error) < ALIGNED:
                break
            self.drive(0.0, 1.5 * error if abs(error) > 0.1 else math.copysign(0.1, error))
            rate.sleep()
        self.drive(0.0, 0.0)

    def find(self, _request):
        while self.scan is None and not rospy.is_shutdown():
            rospy.sleep(0.1)
        self.turn_to(0.0)
        rate = rospy.Rate(10)
        while not rospy.is_shutdown():
            angle, distance = nearest(self.scan, -0.5, 0.5)
            if distance < STOP_AT:
                break
            self.drive(0.1, angle or 0.0)
            rate.sleep()
        self.turn_to(-math.pi / 2.0)
        return FindWallResponse(wallfound=True)


if __name__ == '__main__':
    rospy.init_node('find_wall')
    Finder()
    rospy.spin()
