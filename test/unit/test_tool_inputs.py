"""The evaluation tools on bad input: a world with no robot or no ranger to score, an output in
a folder that does not exist, a world that does not exist. Each is one line saying what is
wrong, found before any run starts, never a traceback."""
import os
import shutil
import subprocess
import sys
import textwrap

import numpy as np
import pytest

from wall_follower.evaluation.outputs import output_problem
from wall_follower.evaluation.scoring.course import CourseMap
from wall_follower.mapping.mapfile import save_map
from wall_follower.sim.worldfile import WorldFileError

REPO = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
MAP_PNG = os.path.join(REPO, 'scripts', 'map_png')


def world_file(tmp_path, body):
    path = os.path.join(str(tmp_path), 'test.world')
    with open(path, 'w') as stream:
        stream.write(textwrap.dedent(body))
    return path


def test_a_world_with_no_robot_to_score_is_a_world_file_error(tmp_path):
    path = world_file(tmp_path, 'model ( name "box" size [ 1 1 0.5 ] )\n')
    with pytest.raises(WorldFileError, match='no robot 0 to score'):
        CourseMap(path)


def test_a_robot_with_no_ranger_to_score_is_a_world_file_error(tmp_path):
    path = world_file(tmp_path, 'position ( name "blind" size [ 0.2 0.2 0.2 ] )\n')
    with pytest.raises(WorldFileError, match='robot "blind" has no ranger'):
        CourseMap(path)


def test_an_output_is_checked_before_a_run(tmp_path):
    here = str(tmp_path)
    assert output_problem(os.path.join(here, 'plot.png')) is None
    assert output_problem(os.path.join(here, 'gone', 'plot.png')) == (
        'no directory %s for %s' % (os.path.join(here, 'gone'),
                                    os.path.join(here, 'gone', 'plot.png')))
    assert output_problem(here) == '%s is a directory' % here


def map_png(*arguments):
    """map_png's exit status and output (it needs no ROS master)."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [os.path.join(REPO, 'src')] + sys.path), MPLBACKEND='Agg')
    done = subprocess.run([sys.executable, MAP_PNG] + list(arguments), env=env,
                          stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          universal_newlines=True, timeout=60)
    return done.returncode, done.stdout


@pytest.fixture
def saved_map(tmp_path):
    save_map(os.path.join(str(tmp_path), 'm'), np.zeros((4, 4), dtype=np.int8), 0.05,
             (0.0, 0.0, 0.0))
    return os.path.join(str(tmp_path), 'm.yaml')


@pytest.mark.parametrize('world, png, says', [
    ('nowhere', 'x.png', 'map_png: no world nowhere (neither a .world file nor a world of '
     'worlds/)\n'),
    ('room', os.path.join('gone', 'x.png'), 'map_png: no directory '),
])
def test_map_png_says_in_one_line_what_is_wrong(tmp_path, saved_map, world, png, says):
    status, output = map_png(saved_map, world, os.path.join(str(tmp_path), png))
    assert status == 1
    assert output.startswith(says)
    assert output.count('\n') == 1


def test_map_png_names_a_world_with_no_robot(tmp_path, saved_map):
    # The room, its bitmap and all, with its robot left out.
    for name in ('room.png', 'burger.inc'):
        shutil.copy(os.path.join(REPO, 'worlds', name), str(tmp_path))
    with open(os.path.join(REPO, 'worlds', 'room.world')) as stream:
        text = stream.read()
    robotless = world_file(tmp_path, text[:text.index('turtlebot3_burger\n(')])
    status, output = map_png(saved_map, robotless, os.path.join(str(tmp_path), 'x.png'))
    assert status == 1
    assert output == 'map_png: %s:0: no robot 0 to score (the world has 0)\n' % robotless
