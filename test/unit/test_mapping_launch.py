"""When mapping.launch ends by itself, read with roslaunch's loader (no master).

Headless in simulation (sim:=true, neither the Stage window nor rviz) there
is nothing to look at once the map is saved, so map_saver is the launch's
required node: its end ends the launch, as course_report's ends main.launch
report:=true. With a window open, or on the real robot, the launch stays up.
Needs the package on ROS_PACKAGE_PATH (the built workspace).
"""
import os

import pytest
import roslaunch.config

LAUNCH = os.path.join(os.path.dirname(__file__), '..', '..', 'launch')


def map_saver(*args):
    config = roslaunch.config.load_config_default(
        [(os.path.join(LAUNCH, 'mapping.launch'), list(args))], None)
    saver, = [node for node in config.nodes if node.name == 'map_saver']
    return saver


def test_a_headless_simulation_ends_with_the_saved_map():
    assert map_saver('sim:=true').required


@pytest.mark.parametrize('args', [(), ('sim:=true', 'rviz:=true'), ('sim:=true', 'gui:=true'),
                                  ('rviz:=true',)])
def test_with_a_window_or_on_the_robot_the_launch_stays_up(args):
    assert not map_saver(*args).required


@pytest.mark.parametrize('args, required', [(('sim:=true', 'end_when_saved:=false'), False),
                                            (('rviz:=true', 'end_when_saved:=true'), True)])
def test_end_when_saved_overrides_either(args, required):
    assert map_saver(*args).required == required
