#!/usr/bin/env python3
"""find_wall and the follower in one node, each command sent once: find_wall sends one
command and replies after a second; the follower then sends one command more."""
import actionlib
import rospy
from geometry_msgs.msg import Twist

from wall_follower.msg import OdomRecordAction, OdomRecordGoal
from wall_follower.srv import FindWall, FindWallResponse


def once(pub, linear, angular):
    command = Twist()
    command.linear.x, command.angular.z = linear, angular
    pub.publish(command)


if __name__ == '__main__':
    rospy.init_node('wall_following')
    pub = rospy.Publisher('cmd_vel', Twist, queue_size=1)

    def find_wall(_request):
        once(pub, 0.0, 0.196)
        rospy.sleep(1.0)
        return FindWallResponse(wallfound=True)
    rospy.Service('find_wall', FindWall, find_wall)
    while pub.get_num_connections() < 2 and not rospy.is_shutdown():
        rospy.sleep(0.1)
    rospy.ServiceProxy('find_wall', FindWall)()
    client = actionlib.SimpleActionClient('record_odom', OdomRecordAction)
    client.wait_for_server()
    client.send_goal(OdomRecordGoal())
    once(pub, 0.10, 0.196)
    rospy.spin()
