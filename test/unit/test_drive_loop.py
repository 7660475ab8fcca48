"""DriveLoop with a scripted clock, source and commander: when it answers, stops and gives up.

Needs ROS's Python modules but no master: rospy's clock and shutdown flag
are replaced by the test's.
"""
import math

import pytest
import rospy

from wall_follower.control.motion import STOP, Answer, Command
from wall_follower.control.sensing.scan_check import check_scan
from wall_follower.nodes.shared.drive_loop import FINISHED_NO_INPUT, DriveLoop, tune_drive_loop
from wall_follower.nodes.shared.latest_scan import Reading
from wall_follower.params.driving import CAMERA_INPUT, LASER_INPUT

PERIOD = 0.05


class Clock(object):
    """ROS time in s, moved on by the scripted scan source at every wait."""
    now = 0.0


class Commander(object):
    def __init__(self):
        self.sent = []
        self.last = STOP

    def send(self, command):
        self.last = command
        self.sent.append((Clock.now, command))

    def stop(self):
        self.send(STOP)


class Msg(object):
    def __init__(self, ranges):
        self.ranges = ranges
        self.angle_min, self.angle_increment = 0.0, 2.0 * math.pi / len(ranges)
        self.angle_max = self.angle_increment * (len(ranges) - 1)
        self.range_min, self.range_max = 0.12, 3.5


GOOD = Msg([1.0] * 360)
DEAD = Msg([0.0] * 360)
BLIND_AHEAD = Msg([0.0] * 31 + [1.0] * 299 + [0.0] * 30)
# Beam 0 ahead: the sector within 30 deg ahead is beams 330..359 and 0..30 (61 beams).
ONE_BEAM_AHEAD = Msg([1.0] + [0.0] * 30 + [1.0] * 299 + [0.0] * 30)
# Beams 150..210: the sector within 30 deg behind.
BLIND_BEHIND = Msg([1.0] * 150 + [0.0] * 61 + [1.0] * 149)
DROPOUTS_AHEAD = Msg([1.0 if i % 4 else 0.0 for i in range(360)])
# 8 of the 61 beams within 30 deg ahead read valid, all right of straight ahead: in view,
# but by fewer than twice the tenth needed.
NARROW_AHEAD = Msg([0.0] * 31 + [1.0] * 299 + [1.0] * 8 + [0.0] * 22)
# The same, with the wall on the right (beams 240..300, within 30 deg of beam 270) at 0.2 m.
NARROW_AHEAD_WALL_NEAR = Msg(NARROW_AHEAD.ranges[:240] + [0.2] * 61 + NARROW_AHEAD.ranges[301:])


class Scans(object):
    """Delivers script[i] = (time, msg) as the clock passes each time; a float
    for msg sets the clock to it instead."""

    def __init__(self, script, timeout=0.5):
        self.script = list(script)
        self.timeout = timeout
        self.current = None
        self.arrival = None
        self.forgotten = 0

    def latest(self, timeout):
        if self.current is None or Clock.now - self.arrival > timeout:
            return Reading(self.current, None, None, 'no scan')
        if self.current.view is None:
            return Reading(self.current, None, None, self.current.problem)
        return Reading(self.current, self.current.view, self.arrival, None)

    def forget(self):
        self.current = None
        self.forgotten += 1

    def wait_for_newer(self, _seen, timeout):
        Clock.now += timeout
        while self.script and self.script[0][0] <= Clock.now:
            when, msg = self.script.pop(0)
            if isinstance(msg, float):
                Clock.now = msg   # the clock jumps
            else:
                self.current, self.arrival = check_scan(msg), when


@pytest.fixture(autouse=True)
def ros_clock(monkeypatch):
    Clock.now = 0.0
    monkeypatch.setattr(rospy, 'get_time', lambda: Clock.now)
    monkeypatch.setattr(rospy, 'is_shutdown', lambda: False)
    monkeypatch.setattr(rospy, 'logwarn', lambda *args: Clock.warnings.append(args[-1]))
    Clock.warnings = []


def run(script, until, answer=lambda view, taken: Command(0.1, 0.2), **kwargs):
    scans, commander = Scans(script), Commander()
    loop = DriveLoop('test', scans, commander, 1.0 / PERIOD, keepalive=0.15, input_timeout=0.5)
    outcome = loop.run(answer, lambda: 'end' if Clock.now >= until else None, **kwargs)
    return outcome, commander.sent, scans


def test_each_new_scan_is_answered_once_and_repeated_after_keepalive():
    outcome, sent, _ = run([(0.1, GOOD)], until=0.5)
    assert outcome == 'end'
    moving = [t for t, c in sent if c == Command(0.1, 0.2)]
    assert moving[0] == pytest.approx(0.1)
    assert all(b - a >= 0.15 - 1e-9 for a, b in zip(moving, moving[1:]))
    assert sent[-1][1] == STOP


class StampedScans(Scans):
    """Scans as Scans, each stamped as `stamps` says (arrival time -> stamp)."""

    def __init__(self, script, stamps):
        super().__init__(script)
        self.stamps = stamps

    def latest(self, timeout):
        reading = super().latest(timeout)
        if reading.view is None:
            return reading
        return reading._replace(taken=self.stamps[reading.taken])


@pytest.mark.parametrize('simulated', [True, False])
def test_an_answer_to_a_scan_ahead_of_the_clock_is_repeated_a_keepalive_after_its_stamp(
        monkeypatch, simulated):
    # Steps of 0.1 s. A simulator sends each step's scan before its /clock: the scan
    # of 0.2 s comes while this node's clock reads 0.1. The next one (0.3 s) comes
    # after its /clock, and no keepalive is due before it: a repeat then would be
    # taken in lockstep for the answer to it. On wall time a stamp proves nothing (a
    # laser host's clock may run ahead), and the keepalive counts by this node's clock.
    monkeypatch.setattr(rospy.rostime, 'is_wallclock', lambda: not simulated)
    scans = StampedScans([(0.099, GOOD), (0.299, GOOD)], {0.099: 0.2, 0.299: 0.3})
    commander = Commander()
    loop = DriveLoop('test', scans, commander, 1.0 / PERIOD, keepalive=0.15, input_timeout=0.5)
    loop.run(lambda view, taken: Command(0.1, 0.2), lambda: 'end' if Clock.now >= 0.32 else None)
    moving = [t for t, c in commander.sent if c == Command(0.1, 0.2)]
    expected = [0.1, 0.3] if simulated else [0.1, 0.25, 0.3]
    assert moving == [pytest.approx(t) for t in expected]


def test_a_stale_scan_stops_the_robot_and_a_new_one_resumes_it():
    outcome, sent, _ = run([(0.1, GOOD), (2.0, GOOD)], until=2.2)
    after_timeout = [c for t, c in sent if 0.65 <= t < 2.0]
    assert after_timeout and all(c == STOP for c in after_timeout)
    assert any(c == Command(0.1, 0.2) for t, c in sent if t >= 2.0)


def test_an_unusable_scan_stops_the_robot_at_once():
    outcome, sent, _ = run([(0.1, GOOD), (0.3, DEAD), (0.6, GOOD)], until=0.8)
    assert [c for t, c in sent if 0.3 <= t < 0.6] and all(
        c == STOP for t, c in sent if 0.3 <= t < 0.6)
    assert any(c == Command(0.1, 0.2) for t, c in sent if t >= 0.6)


def test_an_unusable_scan_is_warned_of_with_what_is_wrong_and_not_again_at_once():
    run([(0.1, DEAD), (0.2, DEAD)], until=0.5)
    assert Clock.warnings == ['none of its 360 readings is usable (360 0.0); stopped']


def test_no_forward_motion_into_a_sector_with_no_valid_reading():
    outcome, sent, _ = run([(0.1, BLIND_AHEAD)], until=0.5)
    answered = [c for t, c in sent if c != STOP]
    assert answered and all(c == Command(0.0, 0.2) for c in answered)
    assert Clock.warnings == ['no valid reading within 30 deg ahead; not driving forward']


def test_no_forward_motion_when_a_beam_or_two_of_the_sector_ahead_read_valid():
    outcome, sent, _ = run([(0.1, ONE_BEAM_AHEAD)], until=0.5)
    answered = [c for t, c in sent if c != STOP]
    assert answered and all(c == Command(0.0, 0.2) for c in answered)
    assert Clock.warnings == ['only 1 of the 61 beams within 30 deg ahead read valid '
                              '(10% needed); not driving forward']


def test_dropouts_scattered_across_the_sector_ahead_do_not_stop_the_robot():
    outcome, sent, _ = run([(0.1, DROPOUTS_AHEAD)], until=0.5)
    assert any(c == Command(0.1, 0.2) for t, c in sent)
    assert Clock.warnings == []


def test_backwards_motion_is_not_held_back_by_a_blind_sector_ahead():
    outcome, sent, _ = run([(0.1, BLIND_AHEAD)], until=0.5,
                           answer=lambda view, taken: Command(-0.1, 0.0))
    assert any(c == Command(-0.1, 0.0) for t, c in sent)


def test_backwards_motion_into_a_blind_sector_behind_keeps_only_its_turn():
    outcome, sent, _ = run([(0.1, BLIND_BEHIND)], until=0.5,
                           answer=lambda view, taken: Command(-0.1, 0.2))
    answered = [c for t, c in sent if c != STOP]
    assert answered and all(c == Command(0.0, 0.2) for c in answered)
    assert Clock.warnings == ['no valid reading within 30 deg behind; not driving backward']


def blind_run(script, until, answer=lambda view, taken: Command(0.1, 0.2)):
    """run() with a loop that turns in place at -0.3 rad/s while the way ahead is unseen;
    the commands sent."""
    scans, commander = Scans(script), Commander()
    loop = DriveLoop('test', scans, commander, 1.0 / PERIOD, keepalive=0.15, input_timeout=0.5,
                     blind_turn=-0.3)
    loop.run(answer, lambda: 'end' if Clock.now >= until else None)
    return commander.sent


def every_tenth(msg, start, end):
    """A scan script: msg every 0.1 s from start to end [s]."""
    return [(round(t * 0.1, 3), msg) for t in range(int(round(start * 10)), int(round(end * 10)))]


def test_with_a_blind_turn_the_robot_turns_in_place_while_nothing_is_seen_ahead():
    sent = blind_run(every_tenth(BLIND_AHEAD, 0.1, 1.0), until=1.0)
    answered = [c for t, c in sent if c != STOP]
    assert answered and all(c == Command(0.0, -0.3) for c in answered)
    assert Clock.warnings == ['no valid reading within 30 deg ahead; turning in place to look '
                              'for the way']


def test_a_blind_turn_stops_once_half_a_turn_has_shown_nothing_ahead():
    # Half a turn at 0.3 rad/s takes 10.5 s.
    sent = blind_run(every_tenth(BLIND_AHEAD, 0.1, 12.0), until=12.0)
    assert all(c == Command(0.0, -0.3) for t, c in sent if 0.1 <= t < 10.4)
    assert all(c == STOP for t, c in sent if t >= 10.7)
    assert Clock.warnings[-1] == ('no valid reading within 30 deg ahead after turning 180 deg '
                                  'to look for it; stopped')


def test_a_view_ahead_ends_the_blind_turn_and_the_next_one_starts_afresh():
    script = (every_tenth(BLIND_AHEAD, 0.1, 10.0) + every_tenth(GOOD, 10.0, 10.5)
              + every_tenth(BLIND_AHEAD, 10.5, 12.0))
    sent = blind_run(script, until=12.0)
    assert any(c == Command(0.1, 0.2) for t, c in sent if 10.0 <= t < 10.5)
    assert all(c == Command(0.0, -0.3) for t, c in sent if 10.5 <= t < 11.9)


def test_a_command_turning_faster_than_the_blind_turn_keeps_its_own_turn():
    sent = blind_run(every_tenth(BLIND_AHEAD, 0.1, 0.5), until=0.5,
                     answer=lambda view, taken: Command(0.1, 0.49))
    answered = [c for t, c in sent if c != STOP]
    assert answered and all(c == Command(0.0, 0.49) for c in answered)
    assert Clock.warnings == ['no valid reading within 30 deg ahead; not driving forward']


def test_a_way_a_blind_turn_found_goes_straight_on_while_it_is_narrow():
    # The answer turns away from the side the blind turn looked to.
    script = (every_tenth(BLIND_AHEAD, 0.1, 0.5) + every_tenth(NARROW_AHEAD, 0.5, 1.0)
              + every_tenth(GOOD, 1.0, 1.5))
    sent = blind_run(script, until=1.5)
    assert all(c == Command(0.0, -0.3) for t, c in sent if 0.15 <= t < 0.5)
    assert all(c == Command(0.1, 0.0) for t, c in sent if 0.55 <= t < 1.0)
    assert any(c == Command(0.1, 0.2) for t, c in sent if t >= 1.05)


def test_a_way_a_blind_turn_found_is_given_up_by_a_turn_away_from_a_near_wall():
    # The answer turns away from the side the blind turn looked to, where the wall comes
    # within 0.215 m.
    script = (every_tenth(BLIND_AHEAD, 0.1, 0.5) + every_tenth(NARROW_AHEAD, 0.5, 0.8)
              + every_tenth(NARROW_AHEAD_WALL_NEAR, 0.8, 1.2))
    sent = blind_run(script, until=1.2)
    assert all(c == Command(0.1, 0.0) for t, c in sent if 0.55 <= t < 0.8)
    assert all(c == Command(0.1, 0.2) for t, c in sent if 0.85 <= t < 1.2)


def test_a_narrow_view_leaves_a_command_as_it_is_without_a_blind_turn_before_it():
    sent = blind_run(every_tenth(NARROW_AHEAD, 0.1, 0.5), until=0.5)
    answered = [c for t, c in sent if c != STOP]
    assert answered and all(c == Command(0.1, 0.2) for c in answered)


def test_a_blind_turn_leaves_other_commands_as_they_are():
    sent = blind_run(every_tenth(GOOD, 0.1, 0.5) + every_tenth(DROPOUTS_AHEAD, 0.5, 1.0), until=1.0)
    assert all(c == Command(0.1, 0.2) for t, c in sent if 0.1 <= t < 1.0)
    assert Clock.warnings == []


def test_with_patience_the_loop_gives_up_without_a_usable_scan():
    outcome, sent, _ = run([(0.1, DEAD)], until=10.0, patience=1.0)
    assert outcome == FINISHED_NO_INPUT
    assert Clock.now == pytest.approx(1.05, abs=PERIOD)
    assert all(c == STOP for t, c in sent)


def test_a_clock_that_runs_past_patience_in_a_burst_waits_once_for_the_scan_on_its_way():
    # Answered at 0.15 s; then the node is starved: on waking, ROS time has run
    # on to 2.5 s before the newest scan, taken just before, is handed on.
    outcome, sent, _ = run([(0.1, GOOD), (0.2, 2.5), (2.51, GOOD)], until=3.0, patience=1.0)
    assert outcome == 'end'
    assert any(c == Command(0.1, 0.2) for t, c in sent if t > 2.5)


def test_after_the_clock_moved_back_patience_again_runs_out_on_two_passes():
    # Patience first runs out at 1.0 s; then the clock moves back to 0.5 s,
    # and patience is counted afresh: out at 1.5 s, given up a pass later.
    outcome, _, _ = run([(1.03, 0.5)], until=10.0, patience=1.0)
    assert outcome == FINISHED_NO_INPUT
    assert Clock.now == pytest.approx(1.5 + PERIOD, abs=0.01)


def test_a_clock_moving_back_drops_the_scan_and_tells_the_node():
    resets = []
    outcome, sent, scans = run([(0.1, GOOD), (0.4, 0.05), (0.3, GOOD)], until=0.5,
                               on_clock_reset=lambda: resets.append(Clock.now))
    assert resets == [pytest.approx(0.05)]
    assert scans.forgotten == 1
    jump = next(i for i in range(1, len(sent)) if sent[i][0] < sent[i - 1][0])
    after_jump = sent[jump:]
    assert all(c == STOP for t, c in after_jump if t < 0.3)
    assert any(c == Command(0.1, 0.2) for t, c in after_jump if t >= 0.3)


def test_with_a_tick_the_loop_answers_on_a_steady_beat_between_scans():
    scans, commander = Scans([(0.1 + 0.2 * i, GOOD) for i in range(5)]), Commander()
    loop = DriveLoop('test', scans, commander, 1.0 / PERIOD, keepalive=0.15, input_timeout=0.5,
                     tick=0.1)
    answers = []
    loop.run(lambda view, taken: answers.append(Clock.now) or Command(0.1, 0.0),
             lambda: 'end' if Clock.now >= 1.0 else None)
    assert answers[0] == pytest.approx(0.1)
    gaps = [b - a for a, b in zip(answers, answers[1:])]
    assert gaps == pytest.approx([0.1] * len(gaps))
    assert len(answers) == 9


def test_with_a_tick_a_stale_scan_still_stops_the_robot():
    scans, commander = Scans([(0.1, GOOD)]), Commander()
    loop = DriveLoop('test', scans, commander, 1.0 / PERIOD, keepalive=0.15, input_timeout=0.5,
                     tick=0.1)
    loop.run(lambda view, taken: Command(0.1, 0.0), lambda: 'end' if Clock.now >= 1.5 else None)
    assert all(c == STOP for t, c in commander.sent if t > 0.65)


def test_an_answer_says_what_its_sensor_knows_ahead():
    """A camera's controller answers with an Answer: its word on the way ahead, not a share
    of beams, decides whether it may drive forward; without beams, a bare Command may not."""
    answers = iter([Answer(Command(0.1, 0.2), False), Answer(Command(0.1, 0.2), True),
                    Command(0.1, 0.2)])
    scans, commander = Scans([(0.1, BLIND_AHEAD), (0.2, GOOD), (0.3, GOOD)]), Commander()
    loop = DriveLoop('test', scans, commander, 1.0 / PERIOD, keepalive=0.15, input_timeout=0.5,
                     ahead_half_width=0.3, ahead_min_known=None, ahead_missing='no line known')
    loop.run(lambda view, taken: next(answers), lambda: 'end' if Clock.now >= 0.35 else None)
    answered = [c for t, c in commander.sent if c != STOP]
    assert answered == [Command(0.0, 0.2), Command(0.1, 0.2), Command(0.0, 0.2)]
    assert Clock.warnings == ['no line known within 17 deg ahead; not driving forward']


class Source(object):
    def __init__(self, parameters):
        self.parameters = parameters


@pytest.mark.parametrize('parameters,timeout,min_known', [
    (LASER_INPUT, 0.7, 0.2), (CAMERA_INPUT, 0.3, None)])
def test_a_loop_is_tuned_from_the_parameters_its_source_names(parameters, timeout, min_known):
    values = {'rate': 10.0, 'keepalive': 0.1, 'scan_timeout': 0.7, 'image_timeout': 0.3,
              'ahead_half_width': 0.4, 'ahead_min_known': 0.2, 'max_linear': 0.1,
              'max_angular': 0.3}
    loop = DriveLoop('test', Source(parameters), Commander(), 1.0 / PERIOD, keepalive=0.15,
                     input_timeout=0.5)
    tune_drive_loop(loop, values)
    assert (loop.input_timeout, loop.ahead_min_known, loop.ahead_half_width) == (
        timeout, min_known, 0.4)
    assert (loop.commander.max_linear, loop.commander.max_angular) == (0.1, 0.3)


def test_a_retuned_blind_turn_is_the_turn_made_for_want_of_a_view_ahead():
    scans, commander = Scans(every_tenth(BLIND_AHEAD, 0.1, 1.0)), Commander()
    loop = DriveLoop('test', scans, commander, 1.0 / PERIOD, keepalive=0.15, input_timeout=0.5)
    values = {'rate': 1.0 / PERIOD, 'keepalive': 0.15, 'scan_timeout': 0.5,
              'ahead_half_width': math.radians(30.0), 'ahead_min_known': 0.1,
              'blind_turn': 0.25, 'max_linear': 0.1, 'max_angular': 0.3}

    def answer(view, taken):
        tune_drive_loop(loop, dict(values, blind_turn=0.0 if Clock.now > 0.5 else 0.25))
        return Command(0.1, 0.2)

    scans.parameters = LASER_INPUT
    loop.run(answer, lambda: 'end' if Clock.now >= 1.0 else None)
    assert all(c == Command(0.0, 0.25) for t, c in commander.sent if 0.1 <= t <= 0.5)
    assert any(c == Command(0.0, 0.2) for t, c in commander.sent if 0.5 < t < 1.0)
