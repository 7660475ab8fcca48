#!/usr/bin/env python3
"""rostest: an evaluation node that a signal stops while it waits ends quietly.

grade_case, line_case, course_report and find_trials are started as
roslaunch starts them (by their path), with no simulator and no find_wall
on the master: each waits for one until its time-limit (tens of seconds).
Once the master lists it on the last topic it takes up before that wait,
it is sent SIGINT or SIGTERM, as Ctrl-C, roslaunch or grade send them. It
must then end (within EXIT_LIMIT wall seconds) with status 0, log no error
(a simulator that never came, a follower that ended, find_wall missing),
show no traceback, and write no record, plot or figures: a signal is no
failure of the grader, the simulator or the solution
(nodes/shared/shutdown.py). A time-limit, not the signal, would be the
node's failure; none is reached here.

Simulated time that never starts (no /clock): the waits are in wall
seconds, and nothing here waits on a clock.
"""
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import unittest

import roslib.packages
import rosgraph
import rospkg
import rospy
import rostest

from waiting import wait_until

PACKAGE = rospkg.RosPack().get_path('wall_follower')
READY_LIMIT = 60.0   # wall s for a node to start and take up its topics (a loaded machine)
EXIT_LIMIT = 10.0    # wall s for it to end after the signal
OUT = '{out}'        # in the arguments: the folder the test makes for the files nodes write
# script -> (its arguments; the topic, in its
# namespace, taken up last before its wait: ('sub' or 'pub', name); the files it must not
# write; the signal it gets)
NODES = {
    'grade_case': (['_world:=' + os.path.join(PACKAGE, 'worlds', 'room.world'),
                    '_json:={out}/grade_case.json', '_plot:={out}/grade_case.png'],
                   ('sub', 'record_odom/status'), ('grade_case.json', 'grade_case.png'),
                   signal.SIGINT),
    'line_case': (['_world:=' + os.path.join(PACKAGE, 'worlds', 'line_lab.world'),
                   '_json:={out}/line_case.json', '_plot:={out}/line_case.png'],
                  ('sub', 'stalled'), ('line_case.json', 'line_case.png'), signal.SIGTERM),
    'course_report': (['_world:=room', '_plot:={out}/course.png', '_json:={out}/course.json'],
                      ('sub', 'record_odom/status'), ('course.png', 'course.json'),
                      signal.SIGINT),
    'find_trials': (['_world:=room', '_poses:={room: [[0.0, 0.0, 0.0]]}',
                     '_json:={out}/trials.json'],
                    ('pub', 'cmd_pose'), ('trials.json',), signal.SIGTERM),
}


def listed(kind, topic, node):
    """Whether the master lists node as a publisher ('pub') or subscriber ('sub') of topic."""
    publishers, subscribers, _ = rosgraph.Master(rospy.get_name()).getSystemState()
    return node in dict(publishers if kind == 'pub' else subscribers).get(topic, ())


class SignalledWhileWaiting(unittest.TestCase):

    def setUp(self):
        self.out = tempfile.mkdtemp(prefix='signal_waits')
        self.addCleanup(shutil.rmtree, self.out)

    def check(self, script):
        arguments, (kind, topic), files, number = NODES[script]
        namespace = '/waits/' + script
        node = '%s/%s' % (namespace, script)
        with tempfile.TemporaryFile() as output:
            process = subprocess.Popen(
                [roslib.packages.find_node('wall_follower', script)[0]]
                + [argument.replace(OUT, self.out) for argument in arguments]
                + ['__name:=' + script, '__ns:=' + namespace],
                stdout=output, stderr=subprocess.STDOUT)
            try:
                ready = wait_until(lambda: listed(kind, '%s/%s' % (namespace, topic), node),
                                   READY_LIMIT)
                if ready:
                    process.send_signal(number)
                status = process.wait(EXIT_LIMIT if ready else 0.0)
            except subprocess.TimeoutExpired:
                status = None
            finally:
                if process.poll() is None:
                    process.kill()
                    process.wait()
            output.seek(0)
            written = output.read().decode(errors='replace')
        self.assertTrue(ready, '%s never took up %s:\n%s' % (script, topic, written[-3000:]))
        self.assertEqual(status, 0, '%s, sent %s while it waited, ended with status %s:\n%s'
                         % (script, signal.Signals(number).name, status, written[-3000:]))
        for sign in ('[ERROR]', 'Traceback'):
            self.assertNotIn(sign, written, written[-3000:])
        self.assertEqual([name for name in files if os.path.exists(os.path.join(self.out, name))],
                         [], 'a signal is no result to write')

    def test_grade_case_waiting_for_the_simulator(self):
        self.check('grade_case')

    def test_line_case_waiting_for_the_simulator(self):
        self.check('line_case')

    def test_course_report_waiting_for_the_simulator(self):
        self.check('course_report')

    def test_find_trials_waiting_for_find_wall(self):
        self.check('find_trials')


if __name__ == '__main__':
    rospy.init_node('check_signal_waits')
    rostest.rosrun('wall_follower', 'check_signal_waits', SignalledWhileWaiting, sys.argv)
