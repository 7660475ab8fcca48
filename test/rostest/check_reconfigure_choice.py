#!/usr/bin/env python3
"""rostest: a parameter's choices reach `dynparam` as an enum, and a bad one is refused there.

dynamic_reconfigure's client passes any string on to the node, whatever
the enum says; the node refuses a value that is not one of the choices by
failing the set_parameters call, so `dynparam set` itself ends in an error
that carries the node's reason, and the node's value stays.
"""
import ast
import subprocess
import sys
import unittest

import rospy
import rostest
from dynamic_reconfigure.client import Client

NODE = '/line_follower'
WALL_LIMIT = 30.0   # wall s, for the node's server to come up and for each dynparam


def dynparam(*words):
    """`rosrun dynamic_reconfigure dynparam WORDS`: (its exit status, its output)."""
    done = subprocess.run(['rosrun', 'dynamic_reconfigure', 'dynparam'] + list(words),
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          universal_newlines=True, timeout=WALL_LIMIT)
    return done.returncode, done.stdout


class ReconfigureChoice(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        cls.client = Client(NODE, timeout=WALL_LIMIT)

    def controller(self):
        return self.client.get_configuration(timeout=WALL_LIMIT)['controller']

    def test_the_choices_are_an_enum(self):
        (described,) = [p for p in self.client.get_parameter_descriptions()
                        if p['name'] == 'controller']
        enum = ast.literal_eval(described['edit_method'])['enum']
        self.assertEqual([const['value'] for const in enum], ['pursuit', 'pixel_p'])

    def test_a_bad_choice_is_refused_by_dynparam_and_the_value_kept(self):
        status, output = dynparam('set', NODE, 'controller', 'bogus')
        self.assertNotEqual(status, 0, output)
        self.assertIn("controller must be one of pursuit, pixel_p, not 'bogus'", output)
        self.assertEqual(self.controller(), 'pursuit')

    def test_a_choice_is_taken_by_its_name_in_any_case(self):
        status, output = dynparam('set', NODE, 'controller', 'PIXEL_P')
        self.assertEqual(status, 0, output)
        self.assertEqual(self.controller(), 'pixel_p')
        status, output = dynparam('set', NODE, 'controller', 'pursuit')
        self.assertEqual((status, self.controller()), (0, 'pursuit'), output)


if __name__ == '__main__':
    rospy.init_node('check_reconfigure_choice')
    rostest.rosrun('wall_follower', 'check_reconfigure_choice', ReconfigureChoice, sys.argv)
