#!/usr/bin/env python3
"""record_odom: a point (x, y, yaw) a second and the distance so far, until back at the
first point (looked for at every odometry message)."""
import math
import threading

import actionlib
import rospy
from geometry_msgs.msg import Point32
from nav_msgs.msg import Odometry

from wall_follower.msg import OdomRecordAction, OdomRecordFeedback, OdomRecordResult

BACK = 0.1
AWAY = 2.0


class Recorder(object):

    def __init__(self):
        self.lock = threading.Lock()
        self.pose = None
        self.total = 0.0
        self.first = None
        self.back = False
        rospy.Subscriber('odom', Odometry, self.on_odom, queue_size=100)
        self.server = actionlib.SimpleActionServer('record_odom', OdomRecordAction,
                                                   self.execute, False)
        self.server.start()

    def on_odom(self, msg):
        position, turn = msg.pose.pose.position, msg.pose.pose.orientation
        with self.lock:
            if self.pose is not None:
                self.total += math.hypot(position.x - self.pose[0], position.y - self.pose[1])
            self.pose = (position.x, position.y, 2.0 * math.atan2(turn.z, turn.w))
            if self.first is not None and self.total > AWAY and \
                    math.hypot(position.x - self.first[0], position.y - self.first[1]) < BACK:
                self.back = True

    def execute(self, _goal):
        while self.pose is None and not rospy.is_shutdown():
            rospy.sleep(0.1)
        with self.lock:
            self.total = 0.0
            self.first = self.pose
            self.back = False
        points = []
        rate = rospy.Rate(1)
        while not rospy.is_shutdown():
            with self.lock:
                x, y, yaw = self.pose
                total, back = self.total, self.back
            points.append(Point32(x=x, y=y, z=yaw))
            self.server.publish_feedback(OdomRecordFeedback(current_total=total))
            if back:
                self.server.set_succeeded(OdomRecordResult(list_of_odoms=points))
                return
            rate.sleep()


if __name__ == '__main__':
    rospy.init_node('record_odom')
    Recorder()
    rospy.spin()
