#!/usr/bin/env python3
"""record_odom that ends the lap after 6 m: a point a second, feedback the distance so far."""
import math

import actionlib
import rospy
from geometry_msgs.msg import Point
from nav_msgs.msg import Odometry

from wall_follower.msg import OdomRecordAction, OdomRecordFeedback, OdomRecordResult

LAP = 6.0


class Recorder(object):
    def __init__(self):
        self.pose = None
        rospy.Subscriber('odom', Odometry, self.on_odom)
        self.server = actionlib.SimpleActionServer('record_odom', OdomRecordAction,
                                                   self.execute, auto_start=False)
        self.server.start()

    def on_odom(self, msg):
        self.pose = msg.pose.pose.position

    def execute(self, _goal):
        points, total, last = [], 0.0, None
        rate = rospy.Rate(1.0)
        while not rospy.is_shutdown():
            here = Point(self.pose.x, self.pose.y, 0.0)
            if last is not None:
                total += math.hypot(here.x - last.x, here.y - last.y)
            last = here
            points.append(here)
            self.server.publish_feedback(OdomRecordFeedback(current_total=total))
            if total >= LAP:
                self.server.set_succeeded(OdomRecordResult(list_of_odoms=points))
                return
            rate.sleep()


if __name__ == '__main__':
    rospy.init_node('odom_recorder')
    Recorder()
    rospy.spin()
