"""wander: forward until something is close in the cone, then pivot to the open side until clear."""
import math

import pytest

from laser_conventions import CONVENTIONS, LDS01, box, scan_view
from wall_follower.control.motion import Command
from wall_follower.control.sensing.scan import ScanView
from wall_follower.exercises.wander import FORWARD, TURN, Wanderer

ROOM = box(-2.0, -1.0, 1.0, 1.0)


@pytest.mark.parametrize('convention', CONVENTIONS, ids=lambda c: c.name)
def test_drives_forward_with_room_ahead(convention):
    wanderer = Wanderer()
    assert wanderer.update(scan_view(ROOM, (0.0, 0.0, 0.0), convention)) == Command(0.19, 0.0)


@pytest.mark.parametrize('convention', CONVENTIONS, ids=lambda c: c.name)
@pytest.mark.parametrize('y, sign', [(0.6, -1.0), (-0.6, 1.0)])
def test_turns_toward_the_more_open_side_until_clear(convention, y, sign):
    wanderer = Wanderer()
    command = wanderer.update(scan_view(ROOM, (0.7, y, 0.0), convention))
    assert wanderer.state == TURN and command == Command(0.0, sign * 0.49)
    # still blocked a little further round: the side chosen is kept
    command = wanderer.update(scan_view(ROOM, (0.7, y, sign * 0.3), convention))
    assert command == Command(0.0, sign * 0.49)
    # facing down the room: clear, forward again
    command = wanderer.update(scan_view(ROOM, (0.7, y, math.pi), convention))
    assert wanderer.state == FORWARD and command == Command(0.19, 0.0)


def test_lds01_zeros_are_not_a_wall_at_zero():
    """The book's min(ranges) sees an LDS-01's 0.0 as a wall and spins for ever."""
    view = scan_view(ROOM, (0.0, 0.0, 0.0), LDS01)
    ranges = view.ranges.copy()
    ranges[100:140] = 0.0     # dropouts on the left
    wanderer = Wanderer()
    assert wanderer.update(ScanView(ranges, 0.0, LDS01.increment, 0.12, 3.5)) == Command(0.19, 0.0)


def test_a_cone_with_nothing_known_counts_as_blocked():
    view = scan_view(ROOM, (0.0, 0.0, 0.0), LDS01)
    ranges = view.ranges.copy()
    ranges[:40] = 0.0
    ranges[-40:] = 0.0
    wanderer = Wanderer()
    command = wanderer.update(ScanView(ranges, 0.0, LDS01.increment, 0.12, 3.5))
    assert wanderer.state == TURN and command.linear == 0.0


def test_clear_distance_below_obstacle_distance_is_refused():
    with pytest.raises(ValueError):
        Wanderer(obstacle_distance=0.5, clear_distance=0.4)


def test_a_new_speed_is_used_at_the_next_scan():
    wanderer = Wanderer()
    view = scan_view(ROOM, (0.0, 0.0, 0.0), CONVENTIONS[0])
    wanderer.reconfigure(speed=0.1)
    assert wanderer.update(view) == Command(0.1, 0.0)


def test_a_change_that_breaks_a_rule_is_refused_and_the_old_values_kept():
    wanderer = Wanderer()
    with pytest.raises(ValueError, match='clear_distance .* must not be below obstacle_distance'):
        wanderer.reconfigure(obstacle_distance=0.6)
    assert wanderer.p['obstacle_distance'] < wanderer.p['clear_distance']
