"""The line worlds and their centrelines: the generator's output is what is shipped,
the drawn line lies where the course file says, lasers and bodies ignore it, and
line_track's distances are exact.
"""
import glob
import importlib.util
import math
import os
import textwrap

import numpy as np
import pytest

from wall_follower.control.motion import MAX_ANGULAR, MAX_LINEAR
from wall_follower.evaluation.scoring.line import speed_bound
from wall_follower.evaluation.scoring.line_track import (CourseError, course_path, load_centreline,
                                                         read_course, trace_path)
from wall_follower.evaluation.worlds import line_world
from wall_follower.sim.engine import Simulation
from wall_follower.sim.worldfile import load_world

REPO = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, os.pardir)
WORLDS = sorted(glob.glob(os.path.join(REPO, 'worlds', 'line_*.world')))
# The issue asks a lap of every closed line world at a mean speed of at least 0.15 m/s;
# each must allow that within the limits with room to spare for slowing into bends.
LEAST_SPEED_BOUND = 0.17


def _tool():
    spec = importlib.util.spec_from_file_location(
        'make_line_worlds', os.path.join(REPO, 'tools', 'make_line_worlds.py'))
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_three_line_worlds_one_of_them_open():
    closed = [load_centreline(path).closed for path in WORLDS]
    assert len(closed) >= 3
    assert closed.count(False) >= 1 and closed.count(True) >= 2


def test_shipped_worlds_are_what_the_generator_makes():
    assert _tool().main(['--check']) == 0


@pytest.mark.parametrize('path', WORLDS, ids=os.path.basename)
def test_line_is_drawn_where_its_centreline_is(path):
    """Every black pixel's centre lies within half a width (plus half a pixel's diagonal)
    of the centreline, and every point of the centreline is inside the line."""
    world = load_world(path)
    centreline = load_centreline(path)
    line = [o for o in world.obstacles if o.name == 'line'][0]
    assert not line.obstacle_return and line.ranger_return < 0
    assert line.color == (1.0, 1.0, 0.0)
    assert 0.04 <= centreline.width <= 0.05
    from PIL import Image
    pixel = line_world.LINE_PIXEL
    black = np.asarray(Image.open(path.replace('.world', '_line.png')).convert('L')) < 128
    rows, cols = black.shape
    # Stage puts the bitmap's black bounding box (here the whole image) on `size` at `pose`.
    edges = line.edges.reshape(-1, 2)
    left, top = line.pose[0] + edges[:, 0].min(), line.pose[1] + edges[:, 1].max()
    assert (edges[:, 0].max() - edges[:, 0].min()) == pytest.approx(cols * pixel)
    r, c = np.nonzero(black)
    x, y = left + (c + 0.5) * pixel, top - (r + 0.5) * pixel
    assert centreline.distance(x, y).max() <= centreline.width / 2 + pixel * 0.71
    on_line = centreline.points[::50]
    col = np.floor((on_line[:, 0] - left) / pixel).astype(int)
    row = np.floor((top - on_line[:, 1]) / pixel).astype(int)
    assert black[row, col].all()


@pytest.mark.parametrize('path', WORLDS, ids=os.path.basename)
def test_robot_is_a_waffle_pi_on_the_line_with_a_raspicam(path):
    robot = load_world(path).robots[0]
    assert robot.size == pytest.approx((0.281, 0.306, 0.141))
    camera = robot.camera
    assert [math.degrees(a) for a in camera.fov] == pytest.approx([62.2, 48.8])
    assert camera.height > robot.size[2]
    assert camera.pantilt[1] > 0
    assert load_centreline(path).distance(robot.pose[0], robot.pose[1]) < 0.005


@pytest.mark.parametrize('path', [p for p in WORLDS if load_centreline(p).closed],
                         ids=os.path.basename)
def test_every_closed_line_allows_the_required_mean_speed_within_the_limits(path):
    assert speed_bound(load_centreline(path), MAX_LINEAR, MAX_ANGULAR) >= LEAST_SPEED_BOUND


def _arcs(path):
    """(radius, angle_deg) of every arc of a world's course."""
    return [(float(piece[1]), float(piece[2])) for piece in read_course(course_path(path))['path']
            if piece[0] == 'arc']


def test_line_tight_has_the_tightest_bends_and_bends_both_ways():
    tight = os.path.join(REPO, 'worlds', 'line_tight.world')
    radii = {path: min(radius for radius, _ in _arcs(path)) for path in WORLDS}
    assert all(radii[tight] <= radius for radius in radii.values())
    angles = [angle for _, angle in _arcs(tight)]
    assert min(angles) < 0 < max(angles)
    assert any(abs(angle) == 60 for angle in angles)


def test_lasers_and_bodies_ignore_the_line():
    path = os.path.join(REPO, 'worlds', 'line_lab.world')
    world = load_world(path)
    bare = world._replace(obstacles=[o for o in world.obstacles if o.name != 'line'])
    # Facing across the line's bottom straight (y = -1.0), 0.2 m before it.
    pose = {0: (-0.5, -1.2, math.pi / 2)}
    with_line, without = Simulation(world, poses=pose), Simulation(bare, poses=pose)
    scan, bare_scan = with_line.step().robots[0].scan, without.step().robots[0].scan
    angles = scan.angle_min + scan.angle_increment * np.arange(len(scan.ranges))
    ahead = np.abs(angles) < math.radians(30)
    # The beams ahead cross the line 0.2 m away and reach the far wall, 2.7 m away.
    assert (scan.ranges[ahead] > 2.0).all()
    # The line's cells only change where Stage's cell-stepping lands (a cell or two).
    both = (scan.ranges < scan.range_max) & (bare_scan.ranges < scan.range_max)
    assert np.abs(scan.ranges - bare_scan.ranges)[both].max() <= 2 * world.resolution
    for _ in range(20):
        with_line.set_command(0, 0.19, 0.0)
        frame = with_line.step(with_scans=False)
        assert not frame.robots[0].stalled
    assert frame.robots[0].ground_truth.y > -0.85


def test_distances_are_exact():
    centreline = load_centreline(os.path.join(REPO, 'worlds', 'line_lab.world'))
    # The first straight runs along y = -1 from x = -1 to 1; the first bend is a
    # quarter circle of 0.5 m about (1, -0.5).
    assert centreline.distance(0.0, -0.9) == pytest.approx(0.1, abs=1e-9)
    assert centreline.distance(0.0, -1.03) == pytest.approx(0.03, abs=1e-9)
    corner = (1.0 + 0.3 * math.cos(-0.7), -0.5 + 0.3 * math.sin(-0.7))
    assert centreline.distance(*corner) == pytest.approx(0.2, abs=1e-6)
    distances, along = centreline.nearest(np.array([0.0, 0.5]), np.array([-1.0, -1.2]))
    assert distances == pytest.approx([0.0, 0.2], abs=1e-9)
    assert along == pytest.approx([1.0, 1.5], abs=1e-9)
    assert centreline.closed and centreline.end == centreline.start
    assert centreline.length == pytest.approx(
        2.0 + 2 * 1.0 + 4 * 0.25 * math.pi + 0.3 + 0.5686291501015
        + 4 * 0.4 * math.pi / 4, abs=1e-6)


def test_open_line_has_an_end():
    centreline = load_centreline(os.path.join(REPO, 'worlds', 'line_open.world'))
    assert not centreline.closed
    end = centreline.end
    assert math.hypot(end[0] - centreline.start[0], end[1] - centreline.start[1]) > 1.0
    assert centreline.distance_to_end(end[0] + 0.3, end[1] + 0.4) == pytest.approx(0.5)


def test_trace_turns_left_for_positive_angles():
    points = trace_path((0.0, 0.0, 0.0), [['arc', 1.0, 90]])
    assert points[-1] == pytest.approx([1.0, 1.0], abs=1e-9)
    points = trace_path((0.0, 0.0, 0.0), [['arc', 1.0, -90]])
    assert points[-1] == pytest.approx([1.0, -1.0], abs=1e-9)


@pytest.mark.parametrize('text, words', [
    ('start: [0, 0, 0]\nwidth: 0.04\n', 'missing key "path"'),
    ('start: [0, 0, 0]\nwidth: 0.04\npath: [[straight, -1]]\n', 'straight'),
    ('start: [0, 0, 0]\nwidth: 0.04\npath: [[wiggle, 1]]\n', 'wiggle'),
    ('start: [0, 0, 0]\nwidth: 0.04\nclosed: true\npath: [[straight, 1]]\n', 'closed'),
    ('[1, 2\n', 'not YAML'),
])
def test_bad_course_file_is_a_one_line_error(tmp_path, text, words):
    path = os.path.join(str(tmp_path), 'bad.course.yaml')
    with open(path, 'w') as stream:
        stream.write(textwrap.dedent(text))
    with pytest.raises(CourseError) as error:
        load_centreline(path)
    assert words in str(error.value) and 'bad.course.yaml' in str(error.value)


def test_course_file_sits_beside_its_world():
    assert course_path('/a/b/line_x.world') == '/a/b/line_x.course.yaml'
    with pytest.raises(CourseError):
        load_centreline('/nonexistent/line_x.world')
