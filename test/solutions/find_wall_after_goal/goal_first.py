#!/usr/bin/env python3
"""Sends the record_odom goal, then calls find_wall, then holds the robot still."""
import actionlib
import rospy
from geometry_msgs.msg import Twist

from wall_follower.msg import OdomRecordAction, OdomRecordGoal
from wall_follower.srv import FindWall

if __name__ == '__main__':
    rospy.init_node('wall_following')
    client = actionlib.SimpleActionClient('record_odom', OdomRecordAction)
    client.wait_for_server()
    client.send_goal(OdomRecordGoal())
    rospy.wait_for_service('find_wall')
    rospy.ServiceProxy('find_wall', FindWall)()
    rospy.loginfo('goal_first: find_wall replied')
    pub = rospy.Publisher('cmd_vel', Twist, queue_size=1)
    rate = rospy.Rate(10)
    while not rospy.is_shutdown():
        pub.publish(Twist())
        rate.sleep()
