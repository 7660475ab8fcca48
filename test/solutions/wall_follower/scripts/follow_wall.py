#!/usr/bin/env python3
"""Calls find_wall, sends the record_odom goal, and follows the wall on the right until the
lap is recorded."""
import math

import actionlib
import rospy
from geometry_msgs.msg import Twist
from sensor_msgs.msg import LaserScan

from sectors import clamp, nearest
from wall_follower.msg import OdomRecordAction, OdomRecordGoal
from wall_follower.srv import FindWall

TARGET = 0.25


def command(scan):
    """The next command: keep the nearest reading on the right at TARGET, abeam."""
    twist = Twist()
    _, front = nearest(scan, -0.4, 0.4)
    angle, distance = nearest(scan, -2.4, -0.6)
    if front < 0.45:
        twist.linear.x, twist.angular.z = 0.03, 0.45
    elif angle is None or distance > 0.6:
        twist.linear.x, twist.angular.z = 0.1, -0.4
    else:
        twist.linear.x = 0.15
        twist.angular.z = clamp(2.5 * (TARGET - distance) + 1.2 * (angle + math.pi / 2.0), 0.45)
    return twist


class Follower(object):

    def __init__(self):
        self.following = False
        self.pub = rospy.Publisher('cmd_vel', Twist, queue_size=1)
        rospy.Subscriber('scan', LaserScan, self.on_scan, queue_size=1)

    def on_scan(self, scan):
        self.pub.publish(command(scan) if self.following else Twist())


if __name__ == '__main__':
    rospy.init_node('follow_wall')
    rospy.wait_for_service('find_wall')
    rospy.ServiceProxy('find_wall', FindWall)()
    client = actionlib.SimpleActionClient('record_odom', OdomRecordAction)
    client.wait_for_server()
    follower = Follower()
    client.send_goal(OdomRecordGoal())
    follower.following = True
    client.wait_for_result()
    follower.following = False
    rospy.spin()
