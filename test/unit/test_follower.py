"""The wall-following state machine on synthetic scans, in every laser convention.

Poses here are the laser's own (x, y, yaw): the controller works in the
laser frame, so the robot's body does not come into it.
"""
import math

import numpy as np
import pytest

from laser_conventions import CONVENTIONS, LDS01, REVERSED, STAGE, box, cast, scan_view
from scan_queries import min_range
from wall_follower.control.following.corner import CornerArc
from wall_follower.control.following.follow_wall import MAX_DIVE, dive_angle, passing_distance
from wall_follower.control.following.follower import (FOLLOW, OUTER_CORNER, SEARCH, WALL_AHEAD,
                                                      FollowerParams, WallFollower)
from wall_follower.control.following.inner_corner import LANDING_MARGIN, OUT_OF_REACH
from wall_follower.control.following.reach_track import JUMP
from wall_follower.control.following.turn_reading import peak_reading
from wall_follower.control.motion import (MAX_ANGULAR, MAX_LINEAR, Command, along_curvature, clamp,
                                          seen_after_move)
from wall_follower.control.sensing.lines import Line
from wall_follower.control.sensing.observation import Observation, in_arc_lane, unbiased
from wall_follower.control.sensing.scan import ScanView
from wall_follower.control.sensing.wall_fit import as_planned
from wall_follower.evaluation.scoring.course import BAND, RIGHT_SECTOR

ALL = CONVENTIONS + [REVERSED]
IDS = [c.name for c in ALL]
# The geometry tests expect exact ranges, so the Stage-grid correction is off,
# and they move the laser itself, so it is the rotation centre.
EXACT = FollowerParams(range_bias=0.0, laser_x=0.0)


def right_wall(distance, start=-5.0, end=5.0):
    """A straight wall along x, distance to the right of the origin."""
    return [((start, -distance), (end, -distance))]


def update(world, pose=(0.0, 0.0, 0.0), convention=STAGE, controller=None):
    controller = controller or WallFollower(EXACT)
    command = controller.update(scan_view(world, pose, convention))
    return controller, command


def noisy_lds01(world, pose, seed):
    """An LDS-01 scan with 1 cm range noise and 2 % of the beams dropped to 0.0."""
    rng = np.random.RandomState(seed)
    ranges = cast(world, pose, LDS01)
    ranges = np.where(ranges > 0.0, ranges + rng.normal(0.0, 0.01, ranges.size), 0.0)
    ranges[rng.random_sample(ranges.size) < 0.02] = 0.0
    return ScanView(ranges, LDS01.angle_min, LDS01.increment, LDS01.range_min, LDS01.range_max)


# --- following a straight wall ---------------------------------------------------------

@pytest.mark.parametrize('convention', ALL, ids=IDS)
def test_parallel_at_target_goes_straight_at_cruise_speed(convention):
    controller, command = update(right_wall(0.25), convention=convention)
    assert controller.state == FOLLOW
    assert abs(command.angular) < 0.01
    assert command.linear == pytest.approx(EXACT.cruise_speed, abs=0.005)


@pytest.mark.parametrize('convention', ALL, ids=IDS)
@pytest.mark.parametrize('distance', [0.32, 0.36, 0.42])
def test_too_far_turns_right_towards_the_wall(convention, distance):
    controller, command = update(right_wall(distance), convention=convention)
    assert controller.state == FOLLOW
    assert command.angular < -0.3
    assert command.linear > 0.1


@pytest.mark.parametrize('convention', ALL, ids=IDS)
@pytest.mark.parametrize('distance', [0.15, 0.18])
def test_too_near_turns_left_away_from_the_wall(convention, distance):
    controller, command = update(right_wall(distance), convention=convention)
    assert controller.state == FOLLOW
    assert command.angular > 0.3
    assert command.linear > 0.1


def test_inside_the_band_it_only_nudges():
    """Inside 0.2-0.3 m the turn is gentle, outside it is strong (the course's band)."""
    turns = dict((d, update(right_wall(d))[1].angular) for d in (0.17, 0.22, 0.25, 0.28, 0.33))
    assert turns[0.17] > turns[0.22] > turns[0.25] > turns[0.28] > turns[0.33]
    assert abs(turns[0.22]) < 0.7 * EXACT.max_turn_rate
    assert abs(turns[0.28]) < 0.7 * EXACT.max_turn_rate
    assert turns[0.17] == EXACT.max_turn_rate and turns[0.33] == -EXACT.max_turn_rate
    assert turns[0.17] >= 0.4 and turns[0.33] <= -0.4


@pytest.mark.parametrize('convention', ALL, ids=IDS)
def test_heading_matters_as_well_as_distance(convention):
    # At the right distance, but heading 10 deg into the wall: turn away; and back.
    _, into = update(right_wall(0.25), (0.0, 0.0, math.radians(-10.0)), convention)
    _, away = update(right_wall(0.25), (0.0, 0.0, math.radians(10.0)), convention)
    assert into.angular > 0.2
    assert away.angular < -0.2


def test_heading_into_the_wall_slows_down_to_turn_in_time():
    _, steep = update(right_wall(0.25), (0.0, 0.0, math.radians(-25.0)))
    _, gentle = update(right_wall(0.25), (0.0, 0.0, math.radians(-5.0)))
    assert steep.linear < gentle.linear


# Heading this far into a wall this near, the lane ahead meets it within
# front_turn_distance, which starts a left turn (see the inner corners below):
# the rule for heading into the wall is tested on its own.
INTO_WALL = FollowerParams(range_bias=0.0, laser_x=0.0, front_turn_distance=0.2)


def test_a_slowed_turn_parallel_is_flown_at_the_full_turn_rate():
    # 2 cm outside closest_distance, 20 deg into the wall: the arc that turns
    # parallel just in time has radius 0.02 / (1 - cos 20 deg), flown at the full rate.
    controller = WallFollower(INTO_WALL)
    _, command = update(right_wall(EXACT.closest_distance + 0.02), (0.0, 0.0, math.radians(-20.0)),
                        controller=controller)
    assert controller.state == FOLLOW
    radius = 0.02 / (1.0 - math.cos(math.radians(20.0)))
    assert command == pytest.approx((radius * EXACT.max_turn_rate, EXACT.max_turn_rate), abs=0.01)
    # Nearer still, that arc would be a pivot on the spot; it is never tighter
    # than min_arc_radius, so the robot keeps moving.
    _, command = update(right_wall(EXACT.closest_distance + 0.002), (0.0, 0.0, math.radians(-15.0)),
                        controller=WallFollower(INTO_WALL))
    assert command == pytest.approx((EXACT.min_arc_radius * EXACT.max_turn_rate,
                                     EXACT.max_turn_rate))


def test_heading_away_the_turn_back_parallel_is_slowed_to_end_within_farthest_distance():
    # 2 cm inside farthest_distance, 20 deg away from the wall: the arc that turns
    # back parallel just in time has radius 0.02 / (1 - cos 20 deg), flown at the full rate.
    controller = WallFollower(EXACT)
    _, command = update(right_wall(EXACT.farthest_distance - 0.02), (0.0, 0.0, math.radians(20.0)),
                        controller=controller)
    assert controller.state == FOLLOW
    radius = 0.02 / (1.0 - math.cos(math.radians(20.0)))
    assert command == pytest.approx((radius * EXACT.max_turn_rate, -EXACT.max_turn_rate), abs=0.01)
    # Heading away by a few degrees, the full rate's arc at cruise speed turns back in time.
    _, command = update(right_wall(EXACT.farthest_distance - 0.02), (0.0, 0.0, math.radians(5.0)))
    assert command.linear == pytest.approx(EXACT.cruise_speed)


def test_the_dive_onto_a_wall_beyond_the_band_is_the_steepest_the_widest_arc_turns_back_from():
    radius = EXACT.cruise_speed / EXACT.max_turn_rate
    target = EXACT.target_distance
    assert dive_angle(EXACT, EXACT.farthest_distance, target) == 0.0
    for distance in (EXACT.farthest_distance + 0.001, 0.33, 0.36):
        dive = dive_angle(EXACT, distance, target)
        assert 0.0 < dive < MAX_DIVE
        assert target + radius * (1.0 - math.cos(dive)) == pytest.approx(distance)
    assert dive_angle(EXACT, 0.6, target) == MAX_DIVE


def test_far_beyond_the_band_it_dives_onto_the_wall_and_turns_back_from_the_dive():
    # 0.36 m off, 30 deg into the wall: the PD law turns away already
    # (k_distance * 0.11 m < k_angle * 30 deg) and glides in on a slope that
    # flattens as it nears; the widest arc at cruise speed still turns
    # parallel at target_distance from 44 deg in, so the robot turns on in.
    # Heading in more steeply than that, it turns back.
    distance = 0.36
    dive = dive_angle(INTO_WALL, distance, INTO_WALL.target_distance)
    controller = WallFollower(INTO_WALL)
    _, shallow = update(right_wall(distance), (0.0, 0.0, math.radians(-30.0)),
                        controller=controller)
    assert controller.state == FOLLOW
    assert shallow.angular < 0.0
    assert shallow.linear == pytest.approx(INTO_WALL.cruise_speed)
    _, steep = update(right_wall(distance), (0.0, 0.0, -dive - math.radians(5.0)),
                      controller=WallFollower(INTO_WALL))
    assert steep.angular > 0.0


@pytest.mark.parametrize('laser_x', [-0.032, -0.064])
def test_that_arc_is_the_rotation_centres_wherever_the_laser_sits(laser_x):
    # The same pose of the rotation centre as above, seen by a laser behind
    # it (Burger, Waffle): the laser is further from the wall, the arc is not.
    params = FollowerParams(range_bias=0.0, laser_x=laser_x, front_turn_distance=0.2)
    yaw = math.radians(-20.0)
    laser = (laser_x * math.cos(yaw), laser_x * math.sin(yaw), yaw)
    _, command = update(right_wall(params.closest_distance + 0.02), laser,
                        controller=WallFollower(params))
    radius = 0.02 / (1.0 - math.cos(math.radians(20.0)))
    assert command == pytest.approx((radius * params.max_turn_rate, params.max_turn_rate), abs=0.01)


@pytest.mark.parametrize('seed', range(5))
def test_lds01_noise_and_dropouts_do_not_shake_it(seed):
    controller = WallFollower(EXACT)
    command = controller.update(noisy_lds01(right_wall(0.25), (0.0, 0.0, 0.0), seed))
    assert controller.state == FOLLOW
    assert abs(command.angular) < 0.15


def test_a_spurious_beam_on_the_right_does_not_move_the_wall():
    ranges = cast(right_wall(0.25), (0.0, 0.0, 0.0), STAGE)
    clean = WallFollower(EXACT).update(ScanView(ranges, STAGE.angle_min, STAGE.increment,
                                                STAGE.range_min, STAGE.range_max))
    ranges[90] = 0.13  # Stage layout: beam 90 points right
    spiked = WallFollower(EXACT).update(ScanView(ranges, STAGE.angle_min, STAGE.increment,
                                                 STAGE.range_min, STAGE.range_max))
    assert spiked.angular == pytest.approx(clean.angular, abs=0.02)


def test_an_obstacle_beside_the_wall_is_not_averaged_into_it():
    # A small box on the right, 0.6 m behind and close to the wall line.
    world = right_wall(0.25) + box(-0.75, -0.2, -0.6, -0.1)
    _, command = update(world)
    assert abs(command.angular) < 0.05


# --- a wall ahead: inner corner --------------------------------------------------------

def corridor_end(ahead, right=0.25):
    """A right wall that meets a wall across the way, ahead metres in front."""
    return [((-5.0, -right), (ahead, -right)), ((ahead, -right), (ahead, 3.0))]


@pytest.mark.parametrize('convention', ALL, ids=IDS)
def test_wall_ahead_turns_left_fast_while_moving(convention):
    controller, command = update(corridor_end(0.45), convention=convention)
    assert controller.state == WALL_AHEAD
    assert command.angular == pytest.approx(EXACT.max_turn_rate)
    assert command.linear > 0.05


@pytest.mark.parametrize('ahead', [0.3, 0.4, 0.48])
def test_the_course_rule_turn_left_when_a_wall_is_within_half_a_metre(ahead):
    # As the laser of a Burger reads it, 32 mm behind the rotation centre.
    controller, command = update(corridor_end(ahead),
                                 controller=WallFollower(FollowerParams(range_bias=0.0)))
    assert controller.state == WALL_AHEAD
    assert command.angular > 0.4 and command.linear > 0.0


def planned_turn(params, right=0.25):
    """The left turn a robot right metres from the right wall plans (see InnerCorner.turn)."""
    controller = WallFollower(params)
    update(corridor_end(1.5, right), (params.laser_x, 0.0, 0.0), controller=controller)
    return controller.inner_corner.turn


def turn_start(params, right=0.25):
    """The rotation centre's distance from a square wall ahead at which the left turn starts."""
    turn = planned_turn(params, right)
    return turn.gap(math.pi / 2) + params.turn_lead + params.inner_corner_distance


@pytest.mark.parametrize('laser_x', [0.0, -0.032, -0.064])
def test_a_left_turn_starts_where_its_arc_does_wherever_the_laser_sits(laser_x):
    # The turn is an arc of the rotation centre, so it starts at the same
    # distance of the centre from the wall ahead on a Burger (laser 32 mm
    # behind it), a Waffle (64 mm) or a robot with the laser on the centre.
    params = FollowerParams(range_bias=0.0, laser_x=laser_x)
    start = turn_start(params)
    for ahead, state in ((start + 0.01, FOLLOW), (start - 0.01, WALL_AHEAD)):
        controller, _ = update(corridor_end(ahead), (laser_x, 0.0, 0.0),
                               controller=WallFollower(params))
        assert controller.state == state


def test_a_turn_begun_farther_from_the_wall_starts_less_wide_and_later():
    # After a short wall there is no time to ride nearer first: the wide
    # start then drifts only wide_allowance past the target, and the tight
    # arc takes the rest of the turn, which so starts nearer the wall ahead.
    drifts, starts = [], []
    for right in (EXACT.target_distance - 0.03, EXACT.target_distance + 0.01):
        start = turn_start(EXACT, right)
        starts.append(start)
        controller, _ = update(corridor_end(start + 0.01, right))
        assert controller.state == FOLLOW
        allowed = EXACT.target_distance + EXACT.wide_allowance - right
        assert controller.inner_corner.turn.drift(math.pi / 2) <= max(0.0, allowed) + 1e-9
        drifts.append(controller.inner_corner.turn.drift(math.pi / 2))
        controller, _ = update(corridor_end(start - 0.01, right), controller=controller)
        assert controller.state == WALL_AHEAD
    assert drifts[1] < drifts[0] and starts[1] < starts[0]


def test_a_turn_begun_without_room_to_ride_nearer_is_the_short_wall_turn():
    # Having ridden nearer, the robot flies the turn with the wide start
    # and the near pivot; still at the target distance (a short wall), its
    # wide start would be cut short, and it flies the short-wall turn.
    dip = WallFollower(EXACT).inner_corner.left_turn.drift(math.pi / 2) - EXACT.wide_allowance
    assert planned_turn(EXACT, EXACT.target_distance - dip).radius == EXACT.inner_corner_radius
    short = planned_turn(EXACT, EXACT.target_distance)
    assert short.radius == EXACT.short_turn_radius
    assert short.drift(math.pi / 2) <= EXACT.wide_allowance + 1e-9


def test_a_turn_begun_at_the_bands_far_edge_is_tightened_to_keep_the_wall_in_band():
    # Riding nearer first, the turn reads about the band's edge at its
    # hand-over, and is flown as configured. Begun at the band's far edge
    # (fresh from find_wall), the short-wall turn's tight arc would carry the
    # reading well past it, and is tightened until it does not.
    params = FollowerParams(range_bias=0.0)
    dip = WallFollower(params).inner_corner.left_turn.drift(math.pi / 2) - params.wide_allowance
    landing = params.inner_corner_distance + LANDING_MARGIN

    def planned(right):
        controller = WallFollower(params)
        update(corridor_end(0.9, right), (params.laser_x, 0.0, 0.0), controller=controller)
        return controller.inner_corner

    def peak(turn, right):
        ahead = Line(turn.gap(math.pi / 2) + landing, math.pi / 2)
        return peak_reading(turn, Line(right, 0.0), ahead, landing, params.laser_x,
                            params.right_sector)

    assert planned(params.target_distance - dip).turn.radius == params.inner_corner_radius
    far = 0.29
    corner = planned(far)
    flown_as_configured = corner.short_turn.drifting_at_most(0.0)
    assert peak(flown_as_configured, far) > params.turn_farthest + params.turn_tolerance
    assert 0.0 < corner.turn.radius < params.short_turn_radius
    assert peak(corner.turn, far) <= params.turn_farthest
    # No more than it takes: a little wider reads past the band's edge.
    wider = flown_as_configured.tightened(corner.turn.radius / params.short_turn_radius + 0.05)
    assert peak(wider, far) > params.turn_farthest


def test_a_turn_once_begun_keeps_its_plan():
    controller, _ = update(corridor_end(0.4))
    assert controller.state == WALL_AHEAD
    planned = controller.inner_corner.turn
    update(corridor_end(0.38, 0.3), controller=controller)
    assert controller.inner_corner.turn is planned


def test_a_distant_wall_ahead_is_not_turned_for_yet():
    controller, command = update(corridor_end(1.5))
    assert controller.state == FOLLOW
    assert abs(command.angular) < 0.01


def test_a_left_turn_passes_a_stub_on_its_right_no_nearer_than_closest_distance():
    # The turn is planned on the wall ahead alone; a stub standing out of the
    # wall on the right, just ahead, is passed on the right as the robot
    # turns left, and the turn's wide start at cruise speed cut inside it.
    corner = (0.2, -0.16)
    controller, command = update(corridor_end(0.45) + box(corner[0], -0.25, 0.24, corner[1]))
    assert controller.state == WALL_AHEAD
    radius = command.linear / command.angular
    passes = math.hypot(corner[0], corner[1] - radius) - radius
    # To within a beam's spacing of the stub's corner.
    assert passes >= EXACT.closest_distance - 0.01, passes


def test_a_left_turn_ends_on_the_wall_reached_while_the_next_one_is_still_far():
    # A room whose walls meet at wide angles: the turn onto one wall ends
    # with the next already across the way, farther than the turn onto it
    # starts. Held on until that wall was gone, the turn carried the robot
    # round off the wall it had just reached.
    start = turn_start(EXACT)
    controller = WallFollower(EXACT)
    controller.state = WALL_AHEAD
    update(corridor_end(start + 0.2), controller=controller)
    assert controller.state == FOLLOW
    controller.state = WALL_AHEAD
    update(corridor_end(start - 0.01), controller=controller)
    assert controller.state == WALL_AHEAD


def test_a_left_turn_goes_on_while_its_wall_ahead_is_just_out_of_reach():
    # On the wide start the wall ahead stays at the edge of reach: its
    # distance and the gap the rest of the turn needs shrink alike. Ended
    # whenever a scan put that wall a few millimetres beyond, the turn handed
    # back to FOLLOW, which steered back at the wall it was leaving, and began
    # again at the next scan: one corner of the arena lost 0.7 s that way.
    # Scans judged where they were taken: the test puts the wall ahead.
    params = FollowerParams(range_bias=0.0, laser_x=0.0, latency=0.0)
    start = turn_start(params)
    for state in (FOLLOW, WALL_AHEAD):
        controller, _ = update(corridor_end(1.5), controller=WallFollower(params))
        controller.state = state
        update(corridor_end(start + OUT_OF_REACH / 2), controller=controller)
        assert controller.state == state


@pytest.mark.parametrize('farther, state', [(0.015, WALL_AHEAD), (JUMP + 0.01, FOLLOW)])
def test_a_left_turn_goes_on_through_a_scan_that_reads_its_wall_ahead_farther(farther, state):
    # Stage's grid reads a wall square ahead in whole cells, and a noisy
    # laser tilts its fit: for a scan the wall can read a centimetre or two
    # farther than it is. Judged on that scan alone, a turn just begun was
    # over, FOLLOW steered back at the wall the turn was leaving, and the
    # turn began again a scan or two later, short of room. How far out of
    # reach the wall is, is tracked by the robot's own motion instead: one
    # such scan moves it by a share of the difference. A wall that reads
    # farther by more than JUMP is another one, and the turn is over.
    # Scans judged where they were taken, 0.1 s apart; the robot flies the
    # command it was given.
    params = FollowerParams(range_bias=0.0, laser_x=0.0, latency=0.0)
    start = turn_start(params)
    controller = WallFollower(params)
    controller.update(scan_view(corridor_end(1.5), (0.0, 0.0, 0.0), STAGE), 0.0)
    command = controller.update(scan_view(corridor_end(start - 0.001), (0.0, 0.0, 0.0), STAGE),
                                0.1)
    assert controller.state == WALL_AHEAD
    radius, turned = command.linear / command.angular, command.angular * 0.1
    moved = (radius * math.sin(turned), radius * (1.0 - math.cos(turned)), turned)
    controller.update(scan_view(corridor_end(start - 0.001 + farther), moved, STAGE), 0.2)
    assert controller.state == state


@pytest.mark.parametrize('turned', [0.1, 0.2, 0.3])
def test_a_left_turn_for_a_step_at_the_lanes_edge_goes_on_until_it_is_clear_of_it(turned):
    # The wall steps 0.13 m nearer the way 0.25 m ahead. The step's corner
    # sits at the lane's edge: a few degrees of left turn take it out of the
    # lane. Handed back to FOLLOW then, the robot steered back into it, and
    # turned for it again, scan after scan, until its nose was on it.
    step = [((-5.0, -0.25), (0.25, -0.25)), ((0.25, -0.25), (0.25, -0.12)),
            ((0.25, -0.12), (5.0, -0.12))]
    controller = WallFollower(EXACT)
    controller.state = WALL_AHEAD
    update(step, (0.0, 0.0, turned), controller=controller)
    assert controller.state == WALL_AHEAD


def test_a_left_turn_held_only_by_the_wall_it_leaves_hands_back_to_following():
    # Nearer its wall than the widened lane's half-width, a robot turning left
    # finds that wall itself at the widened lane's edge. Held on for it, the
    # turn went on until the wall was behind and lost: on a generated world
    # (seed 14, world 28) the lap never closed.
    controller = WallFollower(EXACT)
    controller.state = WALL_AHEAD
    update(right_wall(0.17), (0.0, 0.0, math.radians(20.0)), controller=controller)
    assert controller.state == FOLLOW


def bumpy_wall(distance, proud, start=-0.05, end=0.15, pitch=0.04, width=0.01):
    """A straight wall distance (m) to the right, with bumps width wide standing proud (m)
    out of it toward the way every pitch from start to end (m along x)."""
    near = -distance + proud
    bumps = []
    for x in np.arange(start, end, pitch):
        bumps += [((x, -distance), (x, near)), ((x, near), (x + width, near)),
                  ((x + width, near), (x + width, -distance))]
    return right_wall(distance) + bumps


@pytest.mark.parametrize('away_deg', [3.0, 6.0, 9.0])
def test_a_left_turn_come_round_parallel_to_a_wall_whose_near_side_stands_out_is_over(away_deg):
    # The wall a left turn lands on reads a few centimetres out of its fitted
    # line on the near side (Stage's grid along a slanted wall), at the
    # widened lane's edge. Held on for those hits, the turn went on past
    # parallel, handed over to OUTER_CORNER, and circled 0.41 m out from the
    # wall for 2.7 s (seed 140, world 12, course720 laser: 96.3 % in band).
    controller = WallFollower(EXACT)
    controller.state = WALL_AHEAD
    world = bumpy_wall(0.23, 0.035)
    obs = Observation(scan_view(world, (0.0, 0.0, math.radians(away_deg)), STAGE), EXACT)
    assert not controller.inner_corner.clear_of_lane_edges(obs)
    update(world, (0.0, 0.0, math.radians(away_deg)), controller=controller)
    assert controller.state == FOLLOW


@pytest.mark.parametrize('away_deg', [3.0, 6.0, 9.0])
def test_a_left_turn_goes_on_for_what_stands_out_of_its_wall_farther_than_the_margin(away_deg):
    # A stub standing out of the wall by more than clear_margin is not that
    # wall's reading but something beside the way: a turn handed back to
    # FOLLOW is steered straight back into it.
    controller = WallFollower(EXACT)
    controller.state = WALL_AHEAD
    stub = bumpy_wall(0.23, EXACT.clear_margin + 0.02, start=0.1, end=0.11, width=0.03)
    update(stub, (0.0, 0.0, math.radians(away_deg)), controller=controller)
    assert controller.state == WALL_AHEAD


@pytest.mark.parametrize('distance, into_deg', [(0.23, 5.0), (0.23, 7.0), (0.24, 8.0)])
def test_the_last_degrees_onto_a_wall_that_has_left_the_lane_are_flown_wide(distance, into_deg):
    # Past the corner the new wall has left the lane ahead, but the robot
    # still heads into it, so the widened lane's edge holds the turn on.
    # Flown on the tight arc for want of a wall ahead, those degrees were
    # a pivot (the arena's first corner: three scans at 0.044 m/s).
    controller = WallFollower(EXACT)
    controller.state = WALL_AHEAD
    view = scan_view(right_wall(distance), (0.0, 0.0, -math.radians(into_deg)), STAGE)
    obs = Observation(view, EXACT)
    assert obs.ahead is None and not controller.inner_corner.clear_of_lane_edges(obs)
    command = controller.update(view)
    assert controller.state == WALL_AHEAD
    assert command.linear == pytest.approx(EXACT.cruise_speed)
    assert command.angular == pytest.approx(EXACT.max_turn_rate)


def test_the_last_degrees_onto_a_wall_already_too_near_are_turned_on_the_spot():
    # Planned on the wall it lands on, the wide end still gives way to the
    # tight arc where that wall is nearer than inner_corner_distance.
    controller = WallFollower(EXACT)
    controller.state = WALL_AHEAD
    view = scan_view(right_wall(EXACT.inner_corner_distance - 0.01),
                     (0.0, 0.0, -math.radians(4.0)), STAGE)
    assert Observation(view, EXACT).ahead is None
    command = controller.update(view)
    assert controller.state == WALL_AHEAD
    assert command.linear == pytest.approx(0.0, abs=1e-9)


def short_side_mid_turn(distance, into_deg, runs_on):
    """A left turn's last into_deg degrees onto a side distance (m) to the right that ends
    runs_on (m) ahead at a wall across its end: the controller and its command."""
    side = [((-5.0, -distance), (runs_on, -distance)), ((runs_on, -distance), (runs_on, -3.0))]
    controller = WallFollower(EXACT)
    controller.state = WALL_AHEAD
    view = scan_view(side, (0.0, 0.0, -math.radians(into_deg)), STAGE)
    obs = Observation(view, EXACT)
    assert obs.ahead is None and not controller.inner_corner.clear_of_lane_edges(obs)
    return controller, controller.update(view)


@pytest.mark.parametrize('runs_on', [0.3, 0.6])
def test_the_last_degrees_onto_a_side_are_flown_wide_where_they_land_in_reach(runs_on):
    # A side that ends landing_run ahead or sooner (0.3 m) leaves no room to
    # steer back out before the outer corner at its end. It shows itself
    # short only once the wall ahead has come round to the right; planned
    # afresh for target_distance there, the turn's gap ran out at once and
    # the robot pivoted through the rest of its wide end (the arena's
    # corners onto its short sides: half a second at 0 m/s each). 0.24 m
    # from it and 8 degrees to go, the wide end lands 4 mm nearer, well
    # beyond inner_corner_distance: it is flown at cruise speed, as onto a
    # side that runs on (0.6 m).
    controller, command = short_side_mid_turn(0.24, 8.0, runs_on)
    assert controller.state == WALL_AHEAD
    assert command.linear == pytest.approx(EXACT.cruise_speed, abs=1e-9)


def test_the_last_degrees_onto_a_short_side_do_not_land_nearer_than_inner_corner_distance():
    # Onto a short side (0.3 m), as onto any other wall (see the test above
    # of a wall already too near): flown on wide from 0.215 m (the laser's
    # reading; the rotation centre, behind it, is 8 mm farther out) with 15
    # degrees to go, the turn would land 1.3 cm nearer, short of
    # inner_corner_distance: it tightens instead.
    controller, command = short_side_mid_turn(0.215, 15.0, runs_on=0.3)
    assert controller.state == WALL_AHEAD
    assert command.linear < 0.5 * EXACT.cruise_speed


def test_a_left_turn_that_has_left_a_walls_end_behind_goes_round_it():
    # The wall on the right ended 0.1 m behind the laser, and the robot has
    # turned 60 deg left of it with the lane ahead clear and no wall along
    # the right. The nearest hit is that wall's end, behind the right: a
    # left turn held on for it only carried the robot away, until the wall
    # was lost. Round that end instead.
    controller = WallFollower(EXACT)
    controller.state = WALL_AHEAD
    view = scan_view(right_wall(0.25, end=-0.1), (0.0, 0.0, math.radians(60.0)), STAGE)
    assert Observation(view, EXACT).wall is None
    controller.update(view)
    assert controller.state == OUTER_CORNER


def test_a_wall_right_in_front_is_turned_from_on_the_spot():
    controller, command = update(corridor_end(0.15))
    assert controller.state == WALL_AHEAD
    assert command.linear == 0.0 and command.angular > 0.4


def test_the_nearer_the_wall_ahead_the_tighter_the_turn():
    speeds = [update(corridor_end(ahead))[1].linear for ahead in (0.45, 0.40, 0.36, 0.33)]
    assert speeds == sorted(speeds, reverse=True) and speeds[0] > speeds[-1]


def test_a_wall_ahead_coming_up_is_approached_a_little_nearer():
    # The wide start of the turn will carry the robot off this wall by its
    # drift; riding nearer first by all of it that wide_allowance does not
    # cover keeps the turn's middle in band.
    _, far = update(corridor_end(1.5))
    controller, near = update(corridor_end(0.8))
    assert controller.state == FOLLOW
    assert far.angular == pytest.approx(0.0, abs=0.01)
    dip = controller.inner_corner.left_turn.drift(math.pi / 2) - EXACT.wide_allowance
    assert 0.005 < dip < 0.04
    assert near.angular == pytest.approx(-EXACT.k_distance * dip, rel=0.05)


def test_a_left_turn_starts_wide_at_cruise_speed_and_then_tightens():
    trail = drive(corridor_end(1.2), (0.0, 0.0, 0.0), 80)
    speeds = step_speeds(trail)
    turning = [(math.degrees(pose[2]), speed)
               for (state, pose, _), speed in zip(trail, speeds) if state == WALL_AHEAD]
    start = [speed for yaw, speed in turning if yaw < 10.0]
    middle = [speed for yaw, speed in turning
              if 30.0 < yaw < 90.0 - math.degrees(EXACT.wide_end)]
    assert start and min(start) > 0.9 * EXACT.cruise_speed
    assert middle and max(middle) < 1.1 * EXACT.inner_corner_radius * EXACT.max_turn_rate


@pytest.mark.parametrize('wide_end, ends_wide', [(EXACT.wide_end, True), (0.0, False)])
def test_a_left_turn_ends_wide_again_when_planned_to(wide_end, ends_wide):
    # Past the corner, the last degrees only bring the robot nearer the new
    # wall: planned wide, the tight arc ends early enough for them to be
    # flown near cruise speed.
    params = FollowerParams(range_bias=0.0, laser_x=0.0, wide_end=wide_end)
    trail = drive(corridor_end(1.2), (0.0, 0.0, 0.0), 80, params=params)
    end = [speed for (state, (_, _, yaw), _), speed in zip(trail, step_speeds(trail))
           if state == WALL_AHEAD and math.degrees(yaw) > 60.0]
    assert end and (max(end) > 0.8 * EXACT.cruise_speed) == ends_wide


def test_after_a_turn_onto_a_wall_ahead_it_steers_back_out_harder_for_a_while():
    """The turn lands the robot near closest_distance on purpose, an error well above the
    laser's noise: for settle_time the distance gain is raised by settle_gain."""
    near = scan_view(right_wall(0.22), (0.0, 0.0, 0.0), STAGE)
    turns = {}
    for settle_time in (EXACT.settle_time, 0.0):
        controller = WallFollower(FollowerParams(range_bias=0.0, laser_x=0.0,
                                                 settle_time=settle_time))
        controller.update(scan_view(corridor_end(0.45), (0.0, 0.0, 0.0), STAGE), 0.0)
        assert controller.state == WALL_AHEAD
        turns[settle_time] = controller.update(near, 0.1).angular
        assert controller.state == FOLLOW
        assert controller.follow_wall.settling == pytest.approx(max(0.0, settle_time - 0.1))
    assert EXACT.settle_gain > 1.0
    extra = (EXACT.settle_gain - 1.0) * EXACT.k_distance * 0.03
    assert turns[EXACT.settle_time] - turns[0.0] == pytest.approx(extra, rel=0.2)
    controller.update(near, 0.1 + EXACT.settle_time)
    assert controller.follow_wall.settling == 0.0


def tilted_end(crossing, angle_deg, right=0.25):
    """A right wall that meets a wall crossing the way crossing metres ahead.

    angle_deg is the wall's angle as the controller measures it: 90 for a
    wall square across the way, more for one that leans back over the
    right wall (an acute corner).
    """
    angle = math.radians(angle_deg)
    along = (math.cos(angle), math.sin(angle))
    meet = (crossing - right * along[0] / along[1], -right)
    return [((-5.0, -right), meet), (meet, (crossing + 1.5 * along[0], 1.5 * along[1]))]


def test_a_wall_ahead_turned_onto_on_the_tight_arc_alone_is_not_approached_nearer():
    # A 45 degree wall needs less turn than the tight arc's share, so the
    # turn has no wide start and nothing to ride nearer for.
    controller, command = update(tilted_end(1.0, 45.0))
    assert controller.state == FOLLOW and abs(command.angular) < 0.01
    # With a wide start of 60 degrees the same turn would start wide.
    wide = WallFollower(FollowerParams(range_bias=0.0, laser_x=0.0, wide_start=math.radians(60.0),
                                       wide_allowance=0.0))
    _, command = update(tilted_end(1.0, 45.0), controller=wide)
    assert command.angular < -0.05


def test_a_wall_ahead_past_a_right_angle_is_planned_where_it_crosses_the_way():
    assert as_planned(Line(0.5, math.radians(80.0))) == (0.5, math.radians(80.0))
    distance, angle = as_planned(Line(0.45, math.radians(120.0)))
    assert distance == pytest.approx(0.45 / math.sin(math.radians(120.0)))
    assert angle == pytest.approx(math.pi / 2)
    # So the turn starts where it would for a square wall at that crossing,
    # not sooner because the tilted line's foot is nearer.
    start = turn_start(EXACT)
    for crossing, state in ((start + 0.03, FOLLOW), (start - 0.03, WALL_AHEAD)):
        assert update(corridor_end(crossing))[0].state == state
        assert update(tilted_end(crossing, 120.0))[0].state == state


def test_heading_into_the_right_wall_a_wall_ahead_is_planned_square_to_it():
    into = math.radians(8.0)
    distance, angle = as_planned(Line(0.45, math.pi / 2 + into), Line(0.25, into))
    assert angle == pytest.approx(math.pi / 2 + into)
    assert distance == pytest.approx(0.45)
    # Parallel to the right wall, or heading away from it, it is square to the way.
    for wall in (None, Line(0.25, 0.0), Line(0.25, -into)):
        assert as_planned(Line(0.45, math.pi / 2 + into), wall) == pytest.approx(
            (0.45 / math.cos(into), math.pi / 2))


def test_heading_into_the_right_wall_the_left_turn_starts_sooner():
    # Turning back to square first, on the wide arc, carries the robot
    # nearer the wall ahead by that arc's radius * sin(8 deg) as well.
    into = math.radians(8.0)
    start = turn_start(EXACT) + planned_turn(EXACT, 0.25).wide_radius * math.sin(into)
    for ahead, state in ((start + 0.01, FOLLOW), (start - 0.01, WALL_AHEAD)):
        assert update(corridor_end(ahead), (0.0, 0.0, -into))[0].state == state


@pytest.mark.parametrize('angle_deg', [110.0, 135.0])
def test_an_acute_corner_is_still_turned_onto_in_the_band(angle_deg):
    trail = drive(tilted_end(1.5, angle_deg), (0.0, 0.0, 0.0), 120)
    state, (_, _, yaw), distance = trail[-1]
    assert state == FOLLOW and distance == pytest.approx(0.25, abs=0.03)
    assert math.degrees(yaw) == pytest.approx(angle_deg, abs=5.0)
    assert min(d for _, _, d in trail) > 0.2


def test_an_inner_corner_is_turned_onto_the_next_wall():
    """Closed loop round a corner: ends following the new wall, inside the band, never stopped."""
    (x, y, yaw), distances, _ = round_a_corner(corridor_end(1.2), 80, WALL_AHEAD)
    assert yaw == pytest.approx(math.pi / 2, abs=math.radians(8.0))
    assert 1.2 - x == pytest.approx(0.25, abs=0.04)
    # The arc cuts the corner: at its middle both walls are a little over
    # 0.3 m away, by design (a tighter arc would be slower), never more;
    # and it lands a little nearer than 0.25 m, also by design.
    assert 0.21 < min(distances) and max(distances) < 0.33


# --- the right wall ends: outer corner -------------------------------------------------

def convex_corner(end_x, right=0.25):
    """A right wall that stops end_x ahead of the origin and turns away to the right."""
    return [((-5.0, -right), (end_x, -right)), ((end_x, -right), (end_x, -5.0))]


@pytest.mark.parametrize('convention', ALL, ids=IDS)
def test_a_wall_that_ends_on_the_right_is_rounded_to_the_right(convention):
    controller, command = update(convex_corner(1.0), convention=convention)
    assert controller.state == FOLLOW and abs(command.angular) < 0.01
    # The turn round the end starts where it was planned to (lead) before the end.
    lead = controller.outer_corner.turn.lead
    controller, command = update(convex_corner(lead + 0.04), convention=convention,
                                 controller=controller)
    assert controller.state == FOLLOW
    controller, command = update(convex_corner(lead - 0.03), convention=convention,
                                 controller=controller)
    assert controller.state == OUTER_CORNER
    assert command.angular < -0.3 and command.linear > 0.05


def opening_before_a_wall_across(opening, right=0.25):
    """convex_corner at the outer corner's start, and opening metres beyond the wall's end a
    wall across the lane that ends at the robot's right: the way on is between the two."""
    end_x = WallFollower(EXACT).outer_corner.turn.lead - 0.03
    across = end_x + opening
    return convex_corner(end_x, right) + [((across, -0.05), (across, 3.0))]


def test_a_wall_that_ends_short_of_a_wall_across_the_way_is_rounded_first():
    # Generated world 3 of seed 58, the LDS-01 laser, with a 35 deg wide end
    # to the left turn before it: the wall on the right ended 0.4 m short of
    # a wall across the lane. The turn onto that wall was due as well, and
    # taken first it carried the robot away from the opening and off the
    # wall it followed: it drove back across the room to its start and
    # closed a lap of 18 s, 90 % in band.
    controller = WallFollower(EXACT)
    controller.state = FOLLOW
    # The turn onto the wall across is due there as well.
    assert turn_start(EXACT) > WallFollower(EXACT).outer_corner.turn.lead - 0.03 + 0.35
    controller, command = update(opening_before_a_wall_across(0.35), controller=controller)
    assert controller.state == OUTER_CORNER
    assert command.angular < -0.3


def test_an_opening_too_narrow_to_turn_into_is_passed_by_the_left_turn():
    controller = WallFollower(EXACT)
    controller.state = FOLLOW
    controller, command = update(opening_before_a_wall_across(0.15), controller=controller)
    assert controller.state == WALL_AHEAD
    assert command.angular > 0.3


def test_a_wall_that_ends_before_a_wall_across_comes_near_is_followed_to_its_end_first():
    # Generated world 43 of seed 82, the LDS-01 laser: the turn onto a wall
    # across the lane came due 7 cm before the wall on the right ended, 0.55
    # m short of it. Taken first, it swung the robot toward the far side of
    # the opening, where it dithered between the two turns.
    controller = WallFollower(EXACT)
    controller.state = FOLLOW
    lead = controller.outer_corner.turn.lead
    across = turn_start(EXACT) - 0.01
    # The wall ends 6 cm before the turn round it is due, sooner than the
    # wall across comes within front_turn_distance ...
    assert 0.06 < across - EXACT.front_turn_distance
    world = convex_corner(lead + 0.06) + [((across, -0.05), (across, 3.0))]
    view = scan_view(world, (0.0, 0.0, 0.0), STAGE)
    # ... and the turn onto the wall across is due already.
    assert controller.inner_corner.due(Observation(view, EXACT))
    command = controller.update(view)
    assert controller.state == FOLLOW
    assert command.angular <= 0.0


def test_a_wall_seen_to_the_edge_of_its_sector_is_not_taken_to_end_there():
    # The wall on the right runs on past where its sector is searched: its
    # hits stop at that edge, not at its end, and the turn onto the wall
    # across the way is taken where it comes due.
    start = turn_start(EXACT)
    controller = WallFollower(EXACT)
    controller.state = FOLLOW
    controller, _ = update(corridor_end(start - 0.01), controller=controller)
    assert controller.state == WALL_AHEAD
    ends = math.tan(EXACT.wall_sector) * 0.25
    assert controller.outer_corner.due_within(
        Observation(scan_view(right_wall(0.25), (0.0, 0.0, 0.0), STAGE), EXACT), ends) is False


def lipped_corner(lip, end_x=0.3, right=0.25):
    """convex_corner(end_x) whose next wall's top stands lip out of the wall, toward the robot."""
    top = -right + lip
    return [((-5.0, -right), (end_x, -right)), ((end_x - 0.02, top), (end_x, top)),
            ((end_x, top), (end_x, -5.0))]


def test_the_end_of_a_wall_standing_out_toward_the_robot_is_steered_clear_of():
    # The next wall's top stands 6 cm out of the wall that ends: held at
    # target_distance from the wall's line, the robot would pass it 0.19 m off.
    _, flush = update(lipped_corner(0.0))
    controller, lipped = update(lipped_corner(0.06))
    assert controller.state == FOLLOW
    assert abs(flush.angular) < 0.01 and lipped.angular > 0.3


def stepped_before_a_corner(top, step_x=0.15, across_x=0.7, right=0.3):
    """A right wall `right` off that steps out to `top` to the right step_x ahead, and runs on
    at that to a wall across the way across_x ahead."""
    return [((-5.0, -right), (step_x, -right)), ((step_x, -right), (step_x, -top)),
            ((step_x, -top), (across_x, -top)), ((across_x, -top), (across_x, 3.0))]


@pytest.mark.parametrize('top', [0.16, 0.18])
def test_a_step_out_of_the_wall_before_a_corner_is_held_off(top):
    # 143/1: the right wall stepped out toward the robot just before a
    # corner with a wall across the way. What stood out was taken for that
    # wall's face and left out, and FOLLOW steered right, toward the step's
    # top, to hold the wall beyond it at target_distance: it passed the top
    # 0.14-0.17 m off.
    world = stepped_before_a_corner(top)
    controller = WallFollower(EXACT)
    seen = Observation(scan_view(world, (0.0, 0.0, 0.0), STAGE), EXACT)
    assert controller.inner_corner.blocking(seen) and seen.beside.depth > 0.08
    controller.state = FOLLOW
    controller, command = update(world, controller=controller)
    assert controller.state == FOLLOW
    assert command.angular > 0.05  # away from the step's top, not toward it


def test_the_face_of_the_wall_across_the_way_does_not_stand_beside_it():
    # At an acute corner the face of the wall across the way leans toward
    # the robot out of the right wall's line; the left turn onto that wall
    # is planned for it.
    corner_x, lean = 0.35, 1.0
    world = [((-5.0, -0.25), (corner_x, -0.25)), ((corner_x, -0.25), (corner_x - lean, 1.0))]
    seen = Observation(scan_view(world, (0.0, 0.0, 0.0), STAGE), EXACT)
    assert WallFollower(EXACT).inner_corner.blocking(seen) and seen.proud > 0.03
    assert seen.beside.depth == 0.0


def receding_to_a_step(step_x, top, recedes=math.radians(25.0), right=0.25):
    """A right wall that recedes from the heading, `right` off at the origin, and steps back
    in step_x ahead to a wall along the heading, top to the right of it."""
    def wall_y(x):
        return -right - math.tan(recedes) * x
    return [((-0.6, wall_y(-0.6)), (step_x, wall_y(step_x))),
            ((step_x, wall_y(step_x)), (step_x + 0.05, -top)), ((step_x + 0.05, -top), (3.0, -top))]


@pytest.mark.parametrize('top, turns', [(0.27, 'right'), (0.20, 'left')])
def test_a_step_back_in_ahead_of_a_receding_wall_is_held_where_the_heading_passes_it(top, turns):
    # Heading 25 degrees away from a wall that recedes (a shallow notch), the
    # wall steps back in 0.3 m ahead. Held at target_distance across the
    # receding line, the step's top read as if beside the robot, and FOLLOW
    # turned left at the full turn rate, off the notch and out of the band,
    # even where the present heading passes the top farther out than that.
    world = receding_to_a_step(0.3, top)
    seen = Observation(scan_view(world, (0.0, 0.0, 0.0), STAGE), EXACT)
    assert seen.wall.angle < 0.0 and seen.proud > 0.0
    controller = WallFollower(EXACT)
    controller.state = FOLLOW
    controller, command = update(world, controller=controller)
    assert controller.state == FOLLOW
    if turns == 'right':
        assert command.angular < 0.0
    else:
        assert 0.0 < command.angular < EXACT.max_turn_rate


@pytest.mark.parametrize('angle', [0.0, -0.2, -0.6])
def test_passing_distance_is_where_the_heading_passes_the_top_of_a_step(angle):
    # A top standing depth out of a wall at angle, reach ahead of the laser:
    # the line through it parallel to the wall crosses x = reach that far right.
    distance, depth, reach = 0.3, 0.1, 0.4
    normal = np.array([math.cos(angle - math.pi / 2), math.sin(angle - math.pi / 2)])
    # The point at x = reach on the line (distance - depth) along the normal.
    y = ((distance - depth) - reach * normal[0]) / normal[1]
    assert passing_distance(Line(distance, angle), depth, reach) == pytest.approx(-y)


def test_along_a_parallel_wall_the_heading_passes_a_top_across_the_walls_line():
    assert passing_distance(Line(0.3, 0.0), 0.1, 0.4) == pytest.approx(0.3 - 0.1)


@pytest.mark.parametrize('convention', ALL, ids=IDS)
def test_a_tip_just_rounded_beside_the_robot_does_not_hold_it_off_the_wall_beyond(convention):
    # Round a corner's tip onto a short side that runs straight out to the
    # right, 0.2 m to 0.42 m, where the next wall goes on parallel. The tip
    # lies ahead of the laser but behind the rotation centre (a Burger's
    # laser sits behind it): held at target_distance as if still to come,
    # it steered the robot away from that wall.
    params = FollowerParams(range_bias=0.0)
    tip_x = -params.laser_x / 2
    world = [((tip_x - 0.7, -0.9), (tip_x, -0.2)), ((tip_x, -0.2), (tip_x, -0.42)),
             ((tip_x, -0.42), (5.0, -0.42))]
    controller = WallFollower(params)
    controller.state = FOLLOW
    controller, command = update(world, convention=convention, controller=controller)
    assert controller.state == FOLLOW
    assert command.angular < -0.3


@pytest.mark.parametrize('outer_turn_lead', [0.0, 0.06])
def test_the_turn_round_a_walls_end_starts_outer_turn_lead_early(outer_turn_lead):
    params = FollowerParams(range_bias=0.0, laser_x=0.0, outer_turn_lead=outer_turn_lead)
    start = WallFollower(params).outer_corner.turn.lead + outer_turn_lead
    for end_x, state in ((start + 0.025, FOLLOW), (start - 0.025, OUTER_CORNER)):
        controller = WallFollower(params)
        controller.state = FOLLOW
        assert update(convex_corner(end_x), controller=controller)[0].state == state


def rounding(tip_distance, turned_deg, ending_wide=False):
    """A controller on the arc round convex_corner(0.0)'s tip, tip_distance from it, turned so far.

    Returns it with the robot's pose.
    """
    heading = -math.radians(turned_deg)
    x, y = (tip_distance * math.cos(heading + math.pi / 2),
            -0.25 + tip_distance * math.sin(heading + math.pi / 2))
    controller = WallFollower(EXACT)
    tip = (-x * math.cos(heading) + (-0.25 - y) * math.sin(heading),
           x * math.sin(heading) + (-0.25 - y) * math.cos(heading))
    along = (math.cos(heading), -math.sin(heading))
    controller.state = OUTER_CORNER
    controller.outer_corner.arc = CornerArc(tip, along, controller.outer_corner.turn.center)
    controller.outer_corner.ending_wide = ending_wide
    return controller, (x, y, heading)


def test_the_wide_end_begins_where_the_laser_reads_the_new_wall_in_band():
    # Flown to parallel, the wide end lands inner_corner_distance from the
    # new wall, so it begins wide_radius * (1 - cos wide_end) farther off.
    # The laser, behind the rotation centre, is farther still, and the judge
    # reads that wall through the edge of its sector, past which the wall's
    # normal then lies.
    params = FollowerParams()
    wide_radius = params.cruise_speed / params.max_turn_rate
    centre = params.inner_corner_distance + wide_radius * (1.0 - math.cos(params.wide_end))
    laser = centre - params.laser_x * math.sin(params.wide_end)
    assert laser / math.cos(max(0.0, params.wide_end - RIGHT_SECTOR)) <= BAND[1]


def test_a_wide_end_once_begun_goes_on():
    # Round the end of a free-standing wall no next wall is fitted, and the
    # turn is taken for a square one. Here the wide end would land a little
    # far from the next wall ...
    wall_end = right_wall(0.25, end=0.0)
    controller, pose = rounding(0.25, 60.0)
    _, command = update(wall_end, pose, controller=controller)
    assert not controller.outer_corner.ending_wide
    assert command.linear < 0.9 * EXACT.cruise_speed
    # ... but the tip is seen only to a grid cell or so, and a wide end
    # begun a scan before goes on rather than tighten again.
    controller, pose = rounding(0.25, 60.0, ending_wide=True)
    _, command = update(wall_end, pose, controller=controller)
    assert command == pytest.approx((EXACT.cruise_speed, -EXACT.max_turn_rate))


def test_a_wide_end_begins_where_it_lands_at_the_target_distance():
    controller, pose = rounding(0.2, 60.0)
    _, command = update(convex_corner(0.0), pose, controller=controller)
    assert controller.outer_corner.ending_wide
    assert command == pytest.approx((EXACT.cruise_speed, -EXACT.max_turn_rate))


def test_a_robot_carried_outside_the_arc_round_a_tip_slows_to_turn_back_onto_it():
    # The arc is flown at the full turn rate, with no turn left for the PD
    # law: a robot 6 cm outside it (a wide end cut short round a sharp tip)
    # drifted on outward. It slows down instead, but not on the arc, where
    # a noisy laser's fit of the tip moves it by up to OFF_ARC. Held back
    # until 3 cm outside, the slowdown let the robot drift out that far
    # first: 1.5 cm out, it slows.
    arc_speed = EXACT.outer_corner_radius * EXACT.max_turn_rate
    outside, speeds = [], []
    for tip_distance in (0.215, 0.23, 0.28):
        controller, pose = rounding(tip_distance, 45.0)
        outside.append(controller.outer_corner.arc.offset()[0] - EXACT.outer_corner_radius)
        _, command = update(convex_corner(0.0), pose, controller=controller)
        assert command.angular == pytest.approx(-EXACT.max_turn_rate)
        speeds.append(command.linear)
    assert outside == pytest.approx([0.0, 0.015, 0.065], abs=0.002)
    on_arc, a_little_out, far_out = speeds
    assert on_arc == pytest.approx(arc_speed)
    assert a_little_out < 0.8 * arc_speed
    assert far_out < 0.5 * arc_speed


@pytest.mark.parametrize('period', [0.1, 0.2])
def test_the_arc_round_a_corner_turns_with_the_robot_for_the_time_between_scans(period):
    # The rounded-off corner's centre is fixed in the world: between two
    # scans it turns, seen from the robot, by the robot's own turn, which
    # is the command times the time between the scans' stamps.
    controller = WallFollower(EXACT)
    lead = controller.outer_corner.turn.lead
    view = scan_view(convex_corner(lead - 0.03), (0.0, 0.0, 0.0), STAGE)
    controller.update(scan_view(convex_corner(1.0), (0.0, 0.0, 0.0), STAGE), stamp=9.9)
    controller.update(view, stamp=10.0)
    assert controller.state == OUTER_CORNER
    arc = controller.outer_corner.arc
    before = arc.center - arc.tip
    turn = controller.command.angular * period
    controller.update(view, stamp=10.0 + period)
    after = arc.center - arc.tip
    turned = math.atan2(after[1], after[0]) - math.atan2(before[1], before[0])
    assert turned == pytest.approx(-turn)


def test_circling_a_hit_ends_on_a_wall_that_an_arc_would_still_turn_for():
    # With no wall to pin an arc to (a box's short side, mid-turn) the robot
    # circles the nearest hit, and any straight wall within rejoin_angle
    # ends that; an arc ends only within arc_exit_angle, where it was
    # planned to.
    pose = (0.0, 0.0, math.radians(15.0))
    circling = WallFollower(EXACT)
    circling.state = OUTER_CORNER
    assert update(right_wall(0.25), pose, controller=circling)[0].state == FOLLOW
    on_arc = WallFollower(EXACT)
    on_arc.state = OUTER_CORNER
    on_arc.outer_corner.arc = CornerArc((0.05, -0.25), (1.0, 0.0), (-0.04, -0.04))
    assert update(right_wall(0.25), pose, controller=on_arc)[0].state == OUTER_CORNER


@pytest.mark.parametrize('distance', [0.36, 0.42])
def test_an_arc_onto_a_wall_beyond_the_band_ends_heading_into_it_at_the_dive(distance):
    # Round a tip standing out of the next wall toward the robot, the arc
    # comes parallel to that wall beyond the band: it goes on round the tip
    # until the robot heads into the wall as steeply as FOLLOW dives onto it.
    dive = dive_angle(EXACT, distance, EXACT.target_distance)
    for heading_in, state in ((0.0, OUTER_CORNER), (dive, FOLLOW)):
        controller = WallFollower(INTO_WALL)
        controller.state = OUTER_CORNER
        controller.outer_corner.arc = CornerArc((0.05, -0.25), (1.0, 0.0), (-0.04, -0.04))
        update(right_wall(distance), (0.0, 0.0, -heading_in), controller=controller)
        assert controller.state == state, heading_in


def test_an_arc_is_dropped_once_its_corner_is_over():
    # Parallel to the next wall, the arc has ended where it was planned to:
    # the robot follows that wall, and the next corner gets an arc of its own.
    controller = WallFollower(EXACT)
    controller.state = OUTER_CORNER
    controller.outer_corner.arc = CornerArc((0.05, -0.25), (1.0, 0.0), (-0.04, -0.04))
    assert update(right_wall(0.25), controller=controller)[0].state == FOLLOW
    assert controller.outer_corner.arc is None


def test_an_outer_corner_is_rounded_onto_the_next_wall():
    (x, y, yaw), distances, _ = round_a_corner(convex_corner(0.6), 90, OUTER_CORNER)
    assert yaw == pytest.approx(-math.pi / 2, abs=math.radians(10.0))
    assert x - 0.6 == pytest.approx(0.25, abs=0.05)
    # All the way round, the wall's end stays near the target distance.
    assert all(0.18 < distance < 0.32 for distance in distances)


def test_an_outer_corner_is_flown_mostly_at_cruise_speed_on_its_wide_arcs():
    # A right angle takes the same time at the full turn rate however it is
    # flown: what the turn gains is the ground it covers meanwhile. The wide
    # arcs meet about half way round; between them the robot circles the tip
    # on the tight arc only where it came in nearer than the turn was planned
    # from (outer_corner_offset).
    trail = drive(convex_corner(0.6), (0.0, 0.0, 0.0), 90)
    speeds = step_speeds(trail)
    turning = [(-math.degrees(pose[2]), speed)
               for (state, pose, _), speed in zip(trail, speeds) if state == OUTER_CORNER]
    start = [speed for turned, speed in turning if turned < 10.0]
    cruising = [speed for _, speed in turning if speed > 0.9 * EXACT.cruise_speed]
    tight = [speed for _, speed in turning if speed <= 0.9 * EXACT.cruise_speed]
    assert start and min(start) > 0.9 * EXACT.cruise_speed
    assert len(cruising) >= 0.7 * len(turning)
    assert tight and max(tight) < 1.1 * EXACT.outer_corner_radius * EXACT.max_turn_rate


def step_down(end_x, depth, right=0.25):
    """A right wall that steps down by depth at end_x: an outer corner, then a wall across."""
    return [((-5.0, -right), (end_x, -right)), ((end_x, -right), (end_x, -right - depth)),
            ((end_x, -right - depth), (end_x + 5.0, -right - depth))]


def test_an_outer_corner_lands_nearer_a_short_side_that_ends_at_a_wall_across():
    # Past a short side (a pillar's) the turn onto the wall across comes up
    # at once, with no room to ride nearer first: the outer corner lands
    # nearer the side instead.
    landings = {}
    for depth in (0.6, 3.0):
        trail = drive(step_down(0.6, depth), (0.0, 0.0, 0.0), 150)
        states = [state for state, _, _ in trail]
        landed = states.index(FOLLOW, states.index(OUTER_CORNER))
        landings[depth] = trail[landed][1][0] - 0.6
        # In band, but for the middle of the short-wall turn, which runs to its far edge.
        assert all(0.2 < distance < 0.31 for _, _, distance in trail[landed:])
    # The corner is planned to land outer_corner_offset past target_distance.
    assert landings[3.0] == pytest.approx(EXACT.target_distance + EXACT.outer_corner_offset,
                                          abs=0.005)
    assert landings[0.6] < landings[3.0] - 0.005


@pytest.mark.parametrize('proud, reach, due', [
    (0.0, -math.inf, True), (0.075, 0.05, True), (0.075, 0.3, False)],
    ids=['nothing stands out', "a corner's lip", 'a step up'])
def test_the_end_of_a_wall_is_no_corner_to_round_where_a_nearer_wall_runs_on_past_it(
        proud, reach, due):
    # On Stage's grid the wall's hits stop at the foot of a step up's face
    # (the face's hits lie no farther ahead than its foot, and the step's
    # top begins a face's height away), short of where the turn round its
    # end begins. The step's top stands out of the wall and runs on past
    # that end; the top of the next wall at a corner (its lip) stands out
    # only there.
    seen = Observation.__new__(Observation)
    seen.wall = Line(0.25, 0.0)
    seen.wall_runs = 0.05
    seen.proud, seen.proud_reach = proud, reach
    assert WallFollower(EXACT).outer_corner.due(seen) == due


@pytest.mark.parametrize('angle_deg, proud, pinned', [
    (0.0, 0.0, True), (-20.0, 0.0, True), (-60.0, 0.0, False), (40.0, 0.0, True),
    (60.0, 0.0, True), (0.0, EXACT.corner_gate, True), (0.0, EXACT.corner_gate + 0.01, False)])
def test_an_arc_is_pinned_only_to_a_wall_not_turned_away_that_ends_in_its_corner(
        angle_deg, proud, pinned):
    # Mid-turn onto a box's short side, the wall fitted on the right can be
    # the one the turn left behind, 60 degrees turned away: its end is not
    # the corner that came up, so the robot circles the nearest hit instead.
    # A wall the robot still heads into, however steeply (just after a turn
    # onto a slanted wall), is the one that ends there. Nor is the end of a
    # wall that meets the face of a step up, standing out toward the robot:
    # that end is the face's foot.
    seen = Observation.__new__(Observation)
    seen.wall = Line(0.25, math.radians(angle_deg))
    seen.wall_end = seen.wall_tip = np.array((0.1, -0.25))
    seen.proud = proud
    assert (WallFollower(EXACT).outer_corner._corner_arc(seen) is not None) == pinned


PLANNED_END = WallFollower(EXACT).outer_corner.turn.lead - 0.03


@pytest.mark.parametrize('before, end_x, starting_wide', [
    (FOLLOW, PLANNED_END, True), (WALL_AHEAD, PLANNED_END, False), (FOLLOW, 0.0, False)],
    ids=['following', 'mid left turn', 'following, late'])
def test_only_a_corner_met_while_following_the_wall_where_planned_starts_wide(
        before, end_x, starting_wide):
    # Met mid left turn (a box's short side), the corner is not where the
    # planned turn would start it: that turn circles the tip at once. So
    # does one met late, its end already abeam: the tight arc's centre lies
    # behind, and the wide arc would carry the robot away from it.
    controller = WallFollower(EXACT)
    controller.state = before
    controller, command = update(convex_corner(end_x), controller=controller)
    assert controller.state == OUTER_CORNER and controller.outer_corner.arc is not None
    assert controller.outer_corner.starting_wide == starting_wide
    assert (command.linear == pytest.approx(EXACT.cruise_speed)) == starting_wide


@pytest.mark.parametrize('end_past_tip, next_wall', [(0.0, False), (0.3, True)],
                         ids=['the wall that ended', 'a wall beyond the tip'])
def test_a_wall_fitted_up_to_the_tip_is_never_the_next_wall_however_it_turned(
        end_past_tip, next_wall):
    # The arc takes the way of the wall that ended from its fit as the turn
    # begins; fitted again clear of a hook at its tip, the same wall seemed
    # turned away 20 degrees, more than OTHER_WALL_ANGLE, and the robot flew
    # the wide end along it. A wall as turned that runs on past the tip is
    # another wall.
    controller = WallFollower(EXACT)
    controller.state = FOLLOW
    controller, _ = update(convex_corner(PLANNED_END), controller=controller)
    corner = controller.outer_corner
    assert controller.state == OUTER_CORNER and corner.turn.starts_wide
    seen = Observation.__new__(Observation)
    seen.wall = Line(0.25, math.radians(-20.0))
    seen.wall_end = corner.arc.tip + np.array((0.0, -end_past_tip))
    seen.right = np.zeros((0, 2))
    assert (corner._next_wall(seen) is not None) == next_wall


@pytest.mark.parametrize('lip, starting_wide', [(0.0, True), (0.06, False)])
def test_a_corner_whose_tip_stands_out_toward_the_robot_does_not_start_wide(lip, starting_wide):
    # The wide start is planned for a tip on the wall's line; one standing
    # out lies nearer, and the wide start would carry the robot past it
    # out of the band: the arc round it is flown from the start.
    controller = WallFollower(EXACT)
    controller.state = FOLLOW
    controller, _ = update(lipped_corner(lip, end_x=0.05), controller=controller)
    assert controller.state == OUTER_CORNER and controller.outer_corner.arc is not None
    assert controller.outer_corner.starting_wide == starting_wide


def test_a_box_on_the_wall_is_driven_round_and_the_wall_rejoined():
    """Inner corner onto the box's short side, whose end comes up mid-turn, two outer
    corners round the box, the inner corner back onto the wall: in band all the way."""
    world = [((-5.0, -0.25), (0.8, -0.25)), ((0.8, -0.25), (0.8, 0.05)), ((0.8, 0.05), (1.1, 0.05)),
             ((1.1, 0.05), (1.1, -0.25)), ((1.1, -0.25), (5.0, -0.25))]
    (x, y, yaw), distances, states = round_a_corner(world, 160, OUTER_CORNER)
    assert WALL_AHEAD in states
    assert x > 1.6 and y == pytest.approx(0.0, abs=0.04) and abs(yaw) < math.radians(8.0)
    assert all(0.17 < distance < 0.36 for distance in distances)


# --- no wall near ----------------------------------------------------------------------

@pytest.mark.parametrize('convention', ALL, ids=IDS)
def test_with_no_wall_near_it_searches_straight_ahead(convention):
    controller, command = update(box(-3.0, -3.0, 3.0, 3.0), convention=convention)
    assert controller.state == SEARCH
    assert command == (EXACT.search_speed, 0.0)


def test_search_ends_when_a_wall_comes_up_on_the_right():
    controller, _ = update(box(-3.0, -3.0, 3.0, 3.0))
    controller, _ = update(right_wall(0.3), controller=controller)
    assert controller.state == FOLLOW


def test_search_turns_left_at_a_wall_ahead():
    controller, command = update([((0.4, -2.0), (0.4, 2.0))])
    assert controller.state == WALL_AHEAD and command.angular > 0.0


# --- limits, parameters, helpers -------------------------------------------------------

def test_commands_stay_within_the_robot_limits_anywhere():
    rng = np.random.RandomState(3)
    room = box(-1.5, -1.2, 1.5, 1.2) + box(0.2, -0.3, 0.5, 0.0)
    controller = WallFollower()
    for _ in range(200):
        pose = (rng.uniform(-1.3, 1.3), rng.uniform(-1.0, 1.0), rng.uniform(-math.pi, math.pi))
        command = controller.update(scan_view(room, pose, STAGE))
        assert 0.0 <= command.linear <= MAX_LINEAR
        assert abs(command.angular) <= MAX_ANGULAR
        assert clamp(command) == command


def test_clamp_limits_and_drops_nan():
    assert clamp(Command(0.5, -2.0)) == (MAX_LINEAR, -MAX_ANGULAR)
    assert clamp(Command(-0.5, 2.0)) == (-MAX_LINEAR, MAX_ANGULAR)
    assert clamp(Command(float('nan'), 0.1)) == (0.0, 0.1)
    assert clamp(Command(0.3, 0.3), max_linear=0.1, max_angular=0.2) == (0.1, 0.2)


def test_parameters_default_override_and_reject_typos():
    assert FollowerParams().target_distance == 0.25
    assert FollowerParams(target_distance=0.3).target_distance == 0.3
    assert isinstance(FollowerParams(wall_min_points=7.0).wall_min_points, int)
    with pytest.raises(ValueError, match='target_distanse'):
        FollowerParams(target_distanse=0.3)


def test_look_ahead_moves_hits_against_the_motion():
    points = np.array([[1.0, 0.0], [0.0, -0.25]])
    moved = seen_after_move(points, 0.1, math.pi / 2)
    # Forward 0.1 m, then a quarter turn left: what was ahead is now on the right.
    assert moved[0] == pytest.approx([0.0, -0.9])
    assert moved[1] == pytest.approx([-0.25, 0.1])


def test_range_bias_pulls_hits_in_along_their_beams():
    points = np.array([[0.3, 0.4], [0.0, -0.25]])
    assert unbiased(points, 0.05) == pytest.approx(np.array([[0.27, 0.36], [0.0, -0.2]]))


def test_the_lane_a_right_turn_sweeps_leaves_out_what_lies_ahead_on_its_left():
    ahead_left, ahead_right, square_ahead = (0.3, 0.12), (0.3, -0.12), (0.2, 0.0)
    points = np.array([ahead_left, ahead_right, square_ahead])
    # At cruise speed and the full turn rate, an arc of 0.39 m radius.
    swept = in_arc_lane(points, (0.19, -0.49), 0.0, 0.14)
    assert swept.tolist() == [False, True, True]


@pytest.mark.parametrize('motion', [(0.19, 0.0), (0.05, -0.49), (0.0, -0.49)])
def test_straight_on_or_too_tight_to_hold_the_lane_the_lane_is_left_whole(motion):
    points = np.array([[0.3, 0.12], [0.3, -0.12], [0.2, 0.0]])
    assert in_arc_lane(points, motion, 0.0, 0.14).all()


# --- a small kinematic loop ------------------------------------------------------------

def drive(world, pose, steps, dt=0.1, params=EXACT):
    """Laser pose stepped by the commands, one step late as in Stage.

    Returns (state, pose, distance to the nearest wall point on the right)
    for every step; the distance is measured exactly over +-30 deg of the
    right, as the benchmark scores it.
    """
    controller = WallFollower(params)
    x, y, yaw = pose
    command = Command(0.0, 0.0)
    trail = []
    for _ in range(steps):
        view = scan_view(world, (x, y, yaw), STAGE)
        x += command.linear * dt * math.cos(yaw)
        y += command.linear * dt * math.sin(yaw)
        yaw += command.angular * dt
        command = clamp(controller.update(view))
        sector = scan_view(world, (x, y, yaw), STAGE)
        trail.append((controller.state, (x, y, yaw),
                      min_range(sector, -math.pi / 2, math.radians(30.0))))
    return trail


def step_speeds(trail, dt=0.1):
    """The speed of each step of a drive() trail: one step's travel is that step's command."""
    return [math.hypot(b[0] - a[0], b[1] - a[1]) / dt
            for (_, a, _), (_, b, _) in zip(trail, trail[1:])]


def round_a_corner(world, steps, corner_state):
    """Drive from the origin through corner_state back to FOLLOW.

    Returns (the end pose, the right-wall distance at every step, the states
    passed through).
    """
    trail = drive(world, (0.0, 0.0, 0.0), steps)
    states = [state for state, _, _ in trail]
    assert corner_state in states and states[-1] == FOLLOW
    return trail[-1][1], [distance for _, _, distance in trail], set(states)


@pytest.mark.parametrize('curvature, command', [
    (0.0, (MAX_LINEAR, 0.0)),
    (1.0, (MAX_LINEAR, MAX_LINEAR)),
    (-5.0, (MAX_ANGULAR / 5.0, -MAX_ANGULAR)),
    (5.0, (MAX_ANGULAR / 5.0, MAX_ANGULAR)),
], ids=['straight', 'gentle', 'tight right', 'tight left'])
def test_a_curve_is_flown_at_full_speed_or_at_the_full_turn_rate(curvature, command):
    assert along_curvature(curvature, MAX_LINEAR, MAX_ANGULAR) == pytest.approx(command)
