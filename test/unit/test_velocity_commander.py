"""VelocityCommander: clamps every command, and sends one stop on shutdown and nothing after.

Needs ROS's Python modules but no master: rospy's Publisher and shutdown
hooks are replaced by the test's.
"""
import threading

import pytest
import rospy

from wall_follower.control.motion import MAX_ANGULAR, MAX_LINEAR, Command
from wall_follower.nodes.shared.velocity import VelocityCommander

WAIT_LIMIT = 30.0   # wall s the fake's writer thread may take, at most


class Publisher(object):
    """rospy's, which raises once rospy has closed the topic after the shutdown hooks, and
    writes each message to its one subscriber from a thread of the connection's, WRITE_DELAY
    after it is published."""

    WRITE_DELAY = 0.1

    def __init__(self, *args, **kwargs):
        self.sent = []
        self.closed = False
        self.written = 0
        self.write_done = threading.Condition()
        self.impl = self

    def publish(self, twist):
        if self.closed:
            raise rospy.ROSException('publish() to a closed topic')
        self.sent.append((twist.linear.x, twist.angular.z))
        threading.Timer(self.WRITE_DELAY, self._write).start()

    def _write(self):
        with self.write_done:
            self.written += 1
            self.write_done.notify_all()

    def wait_written(self, count):
        """Until `count` messages are written (WAIT_LIMIT wall s at most: a machine under load
        may run the writer's timer late, and the test must not guess how late)."""
        with self.write_done:
            return self.write_done.wait_for(lambda: self.written >= count, WAIT_LIMIT)

    def get_stats(self):
        return ('/cmd_vel', 0, [(0, 0, self.written, True)])


@pytest.fixture
def commander(monkeypatch):
    hooks = []
    monkeypatch.setattr(rospy, 'Publisher', Publisher)
    monkeypatch.setattr(rospy, 'on_shutdown', hooks.append)
    made = VelocityCommander('cmd_vel', MAX_LINEAR, MAX_ANGULAR)
    made.hooks = hooks
    return made


def test_commands_are_clamped_to_the_robot_limits(commander):
    assert commander.send(Command(0.5, -2.0)) == Command(0.19, -0.49)
    assert commander._pub.sent == [(0.19, -0.49)]


def test_shutdown_sends_one_stop_and_nothing_after_it(commander):
    commander.send(Command(0.1, 0.2))
    for hook in commander.hooks:
        hook()
    commander._pub.closed = True
    assert commander.send(Command(0.1, 0.2)) == Command(0.0, 0.0)
    commander.stop()
    assert commander._pub.sent == [(0.1, 0.2), (0.0, 0.0)]


def test_the_shutdown_hook_returns_once_the_stop_is_written(commander):
    """rospy closes the connections right after the hooks: a stop still queued is lost."""
    commander.send(Command(0.1, 0.2))
    assert commander._pub.wait_written(1)
    for hook in commander.hooks:
        hook()
    assert commander._pub.written == 2


def test_limits_given_or_changed_are_the_clamp(commander):
    commander.max_linear, commander.max_angular = 0.1, 0.3
    assert commander.send(Command(0.5, -2.0)) == Command(0.1, -0.3)
