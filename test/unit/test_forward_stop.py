"""Forward/stop: the schedule on the clock, and the stop for something close ahead."""
import math

import pytest

from laser_conventions import CONVENTIONS, box, scan_view
from wall_follower.control.motion import STOP, Command
from wall_follower.exercises.forward_stop import BLOCKED, FORWARD, STOPPED, ForwardStop

ROOM = box(-2.0, -2.0, 2.0, 2.0)


@pytest.mark.parametrize('convention', CONVENTIONS, ids=lambda c: c.name)
def test_alternates_forward_and_stop_on_the_schedule(convention):
    behaviour = ForwardStop()
    view = scan_view(ROOM, (0.0, 0.0, 0.0), convention)
    states = [behaviour.update(view, 100.0 + 0.1 * i) for i in range(200)]
    assert all(c == Command(0.2, 0.0) for c in states[:50])
    assert all(c == STOP for c in states[50:100])
    assert all(c == Command(0.2, 0.0) for c in states[100:150])


def test_periods_are_parameters():
    behaviour = ForwardStop(forward_period=1.0, stop_period=0.5)
    assert [behaviour.phase(t) for t in (0.0, 0.95, 1.05, 1.45, 1.55)] == \
        [FORWARD, FORWARD, STOPPED, STOPPED, FORWARD]


@pytest.mark.parametrize('convention', CONVENTIONS, ids=lambda c: c.name)
def test_stands_in_a_forward_phase_while_something_is_close_ahead(convention):
    behaviour = ForwardStop(stop_distance=0.4)
    near = scan_view(ROOM, (1.7, 0.0, 0.0), convention)
    far = scan_view(ROOM, (1.0, 0.0, 0.0), convention)
    assert behaviour.update(near, 0.0) == STOP
    assert behaviour.state == BLOCKED
    assert behaviour.update(far, 0.1) == Command(0.2, 0.0)


def test_a_wall_beside_the_cone_does_not_stop_it():
    behaviour = ForwardStop(stop_distance=0.4, cone_half_width=math.radians(20.0))
    corridor = [((-3.0, 0.3), (3.0, 0.3)), ((-3.0, -0.3), (3.0, -0.3))]
    view = scan_view(corridor, (0.0, 0.0, 0.0), CONVENTIONS[0])
    assert behaviour.update(view, 0.0) == Command(0.2, 0.0)


def test_new_periods_start_a_new_cycle_and_other_changes_keep_the_phase():
    behaviour = ForwardStop(forward_period=1.0, stop_period=1.0)
    assert behaviour.phase(0.0) == FORWARD and behaviour.phase(1.5) == STOPPED
    behaviour.reconfigure(forward_period=1.0, stop_period=1.0, speed=0.1)
    assert behaviour.phase(1.6) == STOPPED
    behaviour.reconfigure(forward_period=2.0, stop_period=1.0, speed=0.1)
    assert [behaviour.phase(t) for t in (1.7, 3.6, 3.8, 4.6, 4.8)] == \
        [FORWARD, FORWARD, STOPPED, STOPPED, FORWARD]


def test_a_period_out_of_range_is_refused_by_name():
    with pytest.raises(ValueError, match='forward_period must be at least'):
        ForwardStop(forward_period=0.0)
