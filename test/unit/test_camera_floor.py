"""The camera's floor projection and the base's pose from camera_info and tf
(nodes.shared.camera_floor): tf is never asked for a stamp far from now (tf2's core aborts
the process on one), and one projection serves as long as nothing it was made from changes.

Needs ROS's Python modules but no master: tf's buffer and listener are stand-ins that hold
one transform, the camera_info subscriber is only created.
"""
import math

import pytest
import rospy
import tf2_ros
from geometry_msgs.msg import Transform
from sensor_msgs.msg import CameraInfo

from wall_follower.nodes.shared import camera_floor
from wall_follower.params import defaults
from wall_follower.params.camera.line_follower import TABLE


class Stamped(object):
    def __init__(self, transform):
        self.transform = transform


class Buffer(object):
    """tf2_ros.Buffer's lookup_transform, answering any question with one transform, and
    counting the questions (a real one aborts on a stamp decades from its data)."""

    def __init__(self, cache_time):
        self.asked = []

    def lookup_transform(self, target, source, stamp):
        self.asked.append(stamp)
        transform = Transform()
        transform.translation.z = 0.3
        transform.rotation.x = -math.sin(math.radians(65.0))   # roll -130 deg: 40 deg down
        transform.rotation.w = math.cos(math.radians(65.0))
        return Stamped(transform)


@pytest.fixture
def camera(monkeypatch):
    monkeypatch.setattr(tf2_ros, 'Buffer', Buffer)
    monkeypatch.setattr(tf2_ros, 'TransformListener', lambda buffer: None)
    monkeypatch.setattr(rospy.Time, 'now', staticmethod(lambda: rospy.Time(100)))
    floor = camera_floor.CameraFloor(defaults(TABLE))
    floor._on_info(CameraInfo(width=320, height=240, K=[265, 0, 160, 0, 265, 120, 0, 0, 1]))
    return floor


@pytest.mark.parametrize('stamp', [rospy.Time(4102444800), rospy.Time(2 ** 32 - 1, 999999999),
                                   rospy.Time(0, 1)])
def test_tf_is_not_asked_for_a_stamp_far_from_now(camera, stamp):
    pose, problem = camera.base_pose(stamp)
    assert pose is None and 'stamped' in problem
    assert camera._buffer.asked == []


def test_tf_is_asked_for_a_stamp_near_now(camera):
    pose, problem = camera.base_pose(rospy.Time(99, 500000000))
    assert problem is None and camera._buffer.asked == [rospy.Time(99, 500000000)]


def test_one_projection_serves_while_nothing_changes(camera):
    first, problem = camera.projection('camera')
    assert problem is None
    assert camera.projection('camera')[0] is first
    camera._on_info(CameraInfo(width=640, height=480, K=[530, 0, 320, 0, 530, 240, 0, 0, 1]))
    second = camera.projection('camera')[0]
    assert second is not first and second.intrinsics.width == 640
