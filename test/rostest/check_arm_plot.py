#!/usr/bin/env python3
"""rostest: arm_plot ends after ~duration whatever comes, and loses no recording to its ~file.

On /use_sim_time with no /clock at all (ROS time stands at 0, as before a simulator
starts or while it is frozen): arm_plot with _duration:=2 and no joint_states ends by
itself after 2 s (it once waited for joint_states stamps to advance, for ever). Given
joint_states stamped 0 and then stopped: a directory as ~file has the picture saved in
it as joint_states.png (not as DIR.png while saying "saved to DIR"); a ~file it cannot
write (under /proc) is named in an error and the picture saved in another place, which
the log names, instead of ending in a traceback with the recording lost.

Each arm_plot is a child process of this test, started by its path as roslaunch starts
a node. Before it is stopped it has taken two joint_states for certain: the first is
sent only once this test's publisher is connected to that very arm_plot (by this node's
getBusInfo), the second only once its statistics (getBusStats) count the first as read,
and a subscriber's thread reads the next message only after the callback of the one
before has returned. A connection count would not do: the connection to the arm_plot of
the test before stays counted until rospy next looks for closed sockets (every 0.5 wall
seconds, later on a loaded machine), and a message sent on it alone is lost.
"""
import os
import re
import shutil
import signal
import subprocess
import tempfile
import threading
import unittest
from xmlrpc.client import ServerProxy

import roslib.packages
import rosgraph
import rospy
import rostest
from PIL import Image
from sensor_msgs.msg import JointState

from waiting import wait_until

DURATION = 2.0       # s: the recordings' ~duration
RUN_LIMIT = 60.0     # wall s for a child to start, record and end
TOPIC = '/joint_states'
WALL_STAMP = re.compile(r'^\[ *\w+\] \[(\d+\.\d+)')


class Plot(object):
    """One arm_plot run as a child process: its name, arguments and output."""

    count = 0

    def __init__(self, *arguments):
        Plot.count += 1
        self.name = '/arm_plot_%d' % Plot.count
        self.output = ''
        self.process = subprocess.Popen(
            roslib.packages.find_node('wall_follower', 'arm_plot')[:1] + ['_live:=false'] +
            list(arguments) + ['__name:=' + self.name[1:]],
            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True)
        self._reader = threading.Thread(target=self._read, daemon=True)
        self._reader.start()

    def _read(self):
        for line in self.process.stdout:
            self.output += line

    def end(self, interrupt=False):
        """Its exit code, once it has ended (told to, with SIGINT, if interrupt); None if it
        did not end within RUN_LIMIT (then it is killed)."""
        if interrupt:
            self.process.send_signal(signal.SIGINT)
        try:
            code = self.process.wait(RUN_LIMIT)
        except subprocess.TimeoutExpired:
            self.kill()
            code = None
        self._reader.join(RUN_LIMIT)
        return code

    def kill(self):
        """End it at once, unless it has ended."""
        if self.process.poll() is None:
            self.process.kill()
            self.process.wait()

    def line(self, fragment):
        """The first output line holding fragment, or None."""
        return next((line for line in self.output.splitlines() if fragment in line), None)

    def wall_time(self, fragment):
        """The wall time [s] stamped on the first log line holding fragment."""
        return float(WALL_STAMP.match(self.line(fragment)).group(1))

    def connected(self):
        """Whether this test's publisher of TOPIC has a connection to this very node."""
        caller = rospy.get_name()
        _, _, connections = ServerProxy(rospy.get_node_uri()).getBusInfo(caller)
        return any(destination == self.name and topic == TOPIC
                   for _, destination, _, _, topic, _, _ in connections)

    def messages_taken(self):
        """How many messages of TOPIC the node has read, by its bus statistics; 0 before it
        has registered."""
        caller = rospy.get_name()
        try:
            uri = rosgraph.Master(caller).lookupNode(self.name)
            _, _, (_, subscribed, _) = ServerProxy(uri).getBusStats(caller)
        except (rosgraph.MasterError, OSError):
            return 0
        return sum(sum(connection[2] for connection in connections)
                   for topic, connections in subscribed if topic == TOPIC)


class ArmPlotTest(unittest.TestCase):

    @classmethod
    def setUpClass(cls):
        rospy.init_node('check_arm_plot')
        cls.states = rospy.Publisher(TOPIC, JointState, queue_size=10)

    def setUp(self):
        self.directory = tempfile.mkdtemp(prefix='check_arm_plot')

    def start(self, *arguments):
        """A new Plot, killed after the test if still running: one left from a failed test
        would take the joint_states, and the name, of the tests after it."""
        plot = Plot(*arguments)
        self.addCleanup(plot.kill)
        return plot

    def tearDown(self):
        shutil.rmtree(self.directory)

    def feed(self, plot, count=2):
        """Send plot count joint_states stamped 0, each once it has read the one before."""
        for number in range(count):
            self.assertTrue(wait_until(lambda: plot.connected() and
                                       plot.messages_taken() >= number, RUN_LIMIT),
                            'arm_plot took no joint_states: %s' % plot.output)
            self.states.publish(JointState(name=['hip', 'elbow'], position=[0.1 * number, 0.2],
                                           velocity=[0.0, 0.0]))
        self.assertTrue(wait_until(lambda: plot.messages_taken() >= count, RUN_LIMIT))

    def assert_png(self, path):
        with Image.open(path) as image:
            self.assertEqual(image.format, 'PNG')

    def test_with_no_joint_states_and_no_clock_it_ends_after_its_duration(self):
        plot = self.start('_duration:=%g' % DURATION, '_file:=' + self.directory,
                          'joint_states:=/nothing_comes')
        self.assertEqual(plot.end(), 0, 'arm_plot did not end by itself: %s' % plot.output)
        self.assertGreaterEqual(plot.wall_time('no joint_states came') -
                                plot.wall_time('recording joint_states'), DURATION)
        self.assertEqual(os.listdir(self.directory), [])

    def test_a_directory_as_the_file_holds_joint_states_png(self):
        plot = self.start('_file:=' + self.directory)
        self.feed(plot)
        self.assertEqual(plot.end(interrupt=True), 0, plot.output)
        picture = os.path.join(self.directory, 'joint_states.png')
        self.assertTrue(plot.line('saved 2 joint states to %s' % picture), plot.output)
        self.assert_png(picture)
        self.assertFalse(os.path.exists(self.directory + '.png'))

    def test_a_file_it_cannot_write_is_said_and_the_picture_saved_elsewhere(self):
        unwritable = '/proc/check_arm_plot.png'
        plot = self.start('_file:=' + unwritable)
        self.feed(plot)
        self.assertEqual(plot.end(interrupt=True), 0, plot.output)
        self.assertTrue(plot.line('cannot write %s' % unwritable), plot.output)
        self.assertNotIn('Traceback', plot.output)
        saved = re.search(r'saved 2 joint states to (\S+) instead', plot.output)
        self.assertTrue(saved, plot.output)
        self.assert_png(saved.group(1))
        os.unlink(saved.group(1))


if __name__ == '__main__':
    rostest.rosrun('wall_follower', 'check_arm_plot', ArmPlotTest)
