#!/usr/bin/env python3
"""A course node that fails before it does anything."""
import rospy

if __name__ == '__main__':
    rospy.init_node('wall_following')
    raise RuntimeError('this solution crashes at start')
