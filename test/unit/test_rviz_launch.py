"""rviz and what it shows, in the launch files, read with roslaunch's own loader (no master).

Every launch that drives takes rviz:=true and opens rviz with the config of
its job, through rviz.launch, which checks while the launch is read that
rviz is installed (require_package, as slam.launch does for gmapping; what
it does where a package is missing is tested in test_slam_launch.py). The
simulation publishes the world's walls (world_map) and the robot's shape
(robot_state_publisher with the chosen model's URDF). Needs the package
built (require_package is run with rosrun).
"""
import os

import pytest
import roslaunch.config

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
LAUNCH = os.path.join(ROOT, 'launch')
EXERCISES = ['exercise_forward_stop.launch', 'exercise_range_ahead.launch',
             'exercise_simple_move_square.launch', 'exercise_teleop_key.launch',
             'exercise_wander.launch']
# launch file -> the config its rviz:=true opens
CONFIGS = dict({'main.launch': 'wall_follower.rviz', 'simulation.launch': 'wall_follower.rviz',
                'mapping.launch': 'slam.rviz', 'slam.launch': 'slam.rviz',
                'find_trials.launch': 'wall_follower.rviz',
                'line_following.launch': 'line_following.rviz'},
               **{name: 'exercises.rviz' for name in EXERCISES})


def load(launch_file, *args):
    return roslaunch.config.load_config_default(
        [(os.path.join(LAUNCH, launch_file), list(args))], None)


def nodes_of(config):
    return {node.name: node for node in config.nodes}


@pytest.mark.parametrize('launch_file, args', [(name, ['sim:=true']) for name in sorted(CONFIGS)]
                         + [('main.launch', []), ('exercise_wander.launch', []),
                            ('line_following.launch', [])])
def test_rviz_opens_the_config_of_the_job_after_checking_it_is_installed(launch_file, args):
    config = load(launch_file, 'rviz:=true', *args)
    rviz = nodes_of(config)['rviz']
    assert rviz.package == 'rviz'
    shown = rviz.args.split('-d ', 1)[1].strip()
    assert os.path.basename(shown) == CONFIGS[launch_file]
    assert os.path.isfile(shown)
    assert os.path.isdir(config.params['/rviz/rviz_path'].value)


@pytest.mark.parametrize('launch_file', sorted(CONFIGS))
def test_no_rviz_unless_asked(launch_file):
    assert 'rviz' not in nodes_of(load(launch_file, 'sim:=true'))


@pytest.mark.parametrize('model', ['burger', 'waffle_pi'])
def test_simulation_publishes_the_walls_and_the_robot_model(model):
    config = load('simulation.launch', 'model:=' + model, 'world:=room')
    nodes = nodes_of(config)
    walls = nodes['world_map']
    assert config.params['/world_map/world'].value == 'room'
    assert dict(walls.remap_args) == {'map': 'map', 'map_metadata': 'map_metadata'}
    assert nodes['robot_state_publisher'].package == 'robot_state_publisher'
    description = config.params['/robot_description'].value
    assert '<robot name="turtlebot3_%s">' % model in description
    assert '<link name="base_link">' in description and '<link name="base_scan"' in description
    assert ('camera_rgb_optical_frame' in description) == (model == 'waffle_pi')


def test_mapping_moves_the_world_walls_off_the_map_it_builds():
    walls = nodes_of(load('mapping.launch', 'sim:=true'))['world_map']
    assert dict(walls.remap_args) == {'map': 'world_map', 'map_metadata': 'world_map_metadata'}


def test_line_following_simulation_draws_the_waffle_pi():
    description = load('line_following.launch', 'sim:=true').params['/robot_description'].value
    assert '<robot name="turtlebot3_waffle_pi">' in description


def test_line_following_rviz_shows_the_image_the_follower_reads():
    nodes = nodes_of(load('line_following.launch', 'rviz:=true', 'image:=/raspicam_node/image'))
    assert dict(nodes['rviz'].remap_args) == {'image': '/raspicam_node/image'}
    assert dict(nodes['line_follower'].remap_args)['image'] == '/raspicam_node/image'
