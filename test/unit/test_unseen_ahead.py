"""The hold on forward motion into an unseen way ahead, and the turn in place that looks for it."""
import math

import pytest

from wall_follower.control.motion import STOP, Command
from wall_follower.control.sensing.scan import ScanView
from wall_follower.control.unseen_ahead import (BLIND_TURN_LIMIT, BlindTurn, held_back,
                                                narrow_ahead, unseen_ahead)

FORWARD = Command(0.19, -0.1)
UNSEEN = 'no valid reading within 30 deg ahead'


def view(ranges):
    """A 360-beam LDS-01 scan, beam 0 ahead, counter-clockwise."""
    return ScanView(ranges, 0.0, 2.0 * math.pi / len(ranges), 0.12, 3.5)


def test_the_way_ahead_is_seen_when_a_tenth_of_its_beams_read_valid():
    # 61 beams lie within 30 deg ahead: beams 330..359 and 0..30.
    seven = [1.0] * 7 + [0.0] * 24 + [1.0] * 299 + [0.0] * 30
    six = [1.0] * 6 + [0.0] * 25 + [1.0] * 299 + [0.0] * 30
    assert unseen_ahead(view(seven), math.radians(30.0), 0.1) is None
    assert unseen_ahead(view(six), math.radians(30.0), 0.1) == (
        'only 6 of the 61 beams within 30 deg ahead read valid (10% needed)')
    assert unseen_ahead(view([0.0] * 31 + [1.0] * 299 + [0.0] * 30),
                        math.radians(30.0), 0.1) == UNSEEN


def test_a_view_ahead_is_narrow_below_twice_the_share_needed():
    # 61 beams within 30 deg ahead: 12 valid are fewer than twice a tenth, 13 are not.
    twelve = [1.0] * 12 + [0.0] * 19 + [1.0] * 299 + [0.0] * 30
    thirteen = [1.0] * 13 + [0.0] * 18 + [1.0] * 299 + [0.0] * 30
    assert narrow_ahead(view(twelve), math.radians(30.0), 0.1)
    assert not narrow_ahead(view(thirteen), math.radians(30.0), 0.1)


def a_kept_way(left):
    """A BlindTurn to the right that has turned for want of a view at 0 s and, at 0.5 s,
    found a way it keeps: while the view is narrow, left (a command turning away from the
    turn's side) goes straight on."""
    turn = BlindTurn(-0.3)
    assert held_back(Command(0.19, 0.1), UNSEEN, turn, 0.0) == Command(0.0, -0.3)
    assert held_back(left, None, turn, 0.5, narrow=True) == Command(left.linear, 0.0)
    return turn


def test_a_way_a_blind_turn_found_is_kept_until_a_command_turns_to_its_side():
    left = Command(0.19, 0.35)
    turn = a_kept_way(left)
    assert held_back(left, None, turn, 0.6, narrow=False) == left
    # Lost again: looked for the way it was found, not at the command's own turn.
    assert held_back(left, UNSEEN, turn, 0.7) == Command(0.0, -0.3)
    assert held_back(left, None, turn, 0.8, narrow=True) == Command(0.19, 0.0)
    # A command that turns to the turn's side ends the keeping.
    assert held_back(Command(0.19, -0.1), None, turn, 0.9, narrow=True) == Command(0.19, -0.1)
    assert held_back(left, None, turn, 1.0, narrow=True) == left
    assert held_back(left, UNSEEN, turn, 1.1) == Command(0.0, 0.35)


def test_a_command_that_turns_in_place_away_from_a_kept_way_gives_it_up():
    left = Command(0.19, 0.49)
    turn = a_kept_way(left)
    # An in-place turn toward the turn's side keeps the way ...
    assert held_back(Command(0.0, -0.49), UNSEEN, turn, 0.6) == Command(0.0, -0.49)
    assert held_back(left, UNSEEN, turn, 0.7) == Command(0.0, -0.3)
    assert held_back(left, None, turn, 0.8, narrow=True) == Command(0.19, 0.0)
    # ... one away from it gives it up: the command's own turn goes on, in place.
    assert held_back(Command(0.0, 0.49), UNSEEN, turn, 0.9) == Command(0.0, 0.49)
    assert not turn.keeping
    assert held_back(left, UNSEEN, turn, 1.0) == Command(0.0, 0.49)


def test_a_command_that_turns_away_from_a_near_wall_gives_a_kept_way_up():
    # Each look for the way again had turned the robot further into its
    # wall, and held straight on it closed on the wall while the follower
    # asked to turn away (generated world 35 of seed 109, LDS-01).
    left = Command(0.1, 0.49)
    turn = a_kept_way(left)
    # A near wall alone, with nothing turning away from it, keeps the way ...
    assert held_back(Command(0.1, 0.0), None, turn, 0.6, narrow=True, near=True) == (
        Command(0.1, 0.0))
    assert turn.keeping
    # ... a turn away from it gives it up: the command goes as it is.
    assert held_back(left, None, turn, 0.7, narrow=True, near=True) == left
    assert not turn.keeping
    assert held_back(left, None, turn, 0.8, narrow=True) == left


def test_the_wall_a_blind_turn_looks_toward_is_near_on_its_second_nearest_hit():
    # An LDS-01 scan, beam 270 straight right: the wall on the right at 0.3 m,
    # with hits at 0.2 m in beams 250 and 290, 20 deg either side of it.
    ranges = [2.0] * 360
    ranges[240:301] = [0.3] * 61
    turn = BlindTurn(-0.3)
    one_near, two_near = list(ranges), list(ranges)
    one_near[250] = two_near[250] = two_near[290] = 0.2
    assert not turn.wall_near(view(ranges))
    assert not turn.wall_near(view(one_near))
    assert turn.wall_near(view(two_near))
    assert not BlindTurn(-0.3, clearance=0.19).wall_near(view(two_near))
    # Toward the left for a turn to the left, where nothing is near.
    assert not BlindTurn(0.3).wall_near(view(two_near))
    # Beyond 30 deg of the right, the hits do not count.
    wide = list(ranges)
    wide[235] = wide[305] = 0.2
    assert not turn.wall_near(view(wide))


def test_a_narrow_view_leaves_commands_alone_until_a_blind_turn_has_found_a_way():
    turn = BlindTurn(-0.3)
    assert held_back(Command(0.19, 0.35), None, turn, 0.0, narrow=True) == Command(0.19, 0.35)
    assert held_back(Command(0.19, 0.35), None, None, 0.0, narrow=True) == Command(0.19, 0.35)


def test_without_a_blind_turn_forward_motion_into_the_unseen_is_taken_out():
    assert held_back(FORWARD, UNSEEN, None, 0.0) == Command(0.0, -0.1)
    assert held_back(FORWARD, None, None, 0.0) == FORWARD


def test_a_command_that_turns_faster_than_the_blind_turn_turns_in_place_at_its_own_rate():
    # A left turn onto a wall ahead that the laser does not show (a dark wall
    # an LDS-01 reads as 0.0): it goes on in place, not toward the wall on the
    # right, which would not bring the wall ahead into view.
    turn = BlindTurn(-0.3)
    assert held_back(Command(0.19, 0.49), UNSEEN, turn, 0.0) == Command(0.0, 0.49)
    assert held_back(Command(0.19, -0.3), UNSEEN, turn, 0.0) == Command(0.0, -0.3)
    assert held_back(Command(0.19, 0.29), UNSEEN, turn, 0.0) == Command(0.0, -0.3)


def test_a_blind_turn_under_way_goes_on_through_commands_that_turn_away_faster():
    # Round a wall's end into a room deeper than an LDS-01 reaches, the arc
    # round the tip asked for a left turn now slower, now faster than the
    # blind turn: each fast one undid the blind turn in place, and the robot
    # turned to and fro on the spot for good (gen_s98_039).
    turn = BlindTurn(-0.3)
    assert held_back(Command(0.12, 0.2), UNSEEN, turn, 0.0) == Command(0.0, -0.3)
    assert held_back(Command(0.12, 0.4), UNSEEN, turn, 0.1) == Command(0.0, -0.3)
    assert held_back(Command(0.12, 0.4), None, turn, 0.2) == Command(0.12, 0.4)


def test_a_turn_in_place_goes_as_it_is():
    turn = BlindTurn(-0.3)
    assert held_back(Command(0.0, 0.4), UNSEEN, turn, 0.0) == Command(0.0, 0.4)
    assert turn.turned(5.0) == 0.0


def test_the_way_behind_is_judged_on_the_beams_behind():
    # Beams 150..210 lie within 30 deg behind.
    blind_behind = [1.0] * 150 + [0.0] * 61 + [1.0] * 149
    assert unseen_ahead(view(blind_behind), math.radians(30.0), 0.1) is None
    assert unseen_ahead(view(blind_behind), math.radians(30.0), 0.1, backward=True) == (
        'no valid reading within 30 deg behind')
    assert unseen_ahead(view([1.0] * 360), math.radians(30.0), 0.1, backward=True) is None


def test_backward_motion_into_the_unseen_keeps_only_its_turn_and_never_starts_a_blind_turn():
    turn = BlindTurn(-0.3)
    behind = 'no valid reading within 30 deg behind'
    assert held_back(Command(-0.05, 0.1), behind, turn, 0.0) == Command(0.0, 0.1)
    assert held_back(Command(-0.05, 0.1), None, turn, 0.0) == Command(-0.05, 0.1)
    assert turn.turned(5.0) == 0.0


def test_a_blind_turn_turns_in_place_until_it_has_turned_its_limit():
    turn = BlindTurn(-0.3)
    limit_time = BLIND_TURN_LIMIT / 0.3
    assert held_back(FORWARD, UNSEEN, turn, 2.0) == Command(0.0, -0.3)
    assert held_back(FORWARD, UNSEEN, turn, 2.0 + limit_time - 0.1) == Command(0.0, -0.3)
    assert turn.turned(2.0 + limit_time - 0.1) == pytest.approx(BLIND_TURN_LIMIT - 0.03)
    assert held_back(FORWARD, UNSEEN, turn, 2.0 + limit_time) == STOP


def test_a_way_in_view_ends_the_turn_and_the_next_starts_afresh():
    turn = BlindTurn(0.3, limit=1.0)
    held_back(FORWARD, UNSEEN, turn, 0.0)
    assert held_back(FORWARD, UNSEEN, turn, 3.0) == Command(0.0, 0.3)
    assert held_back(FORWARD, None, turn, 3.1) == FORWARD
    assert turn.turned(3.2) == 0.0
    assert held_back(FORWARD, UNSEEN, turn, 4.0) == Command(0.0, 0.3)
    assert held_back(FORWARD, UNSEEN, turn, 7.0) == Command(0.0, 0.3)
    assert held_back(FORWARD, UNSEEN, turn, 7.4) == STOP


def test_a_clock_that_moved_back_starts_the_turn_afresh():
    turn = BlindTurn(-0.3, limit=1.0)
    turn.turn(10.0)
    assert turn.turn(12.0) == Command(0.0, -0.3)
    assert turn.turn(1.0) == Command(0.0, -0.3)
    assert turn.turned(2.0) == pytest.approx(0.3)
