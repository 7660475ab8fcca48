"""stage_sim's topics of one step: an image never goes out without its camera_info and tf.

Runs the node's publishing code with no master: each publisher's subscriber
count is set by the test and what it publishes is kept. The world is the line
lab's, whose robot carries a camera, stepped once by the engine.
"""
import itertools

import pytest
import rospy

from wall_follower.nodes.sim.stage_sim import RobotTopics
from wall_follower.sim.engine import Simulation
from wall_follower.sim.stage_interface import world_path
from wall_follower.sim.worldfile import load_world

STAMP = rospy.Time(3, 0)


@pytest.fixture(scope='module')
def world():
    return load_world(world_path('line_lab'))


@pytest.fixture(scope='module')
def frame_robot(world):
    return Simulation(world).step(with_scans=True, with_images=True).robots[0]


def watch(monkeypatch, publisher, counts):
    """Give `publisher` the subscriber counts `counts` (one per query, the last one
    for ever after) and return the list its messages go to."""
    sent = []
    queries = itertools.chain(counts, itertools.repeat(counts[-1]))
    monkeypatch.setattr(publisher, 'get_num_connections', lambda: next(queries))
    monkeypatch.setattr(publisher, 'publish', sent.append)
    return sent


def camera_frames(transforms):
    return [t for t in transforms if t.child_frame_id == 'camera']


def test_an_image_subscriber_leaving_mid_step_takes_nothing_of_that_step_away(
        world, frame_robot, monkeypatch):
    topics = RobotTopics('', world.robots[0])
    # Subscribed when the step starts; gone at every later look.
    images = watch(monkeypatch, topics.camera.image, [1, 0])
    infos = watch(monkeypatch, topics.camera.info, [1])
    watch(monkeypatch, topics.camera.depth, [0])
    transforms = topics.publish(STAMP, frame_robot, with_tf=True)
    assert [msg.header.stamp for msg in images] == [STAMP]
    assert [msg.header.stamp for msg in infos] == [STAMP]
    assert [t.header.stamp for t in camera_frames(transforms)] == [STAMP]


def test_a_camera_nobody_watches_sends_no_image_info_or_tf(world, frame_robot, monkeypatch):
    topics = RobotTopics('', world.robots[0])
    # A subscriber arriving mid-step is served from the next step on.
    images = watch(monkeypatch, topics.camera.image, [0, 1])
    depths = watch(monkeypatch, topics.camera.depth, [0, 1])
    infos = watch(monkeypatch, topics.camera.info, [1])
    transforms = topics.publish(STAMP, frame_robot, with_tf=True)
    assert (images, depths, infos, camera_frames(transforms)) == ([], [], [], [])
    assert [t.child_frame_id for t in transforms] == \
        ['base_footprint', 'base_link', 'base_laser_link']


def test_depth_alone_brings_camera_info_and_tf(world, frame_robot, monkeypatch):
    topics = RobotTopics('', world.robots[0])
    images = watch(monkeypatch, topics.camera.image, [0])
    depths = watch(monkeypatch, topics.camera.depth, [1])
    infos = watch(monkeypatch, topics.camera.info, [1])
    transforms = topics.publish(STAMP, frame_robot, with_tf=True)
    assert (len(images), len(depths), len(infos), len(camera_frames(transforms))) == \
        (0, 1, 1, 1)
    assert depths[0].encoding == '32FC1'
    assert topics.publish(STAMP, frame_robot, with_tf=False) == []
