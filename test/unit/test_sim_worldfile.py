"""Stage world-file reader: the shipped worlds, Stage's geometry rules, and bad files."""
import glob
import math
import os
import textwrap

import numpy as np
import pytest

from wall_follower.evaluation.scoring.geometry import obstacle_edges
from wall_follower.sim.worldfile import STAGE_VELOCITY_BOUNDS, WorldFileError, load_world

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.join(HERE, '..', '..')
REFERENCE = os.path.join(HERE, '..', 'data', 'stage_reference')
ALL_WORLDS = sorted(glob.glob(os.path.join(REPO, 'worlds', '*.world')) +
                    glob.glob(os.path.join(REFERENCE, '*.world')))


def _write(directory, name, text):
    path = os.path.join(str(directory), name)
    with open(path, 'w') as stream:
        stream.write(textwrap.dedent(text))
    return path


def _square_png(directory, name='map.png', size=20, border=2, margin=0):
    from PIL import Image
    pixels = np.full((size + 2 * margin, size + 2 * margin), 255, dtype=np.uint8)
    pixels[margin:margin + size, margin:margin + size] = 0
    pixels[margin + border:margin + size - border, margin + border:margin + size - border] = 255
    Image.fromarray(pixels).save(os.path.join(str(directory), name))
    return name


def _bounds(obstacle):
    edges = obstacle_edges(obstacle).reshape(-1, 2)
    return edges.min(axis=0), edges.max(axis=0)


@pytest.mark.parametrize('path', ALL_WORLDS, ids=os.path.basename)
def test_every_world_loads_with_a_robot_and_walls(path):
    world = load_world(path)
    assert world.resolution > 0 and world.interval_sim > 0
    assert world.obstacles, 'no obstacles'
    assert world.robots, 'no robot'
    for robot in world.robots:
        assert robot.drive == 'diff'
        assert robot.ranger is not None
        assert robot.ranger.samples > 1 and robot.ranger.range_max > robot.ranger.range_min


# The line worlds carry a Waffle Pi with a camera instead (test_line_worlds.py).
@pytest.mark.parametrize('path', sorted(
    path for path in glob.glob(os.path.join(REPO, 'worlds', '*.world'))
    if not os.path.basename(path).startswith('line_')), ids=os.path.basename)
def test_shipped_worlds_carry_the_burger(path):
    robot = load_world(path).robots[0]
    assert robot.size == pytest.approx((0.138, 0.178, 0.192))
    assert robot.origin == pytest.approx((-0.032, 0.0, 0.0))
    assert robot.ranger.samples == 360
    assert (robot.ranger.range_min, robot.ranger.range_max) == pytest.approx((0.12, 3.5))
    assert robot.ranger.pose[0] == pytest.approx(-0.032)
    bounds = robot.velocity_bounds
    assert bounds[1] >= 0.22 and bounds[0] <= -0.22
    assert bounds[7] >= 2.84 and bounds[6] <= -2.84


def test_reference_room_as_stage_reads_it():
    world = load_world(os.path.join(REFERENCE, 'ref_room.world'))
    assert (world.resolution, world.interval_sim, world.speedup) == (0.02, 0.1, 1.0)
    room, = world.obstacles
    lo, hi = _bounds(room)
    assert lo == pytest.approx((-2.0, -2.0)) and hi == pytest.approx((2.0, 2.0))
    faces = obstacle_edges(room)
    # the inner (free-space) faces at +-1.9
    vertical = faces[np.isclose(faces[:, 0, 0], faces[:, 1, 0]), 0, 0]
    assert sorted(np.round(vertical, 9)) == [-2.0, -1.9, 1.9, 2.0]
    robot, = world.robots
    assert robot.pose == pytest.approx((-0.5, -0.3, math.radians(30)))
    assert robot.localization == 'gps'
    assert robot.velocity_bounds == STAGE_VELOCITY_BOUNDS
    ranger = robot.ranger
    assert ranger.fov == pytest.approx(2 * math.pi)
    assert ranger.pose == pytest.approx((-0.032, 0.0, 0.0, 0.0))
    assert ranger.sensor_height == pytest.approx(0.192 + 0.02 / 2)


def test_bitmap_margins_are_dropped_and_black_area_fills_size():
    world = load_world(os.path.join(REFERENCE, 'ref_margin.world'))
    lo, hi = _bounds(world.obstacles[0])
    assert lo == pytest.approx((-2.2, -2.1)) and hi == pytest.approx((2.2, 2.1))


def test_floorplan_pose_translates_the_bitmap_and_image_row_0_is_up():
    world = load_world(os.path.join(REFERENCE, 'ref_shapes.world'))
    shapes, box, triangle = world.obstacles
    lo, hi = _bounds(shapes)
    assert lo == pytest.approx((-2.0, -1.7)) and hi == pytest.approx((3.0, 1.3))
    edges = obstacle_edges(shapes)
    # the L wall's leg x [1.0, 1.1] reaches up to y = 0.5 (rows near the image top are +y)
    leg = edges[np.isclose(edges[:, 0, 0], 1.0) & np.isclose(edges[:, 1, 0], 1.0)]
    assert leg[:, :, 1].max() == pytest.approx(0.5)
    assert leg[:, :, 1].min() == pytest.approx(-0.7)


def test_rotated_box_and_block_polygon_are_placed_as_stage_does():
    world = load_world(os.path.join(REFERENCE, 'ref_shapes.world'))
    _, box, triangle = world.obstacles
    assert box.ranger_return == 0.5
    corners = obstacle_edges(box)[:, 0, :]
    yaw = math.radians(30)
    expected = [(-0.9 + dx * math.cos(yaw) - dy * math.sin(yaw),
                 0.55 + dx * math.sin(yaw) + dy * math.cos(yaw))
                for dx, dy in ((-0.2, -0.15), (0.2, -0.15), (0.2, 0.15), (-0.2, 0.15))]
    assert corners == pytest.approx(np.array(expected))
    # points (0,0) (3,0) (0,2) scaled to 0.6 x 0.4 with the bounding box centred
    local = triangle.edges[:, 0, :]
    assert local == pytest.approx(np.array([[-0.3, -0.2], [0.3, -0.2], [-0.3, 0.2]]))
    assert triangle.z_range == pytest.approx((0.0, 0.5))


def test_define_chain_inherits_and_instances_override(tmp_path):
    path = _write(tmp_path, 'chain.world', '''
        define base_ranger ranger ( sensor ( range [ 0.2 5.0 ] fov 270 samples 271 ) )
        define laser base_ranger ( color "blue" )
        define base position ( size [ 0.3 0.2 0.1 ] drive "diff" laser ( pose [ 0.1 0 0 0 ] ) )
        define middle base ( velocity_bounds [ -1 1 0 0 0 0 -90 90 ] )
        define top middle ( color "red" )
        top ( name "bot" pose [ 1 2 0 90 ] size [ 0.5 0.4 0.1 ] )
        model ( name "wall" size [ 1 0.1 0.5 ] )
    ''')
    world = load_world(path)
    robot, = world.robots
    assert robot.name == 'bot'
    assert robot.size == pytest.approx((0.5, 0.4, 0.1))      # instance overrides
    assert robot.pose == pytest.approx((1.0, 2.0, math.pi / 2))
    assert robot.velocity_bounds[6:] == pytest.approx((-math.pi / 2, math.pi / 2))
    assert robot.ranger.fov == pytest.approx(math.radians(270))
    assert robot.ranger.samples == 271
    assert (robot.ranger.range_min, robot.ranger.range_max) == (0.2, 5.0)
    assert robot.ranger.pose == pytest.approx((0.1, 0.0, 0.0, 0.0))


def test_a_ranger_with_several_sensors_uses_the_first_as_stageros(tmp_path):
    path = _write(tmp_path, 'w.world', '''
        define base_ranger ranger ( sensor ( fov 180 samples 181 ) )
        define laser base_ranger ( sensor ( fov 90 samples 91 ) )
        position ( laser ( ) )
        model ( )
    ''')
    assert load_world(path).robots[0].ranger.samples == 181


def test_include_is_relative_to_the_including_file(tmp_path):
    os.makedirs(os.path.join(str(tmp_path), 'lib'))
    _write(tmp_path, os.path.join('lib', 'robot.inc'),
           'define bot position ( ranger ( sensor ( range [ 0 3 ] fov 90 samples 3 ) ) )\n')
    _write(tmp_path, os.path.join('lib', 'robots.inc'), 'include "robot.inc"\n')
    path = _write(tmp_path, 'w.world', 'include "lib/robots.inc"\nbot ( )\nmodel ( )\n')
    assert load_world(path).robots[0].ranger.samples == 3


def test_unknown_keywords_are_collected_not_fatal(tmp_path):
    path = _write(tmp_path, 'w.world', '''
        threads 2
        window ( size [ 100 100 ] scale 10 )
        model ( size [ 1 1 1 ] sparkle 3 )
        fiducial ( )
        position ( ranger ( sensor ( samples 2 ) ) blobfinder ( ) )
    ''')
    world = load_world(path)
    assert {'threads', 'sparkle', 'fiducial', 'blobfinder'} <= set(world.unknown_keywords)


def test_units_and_defaults_follow_stage(tmp_path):
    path = _write(tmp_path, 'w.world', '''
        interval_sim 50
        position ( ranger ( sensor ( samples 2 ) ) )
        model ( )
    ''')
    world = load_world(path)
    assert world.resolution == 0.02 and world.interval_sim == 0.05
    robot = world.robots[0]
    assert robot.size == (0.4, 0.4, 1.0)
    assert robot.velocity_bounds == STAGE_VELOCITY_BOUNDS
    assert (robot.ranger.range_min, robot.ranger.range_max) == (0.0, 5.0)
    assert world.obstacles[0].obstacle_return and world.obstacles[0].ranger_return == 1.0


def test_obstacle_return_zero_is_kept_as_passable(tmp_path):
    path = _write(tmp_path, 'w.world', 'model ( obstacle_return 0 ranger_return -1 )\n')
    obstacle, = load_world(path).obstacles
    assert not obstacle.obstacle_return and obstacle.ranger_return == -1.0


def test_bitmap_bounding_box_of_black_pixels_fills_size(tmp_path):
    name = _square_png(tmp_path, size=20, margin=5)
    path = _write(tmp_path, 'w.world',
                  'model ( bitmap "%s" size [ 2 4 1 ] pose [ 1 1 0 0 ] )\n' % name)
    lo, hi = _bounds(load_world(path).obstacles[0])
    assert lo == pytest.approx((0.0, -1.0)) and hi == pytest.approx((2.0, 3.0))


MALFORMED = [
    ('unbalanced.world', '\nmodel\n(\n  size [ 1 1 1 ]\n', 2, 'unbalanced parenthesis'),
    ('extra_close.world', 'model ( )\n)\n', 2, 'unbalanced parenthesis'),
    ('tuple.world', 'model ( size [ 1 1 1 )\n', 1, 'tuple'),
    ('bad_number.world', 'resolution 0.0.2\n', 1, 'bad number'),
    ('short_tuple.world', 'model (\n pose [ 1 2 3 ]\n)\n', 2, '"pose" needs 4 values'),
    ('bitmap.world', 'model\n(\n  bitmap "nowhere.png"\n)\n', 3, 'missing bitmap file'),
    ('parent.world', '\n\ndefine thing gadget ( )\nthing ( )\n', 3, 'unknown define parent'),
    ('include.world', 'resolution 0.02\ninclude "absent.inc"\n', 2, 'include not found'),
    ('string.world', 'model ( name "open\n)\n', 1, 'unterminated string'),
    ('define.world', 'define only_name\n', 1, 'define'),
    ('syntax.world', 'model ( [ 1 2 ] )\n', 1, 'syntax error'),
    ('drive.world', 'position ( drive "omni" )\n', 1, 'drive "omni"'),
]


@pytest.mark.parametrize('name,text,line,problem', MALFORMED, ids=[m[0] for m in MALFORMED])
def test_malformed_file_fails_with_file_line_and_problem(tmp_path, name, text, line, problem):
    path = _write(tmp_path, name, text)
    with pytest.raises(WorldFileError) as caught:
        load_world(path)
    message = str(caught.value)
    assert message.startswith('%s:%d: ' % (path, line)), message
    assert problem in message
    assert '\n' not in message


def test_error_inside_an_include_names_the_included_file(tmp_path):
    inc = _write(tmp_path, 'broken.inc', 'define a model (\n  size [ 1 x 1 ]\n  size [ 1 1 1 ] (\n')
    path = _write(tmp_path, 'w.world', 'include "broken.inc"\n')
    with pytest.raises(WorldFileError) as caught:
        load_world(path)
    assert str(caught.value).startswith(inc + ':')


def test_missing_world_file(tmp_path):
    path = os.path.join(str(tmp_path), 'none.world')
    with pytest.raises(WorldFileError) as caught:
        load_world(path)
    assert str(caught.value).startswith(path + ':')
