#!/usr/bin/env python3
"""rostest: stage_sim leaves /use_sim_time as it found it, and refuses robots that cannot start.

The simulator is started as a user starts it (rosrun, against this test's
master, which no launch file has given /use_sim_time), runs one simulated
second flat out and exits. /use_sim_time, absent or false before, must be
so again after it; a robot put inside a wall, outside the map, or a world
that does not exist end it with status 1 and one line naming the problem,
never a traceback.
"""
import os
import subprocess
import sys
import unittest

import rospkg
import rospy
import rostest

WALL_LIMIT = 30.0   # wall s for the simulator to start, run and stop
SIM_TIME = '/use_sim_time'


def room():
    return os.path.join(rospkg.RosPack().get_path('wall_follower'), 'worlds', 'room.world')


def run_sim(name, world, *arguments):
    """The exit status and the output of a stage_sim that runs one simulated second."""
    done = subprocess.run(['rosrun', 'wall_follower', 'stage_sim', world, '_quit_time:=1.0',
                           '_speedup:=0', '__name:=' + name] + list(arguments),
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          universal_newlines=True, timeout=WALL_LIMIT)
    return done.returncode, done.stdout


class SimStart(unittest.TestCase):

    def tearDown(self):
        if rospy.has_param(SIM_TIME):
            rospy.delete_param(SIM_TIME)

    def test_an_unset_use_sim_time_is_deleted_again(self):
        self.assertFalse(rospy.has_param(SIM_TIME))
        status, output = run_sim('sim_unset', room())
        self.assertEqual(status, 0, output)
        self.assertIn('/use_sim_time was not set: set it now', output)
        self.assertFalse(rospy.has_param(SIM_TIME), 'left set to %r' % (
            rospy.get_param(SIM_TIME, None),))

    def test_a_false_use_sim_time_is_false_again(self):
        rospy.set_param(SIM_TIME, False)
        status, output = run_sim('sim_false', room())
        self.assertEqual(status, 0, output)
        self.assertIn('/use_sim_time was not set: set it now', output)
        self.assertIs(rospy.get_param(SIM_TIME), False)

    def test_a_true_use_sim_time_is_left_alone(self):
        rospy.set_param(SIM_TIME, True)
        status, output = run_sim('sim_true', room())
        self.assertEqual(status, 0, output)
        self.assertNotIn('set it now', output)
        self.assertIs(rospy.get_param(SIM_TIME), True)

    def check_refused(self, name, world, argument, says):
        status, output = run_sim(name, world, argument)
        self.assertEqual(status, 1, output)
        self.assertIn(says, output)
        self.assertNotIn('Traceback', output)
        self.assertFalse(rospy.has_param(SIM_TIME))

    def test_a_robot_inside_a_wall_is_refused(self):
        self.check_refused('sim_wall', room(), '_pose:=-1.55 0 0',
                           'cannot start: %s: robot "turtlebot3" at (-1.550, 0.000) starts '
                           'inside a wall' % room())

    def test_a_robot_outside_the_map_is_refused(self):
        self.check_refused('sim_outside', room(), '_pose:=9 9 0',
                           'cannot start: %s: robot "turtlebot3" at (9.000, 9.000) is outside '
                           'the map' % room())

    def test_a_missing_world_is_refused(self):
        self.check_refused('sim_missing', room() + '.gone', '_seed:=1',
                           'stage_sim: error: %s.gone:0: world file not found' % room())


if __name__ == '__main__':
    rospy.init_node('check_sim_start')
    rostest.rosrun('wall_follower', 'check_sim_start', SimStart, sys.argv)
