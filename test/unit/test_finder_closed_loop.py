"""The find-wall behaviour in a closed loop with the built-in simulator (no ROS).

scan -> ScanView -> WallFinder -> clamp -> simulator, once per 0.1 s world
update, as the service node runs it against stage_sim in lockstep. Scored
from ground truth against the world's exact edges, as the benchmark does.
"""
import math
import os

import numpy as np
import pytest

from generated_worlds import write_generated
from wall_follower.control.course.finder import WallFinder
from wall_follower.control.motion import MAX_ANGULAR, MAX_LINEAR, clamp
from wall_follower.control.sensing.scan import ScanView
from wall_follower.evaluation.grading.criteria import FIND_WALL_DISTANCE, FIND_WALL_HEADING
from wall_follower.evaluation.scoring.course import CourseMap
from wall_follower.evaluation.scoring.geometry import cast_rays, solid_edges
from wall_follower.params import defaults
from wall_follower.params.course.wall_finder import FINDER
from wall_follower.sim.engine import Simulation
from wall_follower.sim.worldfile import load_world

WORLDS = os.path.join(os.path.dirname(__file__), '..', '..', 'worlds')
WORLD = os.path.join(WORLDS, 'obstacles.world')
LASER_X = -0.032  # the Burger of worlds/burger.inc
TIME_LIMIT = 20.0
WALL_DISTANCE = defaults(FINDER)['wall_distance']
TURN_ROOM = defaults(FINDER)['turn_room']
# Stage's grid cell in the generated worlds [m]: how much nearer a wall may stand than read.
GRID_CELL = 0.02

POSES = {
    'world start, wall on the right at 0.25 m': (-1.75, 0.8, -math.pi / 2),
    'facing away from the nearest wall': (1.0, 1.1, -math.pi / 2),
    'in a corner': (-1.7, -1.2, -2.4),
    'next to the free-standing box': (0.3, -0.6, 0.0),
    # Here Stage's grid makes the fitted wall jump 2 deg as the robot turns
    # a fraction of that: aiming for the tolerance's middle, the robot
    # turned to and fro across it until the call timed out.
    'between the right wall and a pillar': (1.7, 0.6, 0.0),
}


def find_wall(pose, profile, world=WORLD, seed=3):
    """Run one search (seed: the simulator's, for the laser's noise); returns (finder,
    seconds, final true pose, stalled, commands)."""
    sim = Simulation(load_world(world), laser_profile=profile, seed=seed, poses={0: pose})
    finder = WallFinder(laser_x=LASER_X)
    finder.start()
    stalled, commands = False, []
    while not finder.done and sim.time < TIME_LIMIT:
        robot = sim.step().robots[0]
        stalled = stalled or robot.stalled
        scan = robot.scan
        view = ScanView(scan.ranges, scan.angle_min, scan.angle_increment,
                        scan.range_min, scan.range_max)
        command = clamp(finder.update(view))
        commands.append(command)
        sim.set_command(0, command.linear, command.angular)
    elapsed = sim.time
    # The last commands still act for an update or two: score the pose at rest.
    for _ in range(3):
        robot = sim.step(with_scans=False).robots[0]
        stalled = stalled or robot.stalled
    truth = robot.ground_truth
    return finder, elapsed, (truth.x, truth.y, truth.yaw), stalled, commands


@pytest.fixture(scope='module')
def course_map():
    return CourseMap(WORLD)


@pytest.mark.parametrize('profile', ['stage', 'lds01'])
@pytest.mark.parametrize('start', sorted(POSES))
def test_ends_parallel_at_wall_distance_from_the_wall_on_its_right(course_map, start, profile):
    finder, elapsed, pose, stalled, commands = find_wall(POSES[start], profile)
    assert finder.success, finder.failure_reason
    assert elapsed <= TIME_LIMIT
    distance = course_map.right_wall_distance(pose)
    _, heading_error = course_map.right_wall_alignment(pose)
    assert distance == pytest.approx(WALL_DISTANCE, abs=0.015)
    assert abs(math.degrees(heading_error)) <= 3.0
    assert not stalled
    assert max(abs(c.linear) for c in commands) <= MAX_LINEAR
    assert max(abs(c.angular) for c in commands) <= MAX_ANGULAR


@pytest.mark.parametrize('profile', ['stage', 'lds01'])
@pytest.mark.parametrize('start', sorted(POSES))
def test_a_second_call_from_where_the_first_ended_answers_at_once(course_map, start, profile):
    first, _, pose, _, _ = find_wall(POSES[start], profile)
    assert first.success, first.failure_reason
    finder, elapsed, second_pose, stalled, commands = find_wall(pose, profile)
    assert finder.success, finder.failure_reason
    turned = sum(abs(c.angular) for c in commands) * 0.1
    assert math.degrees(turned) <= 3.0, 'turned %.0f deg' % math.degrees(turned)
    # At most a straighten-up of a few scans: where the first call ended on
    # crossing the heading it aimed for, a noisy laser may read it just
    # outside the tolerance.
    assert elapsed <= 1.0
    assert course_map.right_wall_distance(second_pose) == pytest.approx(WALL_DISTANCE, abs=0.015)
    assert not stalled


def generated(directory, seed, index):
    """The generator's world index of seed written into directory: (its path, its start)."""
    path, world = write_generated(directory, seed, index)
    return path, world.start


def assert_found(path, start, profile='stage', seed=3):
    """A search from start in the world at path, with the laser profile and the simulator's
    seed, ends beside a wall as the grader asks; the pose it ends at."""
    finder, elapsed, pose, stalled, _ = find_wall(start, profile, path, seed)
    assert finder.success, finder.failure_reason or 'no answer within %.0f s' % elapsed
    distance, heading_error = CourseMap(path).right_wall_alignment(pose)
    low, high = FIND_WALL_DISTANCE
    assert low <= distance <= high
    assert abs(heading_error) <= FIND_WALL_HEADING
    assert not stalled
    return pose


def test_among_slanted_walls_and_islands_it_first_drives_to_where_a_wall_is_seen_across(tmp_path):
    # Generated world 7 of seed 3: from its start, beside a slanted bar, every
    # wall in sight has the point straight across from the robot round its
    # end or behind something; the search once failed there at once ("no
    # wall in range"), and the grader's lap never began.
    assert_found(*generated(tmp_path, 3, 7))


def test_a_slanted_wall_read_in_steps_wider_than_the_tolerance_still_ends_the_approach(tmp_path):
    # Generated world 20 of seed 7: approaching a wall at a slant to Stage's
    # grid, the reading steps between 0.298 and 0.327 m either side of the
    # target, 1.5 cm off each way; the approach once drove to and fro across
    # it until the call timed out. Read at that slant, the wall is where the
    # grader asks, if not within this file's tighter tolerance.
    assert_found(*generated(tmp_path, 7, 20))


def test_the_way_to_a_wall_is_clear_from_where_the_robot_turns_not_from_its_laser(tmp_path):
    # Generated world 27 of seed 28: from its start, the wall chosen lay
    # east, with a ledge 0.17 m beside the way there as the laser, 3 cm
    # behind the rotation centre, saw it; turned to face east on the spot,
    # the robot drove 0.13 m from the ledge, and turning on the spot again
    # to put the wall on its right, swung its tail into it and stuck there
    # until the call timed out.
    assert_found(*generated(tmp_path, 28, 27))


def test_aligned_beside_a_walls_end_it_slides_along_until_the_grader_reads_the_wall(tmp_path):
    # Generated world 19 of seed 41: the wall chosen from the start ends 0.16 m
    # behind where the laser came to rest, and the grader's sector, 30 degrees
    # either side of the right, read past its end a wall 0.97 m away: 0.21 m and
    # 40 degrees off. The search now slides on along the wall before it ends.
    assert_found(*generated(tmp_path, 41, 19))


def room_ahead(path, pose):
    """How far the nearest wall ahead of the rotation centre at pose lies from it, looking
    from 60 degrees right of the heading round to its left: the wall on the right, 60
    degrees off, reads some way past turn_room."""
    angles = pose[2] + np.radians(np.arange(-60.0, 90.5, 0.5))
    return float(np.min(cast_rays(solid_edges(load_world(path)), pose[0], pose[1], angles)))


@pytest.mark.parametrize('profile', ['stage', 'lds01', 'lds02', 'gazebo', 'course720'])
def test_in_a_sharp_corner_it_backs_out_until_the_laps_first_turn_has_room(tmp_path, profile):
    # Generated world 30 of seed 129: the wall chosen from the start runs into
    # a corner of about 60 degrees. Aligned, the robot's centre was 0.19 m
    # from the corner's other wall, and the lap began with a quarter turn in
    # place onto it that read it at 0.18 m for two seconds (96 % in band).
    path, start = generated(tmp_path, 129, 30)
    pose = assert_found(path, start, profile)
    assert room_ahead(path, pose) >= TURN_ROOM - GRID_CELL


@pytest.mark.parametrize('profile, seed', [('stage', 3), ('lds01', 4), ('lds01', 7)])
def test_it_does_not_take_the_mouth_of_a_wing_for_the_wall_in_line_with_it(
        tmp_path, profile, seed):
    # Generated world 13 of seed 102: the nearest wall runs on, in line, either
    # side of a wing's mouth straight across from the start. Refitted to every
    # hit along its line, the wall seemed seen across the mouth; the search
    # drove into it, found no wall straight across there and failed, on
    # every laser. Seen as it is, the wall ends at the mouth; driving towards
    # a point of it end_margin inside that end, the search then stopped as
    # soon as the end came straight across, and with the LDS-01's noise
    # (these seeds among others) ended so near the end that the grader's
    # sector read into the wing.
    assert_found(*generated(tmp_path, 102, 13), profile=profile, seed=seed)


@pytest.mark.parametrize('profile', ['stage', 'lds01'])
def test_it_slides_on_until_the_wall_reads_past_the_graders_sector_on_a_grid(tmp_path, profile):
    # Generated world 13 of seed 112: the wall chosen ends 0.2 m ahead of
    # where the search came to rest, at a corner that Stage's grid, 2 cm a
    # cell, draws a little longer than the wall is. The laser's beams read
    # the wall all through right_sector there, while the grader's rays, 30
    # degrees either side of the right, graze past the corner itself and read
    # the far end of the corridor beyond it: 0.18 m and 54 degrees off, on
    # every laser.
    assert_found(*generated(tmp_path, 112, 13), profile=profile)


@pytest.mark.parametrize('seed', [0, 1, 116])
def test_a_far_wall_in_line_with_the_wall_ahead_does_not_take_its_place(tmp_path, seed):
    # Generated world 21 of seed 116, under the 720-beam laser: approaching the
    # wall ahead, the search also saw, 2.5 m to its right, a short piece of a far
    # wall lying on the same line. Matched by the line's angle and distance alone,
    # the piece fitted the wall being tracked better than the wall itself; tracked
    # from then on, it was soon lost, and with these seeds the search gave up:
    # "lost sight of the chosen wall 4 times".
    assert_found(*generated(tmp_path, 116, 21), profile='course720', seed=seed)
