"""The find-wall state machine on synthetic scans, in every laser convention."""
import math

import numpy as np
import pytest

from laser_conventions import CONVENTIONS, LDS01, STAGE, Convention, box, cast, scan_view
from wall_follower.control.course import finder
from wall_follower.control.course.finder import WallFinder
from wall_follower.control.motion import MAX_ANGULAR, MAX_LINEAR, STOP, clamp
from wall_follower.control.sensing.scan import ScanView
from wall_follower.evaluation.scoring.course import RIGHT_SECTOR
from wall_follower.params import defaults
from wall_follower.params.course.wall_finder import FINDER
from wall_follower.rotation import wrap_angle

LASER_X = -0.032  # TurtleBot3 Burger: the laser 32 mm behind the axle
ROOM = box(-2.0, -1.5, 2.0, 1.5)
WALL_DISTANCE = defaults(FINDER)['wall_distance']
DT = 0.1


def laser_pose(pose):
    x, y, yaw = pose
    return x + LASER_X * math.cos(yaw), y + LASER_X * math.sin(yaw), yaw


def drive(world, pose, convention, limit=60.0, scan=scan_view, **params):
    """Run a finder (laser_x, and params) in a kinematic loop (commands act one step late, as
    in Stage), on the views scan(world, laser pose, convention) gives.

    Returns the finder, the states in the order visited, every command, the
    final robot pose and the time taken.
    """
    walker = WallFinder(laser_x=LASER_X, **params)
    walker.start()
    x, y, yaw = pose
    command = STOP
    states, commands = [walker.state], []
    t = 0.0
    while not walker.done and t < limit:
        view = scan(world, laser_pose((x, y, yaw)), convention)
        x += command.linear * DT * math.cos(yaw)
        y += command.linear * DT * math.sin(yaw)
        yaw += command.angular * DT
        command = walker.update(view)
        commands.append(command)
        if walker.state != states[-1]:
            states.append(walker.state)
        t += DT
    return walker, states, commands, (x, y, yaw), t


def right_wall_error(world_box, pose):
    """(distance from the laser to the nearest side wall, heading error) for a box room."""
    x0, y0, x1, y1 = world_box
    lx, ly, yaw = laser_pose(pose)
    distances = [lx - x0, x1 - lx, ly - y0, y1 - ly]
    nearest = int(np.argmin(distances))
    # Heading that puts that wall on the right (wall normal at -90 deg).
    normal_directions = [math.pi, 0.0, -math.pi / 2, math.pi / 2]
    wanted = normal_directions[nearest] + math.pi / 2
    error = (yaw - wanted + math.pi) % (2 * math.pi) - math.pi
    return distances[nearest], error


def ids(conventions):
    return [c.name for c in conventions]


@pytest.mark.parametrize('convention', CONVENTIONS, ids=ids(CONVENTIONS))
@pytest.mark.parametrize('pose', [
    (0.4, 0.3, 0.3),            # open floor, nearest wall behind-left
    (1.2, 0.2, math.pi),        # facing away from the nearest wall
    (-1.5, -1.1, 0.8),          # near a corner
], ids=['open', 'facing-away', 'corner'])
def test_finds_aligns_and_stops_in_every_convention(convention, pose):
    walker, states, commands, final, _ = drive(ROOM, pose, convention)
    assert walker.success, walker.failure_reason
    assert states == [finder.CHOOSE_WALL, finder.ROTATE_TO_WALL, finder.APPROACH,
                      finder.ALIGN, finder.DONE]
    distance, heading_error = right_wall_error((-2.0, -1.5, 2.0, 1.5), final)
    assert distance == pytest.approx(WALL_DISTANCE, abs=0.01)
    assert abs(math.degrees(heading_error)) < 2.0
    assert commands[-1] == STOP
    assert all(clamp(c) == c for c in commands)


def test_commands_stay_within_the_real_robot_limits():
    _, _, commands, _, _ = drive(ROOM, (0.0, 0.0, 2.0), STAGE)
    assert max(abs(c.linear) for c in commands) <= MAX_LINEAR
    assert max(abs(c.angular) for c in commands) <= MAX_ANGULAR


@pytest.mark.parametrize('convention', CONVENTIONS, ids=ids(CONVENTIONS))
def test_turns_the_short_way_towards_the_nearest_wall(convention):
    walker = WallFinder(laser_x=LASER_X)
    walker.start()
    # Nearest wall (x = 2) is 0.8 m away on the robot's right (robot faces +y).
    command = walker.update(scan_view(ROOM, (1.2, 0.0, math.pi / 2), convention))
    assert walker.state == finder.ROTATE_TO_WALL
    assert walker.wall.distance == pytest.approx(0.8, abs=0.01)
    assert math.degrees(walker.wall.angle) == pytest.approx(-90.0, abs=1.0)
    assert command.linear == 0.0 and command.angular < 0.0


@pytest.mark.parametrize('convention', CONVENTIONS, ids=ids(CONVENTIONS))
def test_no_wall_in_range_fails_with_a_reason(convention):
    walker = WallFinder()
    walker.start()
    far = box(-50.0, -50.0, 50.0, 50.0)
    command = walker.update(scan_view(far, (0.0, 0.0, 0.0), convention))
    assert walker.state == finder.FAILED and not walker.success
    assert 'no wall in range' in walker.failure_reason
    assert command == STOP
    assert walker.update(scan_view(ROOM, (0.0, 0.0, 0.0), convention)) == STOP


def test_a_small_box_alone_is_not_a_wall():
    walker = WallFinder()
    walker.start()
    walker.update(scan_view(box(0.5, -0.15, 0.8, 0.15), (0.0, 0.0, 0.0), STAGE))
    assert walker.state == finder.FAILED


@pytest.mark.parametrize('convention', CONVENTIONS, ids=ids(CONVENTIONS))
def test_a_spurious_short_beam_does_not_win(convention):
    pose = (1.0, 0.0, 0.0)  # the x = 2 wall 1.0 m ahead, others 1.5 m or more away
    ranges = cast(ROOM, pose, convention)
    angles = convention.angle_min + convention.increment * np.arange(convention.count)
    beam = int(np.argmin(np.abs(np.angle(np.exp(1j * (angles - 2.5))))))
    ranges[beam] = 0.2
    view = ScanView(ranges, convention.angle_min, convention.increment,
                    convention.range_min, convention.range_max)
    walker = WallFinder()
    walker.start()
    walker.update(view)
    assert walker.wall.distance == pytest.approx(1.0, abs=0.01)
    assert walker.wall.angle == pytest.approx(0.0, abs=0.02)


@pytest.mark.parametrize('convention', CONVENTIONS, ids=ids(CONVENTIONS))
def test_a_small_box_nearer_than_a_wall_does_not_win(convention):
    # A 0.3 m box 0.4 m to the left, the x = 2 wall 1.2 m ahead.
    world = ROOM + box(0.7, 0.4, 1.0, 0.7)
    walker = WallFinder()
    walker.start()
    walker.update(scan_view(world, (0.8, 0.0, 0.0), convention))
    assert walker.state == finder.ROTATE_TO_WALL or walker.state == finder.APPROACH
    assert walker.wall.distance == pytest.approx(1.2, abs=0.01)


def test_a_wall_behind_an_obstacle_is_passed_over_for_a_clear_one():
    # The nearest wall (y = -1.5, 0.6 m away) has a box in the way;
    # the x = 2 wall, 0.9 m away, is clear.
    world = ROOM + box(0.9, -1.2, 1.3, -0.95)
    walker = WallFinder()
    walker.start()
    walker.update(scan_view(world, (1.1, -0.6, 0.0), STAGE))
    assert walker.wall.distance == pytest.approx(0.9, abs=0.01)


def test_approach_slows_near_the_target_and_backs_off_when_too_close():
    speeds = {}
    for distance in (1.0, 0.40, 0.36, 0.2):  # laser to wall
        walker = WallFinder(laser_x=LASER_X)
        walker.start()
        command = walker.update(scan_view(ROOM, (2.0 - distance, 0.0, 0.0), STAGE))
        assert walker.state == finder.APPROACH
        speeds[distance] = command.linear
    assert speeds[1.0] == pytest.approx(0.19, abs=0.002)
    assert 0.0 < speeds[0.36] < speeds[0.40] < speeds[1.0]
    assert speeds[0.2] < 0.0


def test_at_the_approach_distance_it_turns_left_to_put_the_wall_on_the_right():
    walker = WallFinder(laser_x=LASER_X)
    walker.start()
    # The laser wall_distance - laser_x from the wall ahead: the approach is already over.
    command = walker.update(scan_view(ROOM, (2.0 - WALL_DISTANCE + LASER_X, 0.0, 0.0), STAGE))
    assert walker.state == finder.ALIGN
    assert command.linear == 0.0 and command.angular > 0.0


def test_already_in_place_it_answers_at_once():
    walker = WallFinder(laser_x=LASER_X)
    walker.start()
    # The wall wall_distance on the right and 0.5 deg off parallel: nothing to do.
    aligned = scan_view(ROOM, laser_pose((0.0, -1.5 + WALL_DISTANCE, 0.009)), STAGE)
    assert walker.update(aligned) == STOP
    assert walker.state == finder.DONE and walker.success
    assert walker.failure_reason is None


def test_dropouts_among_the_beams_that_read_the_wall_are_no_end_to_slide_from():
    # An LDS-01 reads 0.0 for a beam that drops out, a few of the tens
    # within right_sector of the right at a time. Aligned beside a wall that
    # goes on for metres, two such behind the right once sent the robot
    # sliding forward, away from an end that was not there.
    def with_dropouts(segments, pose, convention):
        view = scan_view(segments, pose, convention)
        ranges = np.array(view.ranges)
        for behind in (math.radians(-100.0), math.radians(-110.0)):
            ranges[np.argmin(np.abs(wrap_angle(view.angles - behind)))] = 0.0
        return ScanView(ranges, convention.angle_min, convention.increment,
                        convention.range_min, convention.range_max)
    walker, states, _, _, _ = drive(ROOM, (0.0, -1.5 + WALL_DISTANCE, 0.2), LDS01,
                                    scan=with_dropouts)
    assert walker.success, walker.failure_reason
    assert finder.ALIGN in states and finder.SLIDE not in states


@pytest.mark.parametrize('off, in_place', [(0.015, True), (-0.015, True), (0.03, False)])
def test_a_call_where_a_search_ended_answers_at_once_despite_the_grid(off, in_place):
    # Stage reads a wall up to a grid cell long, by a different amount on each
    # side of the robot: where a search ended may read a cell or so off.
    walker = WallFinder(laser_x=LASER_X)
    walker.start()
    walker.update(scan_view(ROOM, laser_pose((0.0, -1.5 + WALL_DISTANCE + off, 0.0)), STAGE))
    assert (walker.state == finder.DONE) == in_place


def test_nearly_in_place_it_straightens_up_without_the_full_dance():
    walker = WallFinder(laser_x=LASER_X)
    walker.start()
    command = walker.update(scan_view(ROOM, laser_pose((0.0, -1.5 + WALL_DISTANCE, 0.1)), STAGE))
    assert walker.state == finder.ALIGN
    assert command.linear == 0.0 and command.angular < 0.0


def test_losing_the_wall_stops_then_chooses_again_then_fails():
    walker = WallFinder(lost_updates=2, max_reacquire=1)
    walker.start()
    walker.update(scan_view(ROOM, (1.2, 0.0, math.pi / 2), STAGE))
    empty = scan_view([], (0.0, 0.0, 0.0), STAGE)
    assert walker.update(empty) == STOP
    assert walker.state == finder.ROTATE_TO_WALL
    walker.update(empty)
    assert walker.state == finder.CHOOSE_WALL
    walker.update(scan_view(ROOM, (1.2, 0.0, math.pi / 2), STAGE))
    walker.update(empty)
    walker.update(empty)
    assert walker.state == finder.FAILED
    assert 'lost sight' in walker.failure_reason


def test_start_forgets_the_previous_run():
    walker = WallFinder()
    assert walker.update(scan_view(ROOM, (0.0, 0.0, 0.0), STAGE)) == STOP  # not started
    walker.start()
    walker.update(scan_view([], (0.0, 0.0, 0.0), STAGE))
    assert walker.state == finder.FAILED
    walker.start()
    assert walker.state == finder.CHOOSE_WALL and walker.failure_reason is None
    walker.update(scan_view(ROOM, (0.0, 0.0, 0.0), STAGE))
    assert walker.state == finder.ROTATE_TO_WALL


def test_unknown_parameters_are_refused():
    with pytest.raises(ValueError):
        WallFinder(wall_distanse=0.3)


def test_a_wall_ending_just_beside_the_robot_is_passed_over_for_one_that_goes_on():
    # A free-standing wall 0.5 m ahead ends 0.1 m to the left of the point
    # straight ahead: the robot would end at its corner. The room's walls,
    # 1.5 m away, go on for metres either side.
    world = ROOM + [((0.5, -1.0), (0.5, 0.1))]
    walker = WallFinder()
    walker.start()
    walker.update(scan_view(world, (0.0, 0.0, 0.0), STAGE))
    assert walker.wall.distance == pytest.approx(1.5, abs=0.01)


def test_a_wall_partly_hidden_by_a_box_still_counts_where_it_is_seen():
    # The bottom wall, 1.5 m away, is seen only up to 0.18 m past the point
    # straight below the robot: a box hides the rest. The wall goes on
    # behind the box, so it is no corner and beats the walls 2 m away. The
    # laser sits at the rotation centre, so that the box stands 0.16 m off
    # the way down there, just outside the corridor that must be clear.
    world = box(-2.0, -1.5, 2.0, 2.0) + box(0.16, -1.45, 0.46, -1.3)
    walker = WallFinder(laser_x=0.0)
    walker.start()
    walker.update(scan_view(world, (0.0, 0.0, 0.0), STAGE))
    assert walker.wall.distance == pytest.approx(1.5, abs=0.01)
    assert math.degrees(walker.wall.angle) == pytest.approx(-90.0, abs=1.0)


def test_a_wall_is_judged_by_where_the_laser_ends_beside_it_not_by_where_it_starts():
    # A free-standing wall 0.5 m ahead starts 0.22 m to the right of the laser's
    # foot on it, more than end_margin. The robot drives there from its rotation
    # centre and turns left at the wall, which leaves its laser 32 mm back towards
    # that start: 0.19 m from it, short of the margin. The room's walls, 1.5 m
    # away, go on for metres either side.
    world = ROOM + [((0.5, -0.22), (0.5, 1.0))]
    walker = WallFinder(laser_x=LASER_X)
    walker.start()
    walker.update(scan_view(world, (0.0, 0.0, 0.0), STAGE))
    assert walker.wall.distance == pytest.approx(1.5, abs=0.01)


# The grader reads the wall on the right within RIGHT_SECTOR of straight right, from up to
# 0.3 m: the wall must go on this far [m] either side of the laser.
JUDGED_REACH = 0.3 * math.tan(RIGHT_SECTOR)


@pytest.mark.parametrize('convention', CONVENTIONS, ids=ids(CONVENTIONS))
@pytest.mark.parametrize('wall_x', [(-0.15, 3.0), (-3.0, 0.05)], ids=['behind', 'ahead'])
def test_aligned_beside_a_walls_end_it_slides_along_the_wall_until_it_fills_the_right(
        convention, wall_x):
    # The only wall ends 0.15 m behind, or 0.05 m ahead of, the point straight
    # below the robot's centre: aligned there, the wall would read on only part
    # of the right.
    world = [((wall_x[0], -0.5), (wall_x[1], -0.5))]
    walker, states, _, end, _ = drive(world, (0.0, 0.0, -math.pi / 2), convention)
    assert walker.success, walker.failure_reason
    assert finder.SLIDE in states
    laser_x = laser_pose(end)[0]
    assert laser_x - JUDGED_REACH >= wall_x[0] - 0.01
    assert laser_x + JUDGED_REACH <= wall_x[1] + 0.01
    distance, heading = right_wall_error((-3.0, -0.5, 3.0, 3.0), end)
    assert distance == pytest.approx(WALL_DISTANCE, abs=0.015)
    assert abs(heading) <= defaults(FINDER)['heading_tolerance']


def test_a_slide_backward_is_not_begun_where_the_laser_has_no_beams_behind():
    # A 270-degree laser (a Hokuyo's) sees nothing within 45 degrees of straight
    # behind. The wall ends 0.05 m ahead of the point below the robot's centre:
    # the slide would back up along it, blind. It straightens up where it is.
    hokuyo = Convention('hokuyo270', -0.75 * math.pi, 1081, 1.5 * math.pi / 1080, 0.1, 30.0,
                        math.inf)
    world = [((-3.0, -0.5), (0.05, -0.5))]
    walker, _, commands, _, _ = drive(world, (0.0, 0.0, -math.pi / 2), hokuyo)
    assert walker.success, walker.failure_reason
    assert min(command.linear for command in commands) >= 0.0


@pytest.mark.parametrize('min_known', [None, 0.5], ids=['default', 'tuned'])
def test_a_slide_judges_the_way_behind_by_the_loops_ahead_min_known(min_known):
    # An LDS-01 reads 0.0 where nothing is within its reach: of the beams within
    # ahead_half_width (30 degrees) of straight behind, only those that reach the
    # wall on the right read, about 40 %. That shows the way by default, and the
    # slide backs up; a node tuned to ahead_min_known 0.5 holds its loop there,
    # and the slide, judging by the same value, does not begin.
    world = [((-3.0, -0.5), (0.05, -0.5))]
    tuned = {} if min_known is None else {'ahead_min_known': min_known}
    walker, _, commands, _, _ = drive(world, (0.0, 0.0, -math.pi / 2), LDS01, **tuned)
    assert walker.success, walker.failure_reason
    backed_up = min(command.linear for command in commands) < 0.0
    assert backed_up == (min_known is None)


@pytest.mark.parametrize('convention', CONVENTIONS, ids=ids(CONVENTIONS))
def test_aligned_short_of_a_wall_across_the_way_it_slides_back_until_the_first_turn_has_room(
        convention):
    # A step 0.2 m high stands across the way 0.2 m ahead of the point below
    # the robot's centre. Aligned there, its top would lie nearer the centre
    # than turn_room, and the lap's first move, a left turn in place onto its
    # face, would read that face nearer than the band.
    top = (0.2, -0.3)
    world = [((-3.0, -0.5), (3.0, -0.5)), ((top[0], -0.5), top)]
    walker, states, _, end, _ = drive(world, (0.0, 0.0, -math.pi / 2), convention)
    assert walker.success, walker.failure_reason
    assert finder.SLIDE in states
    room = math.hypot(top[0] - end[0], top[1] - end[1])
    assert room >= defaults(FINDER)['turn_room'] - 0.01
    distance, heading = right_wall_error((-3.0, -0.5, 3.0, 3.0), end)
    assert distance == pytest.approx(WALL_DISTANCE, abs=0.015)
    assert abs(heading) <= defaults(FINDER)['heading_tolerance']


def test_a_wall_too_short_to_fill_the_right_ends_the_slide_where_it_is_short_both_sides():
    # With right_sector 1 rad the wall must go on 0.44 m either side of the
    # laser, more than half of this 0.8 m wall. Aligned, the laser is 0.13 m
    # from its end ahead: the robot slides back once, and stops where the wall
    # falls short behind too, 0.44 m from its other end.
    world = [((-0.7, -0.5), (0.1, -0.5))]
    walker, states, _, end, _ = drive(world, (0.0, 0.0, -math.pi / 2), STAGE,
                                      right_sector=1.0)
    assert walker.success, walker.failure_reason
    assert states.count(finder.SLIDE) == 1
    assert laser_pose(end)[0] == pytest.approx(-0.7 + WALL_DISTANCE * math.tan(1.0), abs=0.04)
