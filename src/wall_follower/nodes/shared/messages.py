"""Poses to and from ROS messages (geometry_msgs/Pose, nav_msgs/Odometry)."""
from geometry_msgs.msg import Pose

from wall_follower.rotation import quaternion_of_yaw, yaw_of_quaternion


def yaw_of(orientation):
    """Yaw (rad) of a geometry_msgs/Quaternion."""
    return yaw_of_quaternion(orientation.x, orientation.y, orientation.z, orientation.w)


def pose_of(odometry):
    """(x, y, yaw) of a nav_msgs/Odometry message."""
    p = odometry.pose.pose
    return p.position.x, p.position.y, yaw_of(p.orientation)


def pose_message(x, y, yaw):
    """A geometry_msgs/Pose at (x, y) turned yaw (rad) about z."""
    pose = Pose()
    pose.position.x, pose.position.y = x, y
    pose.orientation.z, pose.orientation.w = quaternion_of_yaw(yaw)
    return pose
