"""The arc round an outer corner: its geometry, how it follows the robot, how it re-pins."""
import math

import numpy as np
import pytest

from wall_follower.control.following.corner import (OFF_ARC, TOLERANCE_HEADING, CornerArc,
                                                    OuterTurn)
from wall_follower.control.following.follower import FollowerParams, WallFollower
from wall_follower.control.motion import seen_after_move
from wall_follower.control.sensing.lines import Line
from wall_follower.control.sensing.wall_fit import in_laser_frame
from wall_follower.evaluation.scoring.course import BAND

RADIUS, ROUNDING = 0.30, 0.05
KEPT = RADIUS - ROUNDING   # distance kept from the rounded-off corner
# The bearing of a tight arc's centre still ahead of abeam, on the right [rad].
RIGHT_AHEAD = math.radians(-60.0)


def corner_points(tip, step=0.005, turn=math.pi / 2):
    """Hits along a wall ending at tip (along +x, wall below) and the next wall, turned turn
    (rad) right from it: going down for a square corner."""
    back = np.arange(-0.5, 0.0, step)
    old = np.column_stack((tip[0] + back, np.full(back.size, tip[1])))
    on = -back[::-1]
    new = tip + np.column_stack((on * math.cos(turn), -on * math.sin(turn)))
    return np.vstack((old, [tip], new))


def start_arc(laser_x=0.0):
    """The arc as it starts: the tip ROUNDING ahead, the wall KEPT to the right."""
    return CornerArc((ROUNDING, -KEPT), (1.0, 0.0), (-ROUNDING, -ROUNDING), laser_x)


def test_an_arc_that_starts_now_has_its_centre_square_to_the_right():
    distance, bearing = start_arc().offset()
    assert distance == pytest.approx(RADIUS)
    assert bearing == pytest.approx(-math.pi / 2)


@pytest.mark.parametrize('laser_x', [0.0, -0.032])
def test_driving_the_arc_keeps_the_centre_square_to_the_right(laser_x):
    arc = start_arc(laser_x)
    # The same arc with the laser off the rotation centre: the centre is
    # measured from the rotation centre, which the turn does not move sideways.
    arc.tip = arc.tip - (laser_x, 0.0)
    turn = math.pi / 64
    tips = []
    for _ in range(32):   # a quarter turn, each step a chord of the arc
        arc.moved(0.0, -turn / 2)
        arc.moved(2.0 * RADIUS * math.sin(turn / 2), 0.0)
        arc.moved(0.0, -turn / 2)
        distance, bearing = arc.offset()
        assert distance == pytest.approx(RADIUS, abs=1e-3)
        assert bearing == pytest.approx(-math.pi / 2, abs=0.01)
        tips.append(math.hypot(*(arc.tip + (laser_x, 0.0))))
    # Round a corner rounded off by ROUNDING: the tip comes to KEPT - 0.41 ROUNDING half way.
    assert min(tips) == pytest.approx(KEPT - (math.sqrt(2.0) - 1.0) * ROUNDING, abs=2e-3)
    assert max(tips) <= math.hypot(KEPT, ROUNDING) + 1e-3


def test_observing_re_pins_the_tip_to_the_corner_not_to_the_wall_beside_it():
    arc = start_arc()
    seen = np.array((0.06, -0.245))
    assert arc.observe(corner_points(seen), gate=0.1)
    assert arc.tip == pytest.approx(seen, abs=0.006)


def test_round_a_corner_that_turns_by_less_than_half_a_right_angle_the_tip_stays_put():
    # The next wall runs on 20 deg further round from the tip, out along the
    # corner's diagonal itself: re-pinned scan after scan, the tip is held
    # within one gate of where it was pinned along the wall that ended.
    arc = start_arc()
    tip = arc.tip.copy()
    for _ in range(10):
        assert arc.observe(corner_points(tip, turn=math.radians(20.0)), gate=0.1)
    assert arc.tip[0] - tip[0] <= 0.1


def test_pulled_toward_the_next_wall_the_centre_moves_square_to_it_and_with_the_robot():
    arc = start_arc()
    planned = arc.center
    # The next wall ahead, turned 30 deg into the way (measured from the right).
    toward = in_laser_frame(Line(0.4, math.radians(60.0))).normal
    assert toward == pytest.approx((math.sin(math.radians(60.0)), -0.5))
    arc.pull(0.03, toward)
    assert arc.center - planned == pytest.approx(0.03 * toward)
    # Pulled again, from where it was planned, not from the last pull.
    arc.pull(0.01, toward)
    assert arc.center - planned == pytest.approx(0.01 * toward)
    # A step and a turn later the pull has turned with everything else.
    arc.moved(0.1, -0.2)
    unpulled = start_arc()
    unpulled.moved(0.1, -0.2)
    turned = np.array(((math.cos(0.2), -math.sin(0.2)), (math.sin(0.2), math.cos(0.2))))
    assert arc.center - unpulled.center == pytest.approx(turned.dot(0.01 * toward))


def test_a_corner_out_of_the_gate_leaves_the_tip_where_it_was_expected():
    arc = start_arc()
    assert not arc.observe(corner_points(np.array((0.5, -0.5))), gate=0.1)
    assert arc.tip == pytest.approx((ROUNDING, -KEPT))


def test_a_turn_carries_a_laser_behind_the_centre_sideways():
    ahead = np.array([[1.0, 0.0]])
    # A quarter turn left on the spot, the laser 0.1 m behind the centre:
    # the point, 0.9 m ahead of the centre, ends up 0.9 m to the centre's
    # right, and the laser, swung round behind the centre, sees it 0.1 m ahead.
    moved = seen_after_move(ahead, 0.0, math.pi / 2, laser_x=-0.1)
    assert moved[0] == pytest.approx([0.1, -0.9])


def chord(arc, radius, turn):
    """Drive `turn` rad right on an arc of radius, as one chord."""
    arc.moved(0.0, -turn / 2)
    arc.moved(2.0 * radius * math.sin(turn / 2), 0.0)
    arc.moved(0.0, -turn / 2)


def fly_square_corner(turn, start, step=math.radians(0.25)):
    """Round a square corner as OuterCorner flies `turn`, from start: (ahead, off), the
    tip's position from the rotation centre, parallel to the wall.

    Returns the angles (rad) turned where the tight arc began and where the
    wide end began (None: never), the rotation centre's distance from the
    tight arc's centre where it began, the tip's distances along the way,
    and the arc as it ends, parallel to the next wall.
    """
    arc = CornerArc(start, (1.0, 0.0), turn.center)
    starting, tight_from, tight_to, met_at = True, None, None, None
    tip_distances = []
    while arc.turned() < math.pi / 2 - step / 2:
        turned, off_centre = arc.turned(), arc.offset()[0]
        starting = starting and turn.starts_wide(turned, arc.offset())
        ending = turn.ends_wide(turned, arc.past_tip())
        if not starting and tight_from is None:
            tight_from, met_at = turned, off_centre
        if ending and tight_to is None:
            tight_to = turned
        chord(arc, turn.wide_radius if starting or ending else turn.radius, step)
        tip_distances.append(math.hypot(*arc.tip))
    return tight_from, tight_to, met_at, tip_distances, arc


@pytest.mark.parametrize('wide_start, wide_end', [(0, 0), (25, 25), (20, 45)])
def test_a_square_corner_flown_as_planned_ends_at_the_distance_it_started(wide_start, wide_end):
    turn = OuterTurn(0.27, 0.39, math.radians(wide_start), math.radians(wide_end), 0.25)
    # Parallel to the wall at 0.25 m, where the plan starts the turn.
    tight_from, tight_to, met_at, tip_distances, arc = fly_square_corner(turn, (turn.lead, -0.25))
    # The wide start meets the tight arc where the plan says, tangentially.
    assert tight_from == pytest.approx(math.radians(wide_start), abs=math.radians(0.5))
    assert met_at == pytest.approx(turn.radius, abs=1e-3)
    if wide_end:
        assert tight_to == pytest.approx(math.radians(90 - wide_end), abs=math.radians(0.5))
    # Parallel to the next wall, which runs through the tip: 0.25 m to the right of it.
    assert -arc.tip[1] == pytest.approx(0.25, abs=2e-3)
    assert 0.2 < min(tip_distances) and max(tip_distances) < 0.3


def test_by_default_a_square_corner_is_planned_at_cruise_speed_clear_of_the_tip():
    """From target_distance, where FOLLOW brings the robot, where the turn starts.

    Wide arcs that meet half way round keep nearly the whole turn at cruise
    speed; planned from target_distance itself, they would pass the tip
    0.196 m from it, out of the band: the turn is planned from
    outer_corner_offset farther out.
    """
    params = FollowerParams()
    turn = WallFollower(params).outer_corner.turn
    start = (turn.lead + params.outer_turn_lead, -params.target_distance)
    tight_from, tight_to, _, tip_distances, arc = fly_square_corner(turn, start)
    # Begun nearer than planned, the wide arcs leave a few degrees between them.
    flown_tight = (tight_to or math.pi / 2) - (tight_from or math.pi / 2)
    assert flown_tight <= math.radians(5.0)
    assert BAND[0] < min(tip_distances) and max(tip_distances) < BAND[1]
    assert BAND[0] < -arc.tip[1] < BAND[1]


def test_without_wide_arcs_the_turn_is_one_arc_round_a_rounded_off_corner():
    turn = OuterTurn(0.29, 0.39, 0.0, 0.0, 0.25)
    assert turn.center == pytest.approx((-0.04, -0.04))
    assert turn.lead == pytest.approx(0.04)
    assert not turn.starts_wide(math.radians(-5.0), (0.35, RIGHT_AHEAD))
    assert not turn.ends_wide(math.pi / 2, 0.1)


def test_a_turn_begun_nearer_the_wall_than_planned_tightens_as_soon_as_it_meets_the_tight_arc():
    turn = OuterTurn(0.27, 0.39, math.radians(25), math.radians(25), 0.25)
    assert turn.starts_wide(math.radians(5.0), (0.28, RIGHT_AHEAD))
    assert not turn.starts_wide(math.radians(5.0), (0.26, RIGHT_AHEAD))
    assert not turn.starts_wide(math.radians(30.0), (0.28, RIGHT_AHEAD))


def test_within_its_tolerance_of_the_tight_arc_a_turn_still_starts_wide():
    turn = OuterTurn(0.27, 0.39, math.radians(25), math.radians(25), 0.25, tolerance=0.03)
    assert turn.starts_wide(math.radians(5.0), (0.25, RIGHT_AHEAD))
    assert not turn.starts_wide(math.radians(5.0), (0.23, RIGHT_AHEAD))
    assert not turn.starts_wide(math.radians(30.0), (0.25, RIGHT_AHEAD))


@pytest.mark.parametrize('bearing', [-90.0, -100.0])
def test_a_wide_start_off_the_tight_arc_with_its_centre_abeam_or_behind_ends(bearing):
    # Begun late, or heading away from the wall: flown on, the wide arc, which
    # turns less sharply than the tight one, carries the robot farther out.
    turn = OuterTurn(0.27, 0.39, math.radians(25), math.radians(25), 0.25, tolerance=0.03)
    assert turn.starts_wide(math.radians(5.0), (0.29, math.radians(-80.0)))
    assert not turn.starts_wide(math.radians(5.0), (0.29, math.radians(bearing)))
    # Within OFF_ARC of the arc, where a noisy fit puts a start that meets it.
    assert turn.starts_wide(math.radians(5.0), (0.27 + OFF_ARC, math.radians(bearing)))


def test_a_wide_end_begun_on_the_tight_arc_heading_along_it_clears_it():
    turn = OuterTurn(0.25, 0.39, math.radians(45), math.radians(45), 0.265)
    assert turn.end_clears((0.25, -math.pi / 2), math.radians(45.0))
    # Heading out from it: its centre behind abeam.
    assert turn.end_clears((0.25, math.radians(-100.0)), math.radians(45.0))
    # Inside it, heading along it: no nearer than now.
    assert turn.end_clears((0.20, -math.pi / 2), math.radians(45.0))


def test_a_wide_end_begun_heading_in_toward_the_tip_would_cut_inside_the_tight_arc():
    turn = OuterTurn(0.25, 0.39, math.radians(45), math.radians(45), 0.265)
    # Outside the arc, but heading in toward its centre by 45 degrees.
    assert not turn.end_clears((0.30, math.radians(-45.0)), math.radians(45.0))
    # Inside it, heading in by 20 degrees: 2.5 cm nearer than now.
    assert not turn.end_clears((0.22, math.radians(-70.0)), math.radians(45.0))
    # Ended within a few degrees, the wide arc has not yet come near it.
    assert turn.end_clears((0.30, math.radians(-45.0)), math.radians(2.0))
    assert turn.end_clears((0.30, math.radians(-45.0)), 0.0)


def test_a_turn_begun_heading_into_the_wall_has_less_tolerance_the_steeper_it_heads_in():
    turn = OuterTurn(0.27, 0.39, math.radians(25), math.radians(25), 0.25, tolerance=0.03)
    # Half TOLERANCE_HEADING in: half the tolerance, 0.015 m inside the arc.
    half = TOLERANCE_HEADING / 2
    assert turn.starts_wide(math.radians(5.0), (0.26, RIGHT_AHEAD), heading_in=half)
    assert not turn.starts_wide(math.radians(5.0), (0.25, RIGHT_AHEAD), heading_in=half)
    # That far in or more: none.
    for heading_in in (TOLERANCE_HEADING, 2 * TOLERANCE_HEADING):
        assert turn.starts_wide(math.radians(5.0), (0.275, RIGHT_AHEAD), heading_in=heading_in)
        assert not turn.starts_wide(math.radians(5.0), (0.265, RIGHT_AHEAD), heading_in=heading_in)


def wide_start_centres(turn, distance, heading_in):
    """The centres of the wide start and of the tight arc, from the rotation centre, for a
    turn begun where lead_from says: distance (m) off the wall, heading into it (rad)."""
    ahead = turn.lead_from(distance, heading_in)
    # The tip lies on the wall's line: turned heading_in to the left of the heading.
    tip = (ahead, ahead * math.tan(heading_in) - distance / math.cos(heading_in))
    arc = CornerArc(tip, (math.cos(heading_in), math.sin(heading_in)), turn.center)
    return np.array((0.0, -turn.wide_radius)), arc.center


def test_a_turn_begun_parallel_at_the_planned_distance_starts_where_planned():
    turn = OuterTurn(0.25, 0.39, math.radians(45), math.radians(45), 0.265)
    assert turn.lead_from(0.265) == pytest.approx(turn.lead)


@pytest.mark.parametrize('distance, heading_in', [(0.265, 0.0), (0.245, 0.0), (0.29, 0.0),
                                                  (0.265, math.radians(4)),
                                                  (0.245, math.radians(8))])
def test_a_turn_starts_where_its_wide_start_meets_the_tight_arc(distance, heading_in):
    turn = OuterTurn(0.25, 0.39, math.radians(45), math.radians(45), 0.265)
    wide, tight = wide_start_centres(turn, distance, heading_in)
    # Tangent inside it: the centres lie the difference of the radii apart.
    assert np.hypot(*(tight - wide)) == pytest.approx(turn.wide_radius - turn.radius)


def test_nearer_the_wall_or_heading_into_it_a_turn_starts_later():
    turn = OuterTurn(0.25, 0.39, math.radians(45), math.radians(45), 0.265)
    # As after a left turn onto a short side: 2 cm nearer, and 4 degrees in.
    assert turn.lead_from(0.245) < turn.lead - 0.02
    assert turn.lead_from(0.265, math.radians(4)) < turn.lead - 0.005
    assert turn.lead_from(0.285) > turn.lead


def test_so_near_the_wall_that_the_wide_start_cannot_meet_the_tight_arc_a_turn_starts_abreast():
    turn = OuterTurn(0.25, 0.39, math.radians(45), math.radians(45), 0.265)
    wide, tight = wide_start_centres(turn, 0.15, 0.0)
    assert tight[0] == pytest.approx(wide[0])


def test_the_wide_end_begins_where_it_will_end_at_the_planned_distance():
    turn = OuterTurn(0.27, 0.39, math.radians(25), math.radians(25), 0.25)
    # With 25 degrees left to turn, the wide arc carries the robot
    # 0.39 * (1 - cos 25 deg) = 0.037 m further from the next wall.
    carried = 0.39 * (1.0 - math.cos(math.radians(25.0)))
    assert turn.ends_wide(math.radians(65.0), 0.25 - carried - 0.002)
    # Wide of the tight arc, the robot turns on round the tip a while longer.
    assert not turn.ends_wide(math.radians(65.0), 0.25 - carried + 0.01)
    # Never before the planned angle, wherever the robot is.
    assert not turn.ends_wide(math.radians(45.0), 0.0)


def test_a_wide_end_asked_to_land_nearer_begins_that_much_later():
    turn = OuterTurn(0.27, 0.39, math.radians(25), math.radians(25), 0.25)
    carried = 0.39 * (1.0 - math.cos(math.radians(25.0)))
    assert not turn.ends_wide(math.radians(65.0), 0.25 - carried - 0.002, nearer=0.02)
    assert turn.ends_wide(math.radians(65.0), 0.25 - carried - 0.022, nearer=0.02)
