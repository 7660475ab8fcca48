#!/usr/bin/env python3
"""Calls find_wall, starts record_odom, then drives straight ahead at the speed limit."""
import actionlib
import rospy
from geometry_msgs.msg import Twist

from wall_follower.msg import OdomRecordAction, OdomRecordGoal
from wall_follower.srv import FindWall

if __name__ == '__main__':
    rospy.init_node('wall_following')
    rospy.wait_for_service('find_wall')
    rospy.ServiceProxy('find_wall', FindWall)()
    client = actionlib.SimpleActionClient('record_odom', OdomRecordAction)
    client.wait_for_server()
    client.send_goal(OdomRecordGoal())
    publisher = rospy.Publisher('cmd_vel', Twist, queue_size=1)
    forward = Twist()
    forward.linear.x = 0.19
    rate = rospy.Rate(10.0)
    while not rospy.is_shutdown():
        publisher.publish(forward)
        rate.sleep()
