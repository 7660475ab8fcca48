"""The grader's generated line courses (evaluation/worlds/line_courses.py): named by (seed,
index) on every machine, of every kind, fit to follow, and drawn as the world the
simulator loads with the camera the course names.
"""
import math
import os

import numpy as np
import pytest
import yaml

from wall_follower.control.motion import MAX_ANGULAR, MAX_LINEAR
from wall_follower.evaluation.scoring.line import speed_bound
from wall_follower.evaluation.scoring.line_track import centreline_of, load_centreline
from wall_follower.evaluation.worlds import line_courses
from wall_follower.evaluation.worlds.line_courses import (KINDS, LineGenerationError,
                                                          camera_from_keys, course_problems,
                                                          generate_line, write_line_world)
from wall_follower.evaluation.worlds.line_world import MARGIN
from wall_follower.sim.worldfile import load_world

REPO = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, os.pardir)
CASES = [(seed, index) for seed in (0, 1, 7) for index in range(6)]


def arcs(course):
    return [(float(p[1]), float(p[2])) for p in course['path'] if p[0] == 'arc']


def test_the_same_seed_and_index_give_the_same_course():
    assert generate_line(3, 4) == generate_line(3, 4)
    assert generate_line(3, 4) != generate_line(4, 4)
    assert generate_line(3, 4).name == 'line_s3_004'


def test_every_three_courses_hold_a_loop_a_tight_loop_and_an_open_line():
    assert [generate_line(5, i).kind for i in range(6)] == list(KINDS) * 2
    assert not centreline_of(generate_line(5, 2).course).closed


@pytest.mark.parametrize('seed, index', CASES)
def test_every_course_is_fit_to_follow(seed, index):
    line_course = generate_line(seed, index)
    course = line_course.course
    assert course_problems(course) == []
    centreline = centreline_of(course)
    assert centreline.distance(*course['robot'][:2]) < 1e-6
    radii = [radius for radius, _ in arcs(course)]
    if line_course.kind == 'tight':
        assert max(radii) <= 0.40 and min(radii) >= 0.35
    if centreline.closed:
        assert speed_bound(centreline, MAX_LINEAR, MAX_ANGULAR) >= line_courses.LEAST_SPEED_BOUND
    camera = line_course.camera
    assert camera.resolution in line_courses.RESOLUTIONS
    assert 50.0 <= camera.fov[0] <= 75.0 and camera.fov[1] < camera.fov[0]
    assert 0.12 <= camera.height <= 0.20
    # The top of the image sees the floor, the bottom the floor beyond the robot's body:
    # where its lowest row meets the body's top height, it is ahead of the body's front.
    assert camera.tilt > camera.fov[1] / 2.0
    lowest = math.radians(camera.tilt + camera.fov[1] / 2.0)
    assert camera.height / math.tan(lowest) >= line_courses.BODY_FRONT


def test_the_cameras_differ_in_resolution_field_of_view_height_and_tilt():
    cameras = [generate_line(seed, index).camera for seed, index in CASES]
    for field in range(4):
        assert len(set(camera[field] for camera in cameras)) > 2


def test_tight_loops_bend_both_ways_and_loops_go_both_ways_round():
    turns = [np.sign([angle for _, angle in arcs(generate_line(seed, 1).course)])
             for seed in range(8)]
    assert any(t.min() < 0 < t.max() for t in turns)
    assert {int(np.sign(np.sum(t))) for t in turns} == {-1, 1}


def test_a_line_that_comes_back_near_itself_is_refused():
    # Two straights 0.3 m apart, joined by a U-turn of 0.15 m radius.
    course = {'start': [0.0, 0.0, 0.0], 'closed': False, 'width': 0.045,
              'path': [['straight', 1.5], ['arc', 0.15, 180.0], ['straight', 1.5]]}
    (problem,) = course_problems(course)
    assert problem.startswith('the line passes within 0.40 m of itself at (')


def test_a_loop_too_tight_for_the_required_speed_is_refused():
    course = {'start': [0.0, 0.0, 0.0], 'closed': True, 'width': 0.045,
              'path': [['straight', 0.5], ['arc', 0.3, 90.0]] * 4}
    problems = course_problems(course)
    assert len(problems) == 1 and problems[0].startswith('its best mean speed within the limits')


def test_a_room_no_course_fits_is_refused():
    with pytest.raises(LineGenerationError):
        generate_line(0, 0, room=(0.5, 0.6), attempts=20)


@pytest.mark.parametrize('index', range(3))
def test_the_world_written_is_the_course_with_its_camera(tmp_path, index):
    line_course = generate_line(2, index)
    path = write_line_world(line_course, str(tmp_path), os.path.join(REPO, 'worlds'), 2, index)
    world = load_world(path)
    line = [o for o in world.obstacles if o.name == 'line'][0]
    assert not line.obstacle_return and line.ranger_return < 0
    robot = world.robots[0]
    camera = robot.camera
    wanted = line_course.camera
    assert tuple(camera.resolution) == wanted.resolution
    assert [math.degrees(a) for a in camera.fov] == pytest.approx(list(wanted.fov), abs=0.01)
    assert math.degrees(camera.pantilt[1]) == pytest.approx(wanted.tilt, abs=0.01)
    assert camera.height == pytest.approx(robot.size[2] + wanted.height, abs=1e-6)
    # The course file beside the world is the one it was drawn from, camera included.
    centreline = load_centreline(path)
    assert centreline.length == pytest.approx(centreline_of(line_course.course).length)
    assert centreline.distance(robot.pose[0], robot.pose[1]) < 0.001
    with open(path[:-len('.world')] + '.course.yaml') as stream:
        keys = yaml.safe_load(stream)
    assert camera_from_keys(keys['camera']) == wanted and keys['kind'] == line_course.kind
    # Walls stand MARGIN beyond the line: an open line's end is that far from any.
    walls = {o.name: o.pose for o in world.obstacles if o.name.startswith('wall')}
    assert sorted(walls) == ['wall_east', 'wall_north', 'wall_south', 'wall_west']
    assert os.path.isfile(os.path.join(str(tmp_path), 'waffle.inc'))
    x, y = centreline.points.T
    assert walls['wall_west'][0] < x.min() - MARGIN and walls['wall_east'][0] > x.max() + MARGIN
    assert walls['wall_south'][1] < y.min() - MARGIN and walls['wall_north'][1] > y.max() + MARGIN
