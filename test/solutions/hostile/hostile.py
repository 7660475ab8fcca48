#!/usr/bin/env python3
"""A hostile solution: each thing it tries is said on its output.

It commands angular.z = -inf; writes a file in /tmp and one in grade's
output directory; starts a grandchild that leaves its session and its
environment (env -i setsid) and would live for minutes; and connects to a
port on the host's loopback. Then it idles, and the case ends.
"""
import os
import socket
import subprocess
import sys

import rospy
from geometry_msgs.msg import Twist


def attempt(what, action):
    try:
        action()
        print('did: %s' % what, flush=True)
    except OSError as err:
        print('could not: %s (%s)' % (what, err), flush=True)


def write(path):
    with open(path, 'w') as stream:
        stream.write('written by a hostile solution\n')


def main():
    port, marker, out = sys.argv[1:4]
    rospy.init_node('wall_following')
    pub = rospy.Publisher('cmd_vel', Twist, queue_size=1)
    # The simulator and grade's own listener.
    while pub.get_num_connections() < 2 and not rospy.is_shutdown():
        rospy.sleep(0.1)
    rospy.sleep(1.0)
    command = Twist()
    command.angular.z = float('-inf')
    pub.publish(command)
    print('did: command angular.z = -inf', flush=True)
    attempt('write /tmp/%s' % marker, lambda: write(os.path.join('/tmp', marker)))
    attempt('write %s/%s' % (out, marker), lambda: write(os.path.join(out, marker)))
    attempt('start a grandchild', lambda: subprocess.Popen(
        ['env', '-i', 'setsid', sys.executable, '-c', 'import time; time.sleep(600)', marker],
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
    attempt('connect to 127.0.0.1:%s' % port,
            lambda: socket.create_connection(('127.0.0.1', int(port)), timeout=2.0).close())
    rospy.spin()


if __name__ == '__main__':
    main()
