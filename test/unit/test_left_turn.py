"""The planned left turn onto a wall ahead: its gap, its arcs, and how it is scaled to fit."""
import math

import pytest

from wall_follower.control.following.left_turn import LeftTurn

TIGHT, WIDE, WIDE_ANGLE, WIDE_END = 0.23, 0.19 / 0.49, math.radians(15.0), math.radians(25.0)


def plan(wide_angle=WIDE_ANGLE, wide_end=0.0):
    return LeftTurn(TIGHT, WIDE, wide_angle, wide_end)


@pytest.mark.parametrize('angle_deg', [10.0, 45.0, 90.0])
def test_without_a_wide_start_it_is_one_arc(angle_deg):
    angle = math.radians(angle_deg)
    assert plan(0.0).gap(angle) == pytest.approx(TIGHT * (1.0 - math.cos(angle)))
    assert plan(0.0).arc_radius(angle) == TIGHT


def test_a_square_turn_uses_the_wide_arc_first_then_the_tight_one():
    # The wide arc turns from 90 to 75 deg, the tight one from 75 deg to parallel.
    expected = WIDE * math.sin(WIDE_ANGLE) + TIGHT * (1.0 - math.sin(WIDE_ANGLE))
    assert plan().gap(math.pi / 2) == pytest.approx(expected)
    assert plan().arc_radius(math.radians(80.0)) == WIDE
    assert plan().arc_radius(math.radians(70.0)) == TIGHT


def test_a_wide_end_takes_the_turns_last_angles_on_the_wide_arc():
    # Wide from 90 to 75 deg, tight from 75 to 25 deg, wide again to parallel.
    turn = plan(wide_end=WIDE_END)
    expected = (WIDE * math.sin(WIDE_ANGLE)
                + TIGHT * (math.cos(WIDE_END) - math.sin(WIDE_ANGLE))
                + WIDE * (1.0 - math.cos(WIDE_END)))
    assert turn.gap(math.pi / 2) == pytest.approx(expected)
    assert [turn.arc_radius(math.radians(a)) for a in (80.0, 50.0, 20.0)] == [WIDE, TIGHT, WIDE]
    # A turn through less than the wide end's share is all wide.
    assert turn.gap(math.radians(20.0)) == pytest.approx(
        WIDE * (1.0 - math.cos(math.radians(20.0))))


def test_wide_ends_that_meet_leave_no_tight_arc():
    turn = plan(math.radians(50.0), math.radians(60.0))
    assert turn.gap(math.pi / 2) == pytest.approx(WIDE)
    assert turn.arc_radius(math.radians(45.0)) == WIDE


@pytest.mark.parametrize('wide_end', [0.0, WIDE_END])
def test_the_gap_grows_with_the_angle_left_and_has_no_jump(wide_end):
    angles = [math.radians(a / 10.0) for a in range(0, 901)]
    gaps = [plan(wide_end=wide_end).gap(a) for a in angles]
    assert gaps[0] == 0.0
    assert all(later > earlier for earlier, later in zip(gaps, gaps[1:]))
    assert max(later - earlier for earlier, later in zip(gaps, gaps[1:])) < 1e-3


def test_angles_past_a_right_angle_are_turned_on_the_first_arc():
    # Heading 30 deg into the wall it leaves, the wide start first turns
    # back to square, coming WIDE * sin(30 deg) nearer the wall ahead.
    past = plan().gap(math.radians(120.0)) - plan().gap(math.pi / 2)
    assert past == pytest.approx(WIDE * 0.5)
    # Even without a wide start: turning back to square only comes nearer
    # the old wall, so those degrees are flown wide.
    assert plan(0.0).gap(math.radians(120.0)) == pytest.approx(WIDE * 0.5 + TIGHT)
    assert plan(0.0).arc_radius(math.radians(100.0)) == WIDE
    assert plan().gap(-0.1) == 0.0


def test_the_wide_start_drifts_off_the_old_wall_as_its_arc_does():
    assert plan().drift(math.pi / 2) == pytest.approx(WIDE * (1.0 - math.cos(WIDE_ANGLE)))
    assert plan().drift(math.radians(120.0)) == plan().drift(math.pi / 2)
    assert plan(0.0).drift(math.pi / 2) == 0.0


def test_a_turn_short_of_the_tight_arcs_share_has_no_wide_start_and_no_drift():
    assert plan().drift(math.radians(45.0)) == 0.0
    assert plan().drift(math.radians(80.0)) == pytest.approx(
        WIDE * (1.0 - math.cos(math.radians(5.0))))


def test_with_the_gap_it_plans_the_turn_flies_the_planned_arc():
    for angle_deg in (85.0, 60.0, 10.0):
        angle = math.radians(angle_deg)
        turn = plan(wide_end=WIDE_END)
        assert turn.radius_within(turn.gap(angle), angle) == turn.arc_radius(angle)


def test_a_long_gap_is_spent_on_the_wide_end_not_on_a_wider_tight_arc():
    # Begun early, the tight arc is flown as planned, and the wide end
    # begins as soon as a wide arc from here ends the turn where planned.
    angle = math.radians(60.0)
    turn = plan(wide_end=WIDE_END)
    assert turn.radius_within(1.2 * turn.gap(angle), angle) == TIGHT
    assert turn.radius_within(WIDE * (1.0 - math.cos(angle)), angle) == WIDE
    assert turn.radius_within(3.0 * turn.gap(angle), angle) == WIDE
    # The wide start was at its widest already.
    assert turn.radius_within(1.2 * turn.gap(math.radians(85.0)), math.radians(85.0)) == WIDE
    # Planned without a wide end, the tight arc widens to end where planned.
    assert plan().radius_within(1.2 * plan().gap(angle), angle) == pytest.approx(1.2 * TIGHT)


def fly(turn, gap, angle, step=math.radians(0.1)):
    """Fly a turn as radius_within commands it: (gap left at its end, farthest off the old wall
    at 45 degrees still to turn)."""
    off_old_wall = 0.0
    while angle > 0.0:
        radius = turn.radius_within(gap, angle)
        gap -= radius * (math.cos(angle - step) - math.cos(angle))
        if angle > math.pi / 4:
            off_old_wall += radius * (math.sin(angle) - math.sin(angle - step))
        angle -= step
    return gap, off_old_wall


@pytest.mark.parametrize('early', [0.005, 0.015, 0.03])
def test_an_early_turn_ends_where_planned_and_passes_the_corner_as_planned(early):
    turn = plan(wide_end=WIDE_END)
    start = math.radians(70.0)
    _, planned_off = fly(turn, turn.gap(start), start)
    gap, off = fly(turn, turn.gap(start) + early, start)
    assert abs(gap) < 2e-3
    # Scaling the tight arc up instead would swing the robot farther off the
    # wall it leaves by the corner.
    assert off == pytest.approx(planned_off, abs=1e-3)


def test_a_short_gap_shrinks_the_rest_of_the_turn_in_proportion():
    angle = math.radians(85.0)
    turn = plan()
    assert turn.radius_within(0.5 * turn.gap(angle), angle) == pytest.approx(0.5 * WIDE)
    assert turn.radius_within(0.0, angle) == 0.0
    assert turn.radius_within(-0.1, angle) == 0.0


def test_a_wide_start_cut_short_drifts_no_more_than_allowed():
    turn = plan(wide_end=WIDE_END)
    drift = WIDE * (1.0 - math.cos(math.radians(10.0)))
    cut = turn.drifting_at_most(drift)
    assert cut.wide_start == pytest.approx(math.radians(10.0))
    assert cut.drift(math.pi / 2) == pytest.approx(drift)
    # The tight arc takes over the angles cut off; the wide end stays.
    assert [cut.arc_radius(math.radians(a)) for a in (85.0, 75.0, 20.0)] == [WIDE, TIGHT, WIDE]
    assert turn.drifting_at_most(1.0).gap(math.pi / 2) == turn.gap(math.pi / 2)
    no_start = turn.drifting_at_most(-0.01)
    assert no_start.gap(math.pi / 2) == pytest.approx(plan(0.0, WIDE_END).gap(math.pi / 2))
