"""The watchdog's cuts as grading counts them (evaluation/grading/commands.py), with no ROS.

A run is played as the simulators step it (command_replay.py).
"""
import pytest

from command_replay import SIMULATORS, STEP, WATCHDOG, stage_log
from wall_follower.evaluation.grading.commands import CommandLog, watchdog_note


def every_step(first, last, linear=0.19, angular=0.0, late=lambda sent: 0.0):
    """A command sent at every step from first to last, heard late(sent) s late."""
    return [(sent, sent * STEP + late(sent), linear, angular) for sent in range(first, last + 1)]


def cuts(commands, steps, simulator='builtin'):
    return stage_log(commands, steps, simulator).record()['cut_by_watchdog']


def bursts(sent):
    """A busy grader: every fourth command heard 0.35 s late, the next three with it."""
    return 0.35 - (sent % 4) * STEP if sent % 4 else 0.0


@pytest.mark.parametrize('simulator', SIMULATORS)
def test_commands_heard_late_or_in_bursts_while_the_robot_moves_are_no_cuts(simulator):
    commands = every_step(0, 600, late=bursts)
    commands[100:110] = every_step(100, 109, late=lambda sent: 0.5)
    assert cuts(commands, 600, simulator) == 0


@pytest.mark.parametrize('simulator', SIMULATORS)
def test_a_command_heard_a_step_late_is_no_cut_but_two_steps_unsent_are(simulator):
    commands = every_step(0, 383, late=lambda sent: STEP if sent == 381 else 0.0)
    assert cuts(commands, 384, simulator) == 0
    # Nothing sent for the steps at 38.4 and 38.5: the watchdog stopped the robot.
    commands += every_step(386, 400)
    assert cuts(commands, 400, simulator) == 1


@pytest.mark.parametrize('simulator', SIMULATORS)
def test_a_command_sent_once_then_silence_is_cut(simulator):
    log = stage_log([(10, 1.0, 0.10, 0.196)], 100, simulator)
    assert log.record()['cut_by_watchdog'] == 1
    assert watchdog_note(log.record()) == (
        "each command was sent once and stopped by the simulator's 0.2 s watchdog: "
        "publish cmd_vel continuously")


@pytest.mark.parametrize('simulator', SIMULATORS)
def test_commands_sent_once_are_cut_even_when_a_stop_follows_later(simulator):
    commands = [(10, 1.0, 0.0, 0.196), (30, 3.3, 0.10, 0.196), (50, 5.0, 0.0, 0.0)]
    log = stage_log(commands, 100, simulator)
    assert (log.record()['moving'], log.record()['cut_by_watchdog']) == (2, 2)


@pytest.mark.parametrize('simulator', SIMULATORS)
def test_a_stop_the_solution_commanded_is_no_cut(simulator):
    # It moves, then stands, telling the robot to stand at every step or once only.
    assert cuts(every_step(0, 100) + every_step(101, 200, linear=0.0), 200, simulator) == 0
    assert cuts(every_step(0, 100) + [(101, 10.1, 0.0, 0.0)], 200, simulator) == 0


@pytest.mark.parametrize('simulator', SIMULATORS)
def test_a_stop_heard_late_is_still_the_solutions_own(simulator):
    commands = every_step(0, 100) + [(101, 10.1 + 0.15, 0.0, 0.0)]
    assert cuts(commands, 200, simulator) == 0


def test_zero_commands_alone_are_never_cut():
    log = stage_log([(5, 0.5, 0.0, 0.0)], 100)
    assert log.record() == {'count': 1, 'moving': 0, 'cut_by_watchdog': 0, 'watchdog': WATCHDOG,
                            'non_finite': None}
    assert watchdog_note(log.record()) == ''


def test_a_stalled_robot_pushing_on_is_no_cut():
    # Against a wall the robot stands, but odometry's twist stays at the command it pushes
    # with (real Stage and the built-in simulator alike): heard late or not, nothing was cut.
    log = CommandLog(WATCHDOG)
    for index in range(1, 100):
        log.add(index * STEP + (0.3 if index % 7 == 0 else 0.0), 0.19, 0.0)
        log.applied(index * STEP, 0.19, 0.0)
    assert log.record()['cut_by_watchdog'] == 0


def test_a_cut_is_counted_whichever_is_heard_first():
    # Odometry's stop heard before the command that moves the robot on, and after it.
    for stop_first in (True, False):
        log = CommandLog(WATCHDOG)
        log.add(1.0, 0.19, 0.0)
        log.applied(1.1, 0.19, 0.0)
        log.applied(1.2, 0.19, 0.0)
        if stop_first:
            log.applied(1.3, 0.0, 0.0)
        log.add(1.5, 0.19, 0.0)
        if not stop_first:
            log.applied(1.3, 0.0, 0.0)
        assert log.record()['cut_by_watchdog'] == 1
