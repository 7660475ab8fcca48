"""What arm.launch starts, read with roslaunch's loader: headless and on wall time by
default; the built-in controller or, with controller:=gazebo, a clear error before any node
starts where Gazebo is missing; sliders instead of a controller with gui:=true. Needs the
package built (require_package is run with rosrun)."""
import os

import pytest
import rospkg
import roslaunch.config
from roslaunch.core import RLException

from wall_follower.evaluation.launching import free_port, launch_and_read, launch_command

LAUNCH = os.path.join(os.path.dirname(__file__), '..', '..', 'launch', 'arm.launch')
# Wall seconds for roslaunch to read the launch file and give up.
LAUNCH_BOUND = 30.0


def load(*args):
    return roslaunch.config.load_config_default([(LAUNCH, list(args))], None)


def started(config):
    return sorted((node.package, node.type) for node in config.nodes)


def test_by_default_the_builtin_controller_move_arm_and_the_state_publisher_on_wall_time():
    config = load()
    assert started(config) == [('robot_state_publisher', 'robot_state_publisher'),
                               ('wall_follower', 'arm_controller'),
                               ('wall_follower', 'move_arm')]
    assert '/use_sim_time' not in config.params
    assert config.params['/arm_controller/publish_clock'].value is False
    assert '<robot name="cougarbot">' in config.params['/robot_description'].value
    assert '<group name="arm">' in config.params['/robot_description_semantic'].value
    assert config.params[
        '/robot_description_planning/joint_limits/hip/max_acceleration'].value > 0


def test_sim_time_has_the_controller_drive_the_clock():
    config = load('sim_time:=true')
    assert config.params['/use_sim_time'].value is True
    assert config.params['/arm_controller/publish_clock'].value is True


def test_gui_puts_sliders_in_place_of_the_controller_and_rviz_shows_the_arm():
    config = load('gui:=true', 'rviz:=true')
    assert started(config) == [('joint_state_publisher_gui', 'joint_state_publisher_gui'),
                               ('robot_state_publisher', 'robot_state_publisher'),
                               ('rviz', 'rviz')]
    rviz, = [node for node in config.nodes if node.type == 'rviz']
    assert rviz.args.endswith('config/arm.rviz')


@pytest.fixture
def gazebo_missing(monkeypatch):
    entries = os.environ.get('ROS_PACKAGE_PATH', '').split(os.pathsep)
    kept = [entry for entry in entries
            if 'gazebo_ros' not in rospkg.RosPack([entry]).list()]
    monkeypatch.setenv('ROS_PACKAGE_PATH', os.pathsep.join(kept))


def test_missing_gazebo_fails_the_launch_saying_what_to_do(gazebo_missing, capfd):
    with pytest.raises(RLException):
        load('controller:=gazebo')
    said = capfd.readouterr().err
    assert 'the ROS package gazebo_ros is not installed' in said
    assert 'ros-noetic-gazebo-ros-pkgs' in said and 'controller:=builtin' in said


def test_missing_gazebo_stops_roslaunch_before_any_node_starts(gazebo_missing):
    port = free_port()
    ended, output = launch_and_read(launch_command('arm.launch', {'controller': 'gazebo'}, port),
                                    port, LAUNCH_BOUND)
    assert ended, output
    assert 'the ROS package gazebo_ros is not installed' in output
    assert 'process[' not in output and 'started with pid' not in output
