"""The loop every driving node runs, on a laser or a camera, and the stops it makes.

One answer per reading (a scan, a camera frame), as soon as it arrives: in
lockstep simulation a command that merely repeats the last one would let
the world step on a stale decision. Between readings the last command is
sent again after `keepalive`, so that the robot's cmd_vel watchdog
(stageros: 0.2 s) does not stop it mid-turn. The robot is stopped, with a
throttled warning that says why, whenever the newest reading is older
than `input_timeout` or unusable, and it goes on by itself once usable
readings return. No command drives forward into what the sensor does not
show: a camera's controller answers with an Answer that says whether it
knows the way ahead; a laser's command is held back while fewer than
`ahead_min_known` of the beams within `ahead_half_width` of straight ahead
are valid readings (a hit or a proven no-return): a laser that sees
nothing there, or a beam or two of the sector, may be blind, not looking
at free space; with a `blind_turn`, the robot turns in place instead, to
bring the way ahead into view, and keeps a way it found in view while the
view is narrow and its wall not near (control.unseen_ahead.BlindTurn). Nor does a
laser's command drive backward into a sector behind that it does not show
by the same rule; it turns in place instead. A clock
that jumps back (a simulator restarted, a bag looped) drops the reading
held and lets the node reset what it timed on the old clock.

A node whose commands change between readings (keyboard teleop) can ask
for a steady beat instead: `tick` answers on a fixed ROS-time schedule
with the newest usable reading, however often the sensor sends one (an
LDS-01 sends 5).

drive_loop() builds a loop from a node's parameters (params.driving's
sections) on a LatestScan or a LatestImage, whose `parameters` name the
ones that set it (~scan_timeout and ~ahead_min_known for a laser,
~image_timeout for a camera; ~blind_turn where a node declares it);
tune_drive_loop() and take_retuned() put changed values in force.
"""
import math

import rospy

from wall_follower.control.motion import STOP, Answer
from wall_follower.control.stamps import arrival_time
from wall_follower.control.unseen_ahead import (BlindTurn, held_back, its_own_turn, narrow_ahead,
                                                unseen_ahead)
from wall_follower.nodes.shared.velocity import VelocityCommander
from wall_follower.params.driving import AHEAD_MIN_KNOWN

FINISHED_NO_INPUT = 'no input'
WARNING_PERIOD = 5.0   # ROS s between repeats of one warning
TICK_SLACK = 0.01      # share of a tick by which an answer may come early (clock rounding)


class DriveLoop(object):
    """Answers readings with commands through a VelocityCommander.

    source: where readings come from (a LatestScan, a LatestImage: latest(timeout),
    wait_for_newer(seen, timeout), forget()); commander: a VelocityCommander; name:
    the prefix of every log line. rate: how often (Hz) the loop looks at the clock while
    it waits for readings. keepalive, input_timeout: ROS seconds. ahead_half_width: rad
    either side of straight ahead; ahead_min_known: the share of a scan's beams there that
    must be valid for a bare Command to drive forward (None for a sensor with no beams,
    whose controller must answer with an Answer to drive forward). tick: None to answer
    each new reading once; else answer every tick ROS seconds, on a steady schedule, with
    the newest usable reading. ahead_missing: what the warning says is missing when an
    Answer does not know the way ahead. blind_turn: while forward motion is held back for
    want of a view ahead, turn in place at this rate [rad/s, positive left] to look for it,
    for at most control.unseen_ahead.BLIND_TURN_LIMIT, unless the command turns faster
    (control.unseen_ahead.held_back); None or 0 keeps the command's turn.
    """

    def __init__(self, name, source, commander, rate, keepalive, input_timeout,
                 ahead_half_width=math.radians(30.0), ahead_min_known=AHEAD_MIN_KNOWN, tick=None,
                 ahead_missing='nothing seen', blind_turn=None):
        self.name = name
        self.source = source
        self.commander = commander
        self._blind_turn = None
        self.tune(rate, keepalive, input_timeout, ahead_half_width, ahead_min_known, blind_turn)
        self.tick = tick
        self._ahead_missing = ahead_missing
        self._warned = (None, None)   # (text, ROS time) of the last warning
        # ROS times, set by run(): of this pass, of the last answer (or the start), of
        # the last command sent, and of the next tick.
        self._now = self._started = self._sent = self._due_at = None
        self._out_of_patience = False   # patience ran out on the pass before

    def tune(self, rate, keepalive, input_timeout, ahead_half_width, ahead_min_known,
             blind_turn=None):
        """Take new settings (as in the constructor); call it between two readings, from
        answer(). A changed blind_turn rate goes on with the turn under way."""
        self.period = 1.0 / rate
        self.keepalive = keepalive
        self.input_timeout = input_timeout
        self.ahead_half_width = ahead_half_width
        self.ahead_min_known = ahead_min_known
        if not blind_turn:
            self._blind_turn = None
        elif self._blind_turn is None:
            self._blind_turn = BlindTurn(blind_turn)
        else:
            self._blind_turn.rate = blind_turn

    def run(self, answer, finished=lambda: None, patience=None, on_clock_reset=None):
        """Drive until shutdown or finished() returns something other than None.

        answer(view, taken) -> a Command, or an Answer, for each new usable
        reading (taken: its stamp in s). finished: checked before each pass
        and right after each answer; what it returns ends the loop and is
        returned. patience: without a usable reading for this long [ROS s]
        the loop ends with FINISHED_NO_INPUT; None waits for ever, stopped.
        on_clock_reset(): called when ROS time has moved backwards.
        Returns None on shutdown. The robot is stopped on every way out.
        """
        seen = None
        self._now = self._started = self._sent = self._due_at = rospy.get_time()
        self._out_of_patience = False
        try:
            while not rospy.is_shutdown():
                outcome = finished()
                if outcome is not None:
                    return outcome
                self._read_clock(on_clock_reset)
                reading = self.source.latest(self.input_timeout)
                if reading.view is None:
                    if self._stop_without_input(reading, patience):
                        return FINISHED_NO_INPUT
                elif self._due(reading.check is not seen):
                    self._answer(answer, reading)
                    outcome = finished()
                    if outcome is not None:
                        return outcome
                elif self._now - self._sent >= self.keepalive:
                    self._send(self.commander.last)
                seen = reading.check
                self.source.wait_for_newer(seen, self.period)
            return None
        finally:
            self.commander.stop()

    def _read_clock(self, on_clock_reset):
        """Take the time of this pass; on a clock that moved back, start timing afresh."""
        previous, self._now = self._now, rospy.get_time()
        if self._now < previous:
            self._clock_moved_back(previous, self._now, on_clock_reset)
            self._started = self._sent = self._due_at = self._now
            self._out_of_patience = False

    def _stop_without_input(self, reading, patience):
        """Stop for want of a usable reading, warning why; True once patience has run out
        on two passes in a row.

        A node starved of the CPU for a while wakes to a backlog of /clock
        that moves ROS time on in a burst, perhaps before its scan thread has
        handed on the newest scan, already on its way: the wait for a newer
        reading between the two passes lets it come.
        """
        if patience is not None and self._now - self._started > patience:
            if self._out_of_patience:
                rospy.logwarn('%s: %s; giving up', self.name, reading.problem)
                return True
            self._out_of_patience = True
        self._send(STOP)
        if reading.check is not None or self._now - self._started > self.input_timeout:
            self._warn('%s; stopped' % reading.problem, self._now)
        return False

    def _answer(self, answer, reading):
        """Send answer's command for a usable reading, made safe.

        The keepalive counts from the reading's time when that is later than
        the clock's, on simulated time (control.stamps.arrival_time): a
        simulator sends /clock after the scan, so a scan can come a step
        ahead of this node's clock. Counted from the clock alone, the
        answer looked a step old when the next /clock came, and a repeat of
        it went out before the next scan was read: in lockstep the world
        stepped on that repeat, and the answers after it came a step late.
        """
        self._started = self._now
        self._out_of_patience = False
        self._due_at = self._next_due(self._due_at, self._now)
        command = self._safe(answer(reading.view, reading.taken), reading.view, self._now)
        self._send(command, arrival_time(self._now, reading.taken,
                                         not rospy.rostime.is_wallclock()))

    def _send(self, command, dated=None):
        """Send command; the keepalive counts from `dated` (ROS s), now by default."""
        self.commander.send(command)
        self._sent = self._now if dated is None else dated

    def _due(self, fresh):
        """Whether to answer now: at each new reading, or with a tick, once the tick is due."""
        if self.tick is None:
            return fresh
        return self._now >= self._due_at - TICK_SLACK * self.tick

    def _next_due(self, due, now):
        """When the next tick falls: a steady beat, restarted from now if it fell behind."""
        if self.tick is None:
            return due
        return due + self.tick if now < due + self.tick else now + self.tick

    def _safe(self, answered, view, now):
        """The Command of answered (a Command or an Answer), with no motion into a sector
        ahead, or behind, that the sensor does not show."""
        command, known = answered if isinstance(answered, Answer) else (answered, None)
        problem = self._unseen_way(view, known, command.linear)
        narrow = (self._blind_turn is not None and known is None
                  and self.ahead_min_known is not None
                  and narrow_ahead(view, self.ahead_half_width, self.ahead_min_known))
        near = self._blind_turn is not None and self._blind_turn.wall_near(view)
        safe = held_back(command, problem, self._blind_turn, now, narrow, near)
        if problem is not None:
            self._warn(problem + self._holding(command, safe, now), now)
        return safe

    def _holding(self, command, safe, now):
        """What the loop does for want of a view of its way, as its warning ends."""
        if command.linear < 0.0:
            return '; not driving backward'
        if its_own_turn(command, self._blind_turn):
            return '; not driving forward'
        if safe == STOP:
            return (' after turning %.0f deg to look for it; stopped'
                    % math.degrees(self._blind_turn.turned(now)))
        return '; turning in place to look for the way'

    def _unseen_way(self, view, known, linear):
        """Why the way linear [m/s] drives is not known well enough to drive into; None if
        it is, or if the command does not drive. Backward, only a laser's beams can tell:
        an Answer's word is about the way ahead."""
        if linear > 0.0:
            return self._unseen_ahead(view, known)
        if linear < 0.0 and self.ahead_min_known is not None:
            return unseen_ahead(view, self.ahead_half_width, self.ahead_min_known, backward=True)
        return None

    def _unseen_ahead(self, view, known):
        """Why the way ahead is not known well enough to drive into (known: the Answer's
        word, None for a bare Command); None if it is."""
        if known is None and self.ahead_min_known is not None:
            return unseen_ahead(view, self.ahead_half_width, self.ahead_min_known)
        if known:
            return None
        return '%s within %.0f deg ahead' % (self._ahead_missing,
                                             math.degrees(self.ahead_half_width))

    def warn(self, text):
        """Log a warning, named as the loop's: at once when it is new, and again every
        WARNING_PERIOD while it lasts; for answer() to say why it stops the robot."""
        self._warn(text, self._now)

    def _warn(self, text, now):
        """Log a warning at once when it is new, and again every WARNING_PERIOD while it lasts."""
        last_text, last_time = self._warned
        if text != last_text or now - last_time >= WARNING_PERIOD or now < last_time:
            rospy.logwarn('%s: %s', self.name, text)
            self._warned = (text, now)

    def _clock_moved_back(self, previous, now, on_clock_reset):
        rospy.logwarn('%s: ROS time moved back from %.2f s to %.2f s; dropping what was timed '
                      'on the old clock', self.name, previous, now)
        self.source.forget()
        if on_clock_reset is not None:
            on_clock_reset()


def drive_loop(name, values, source, tick=None, ahead_missing='nothing seen'):
    """A DriveLoop on source (a LatestScan or a LatestImage) and cmd_vel, set up from a driving
    node's parameters (name -> value: those of params.driving's sections, read as
    source.parameters names them); tick and ahead_missing as DriveLoop's."""
    commander = VelocityCommander('cmd_vel', values['max_linear'], values['max_angular'])
    return DriveLoop(name, source, commander, values['rate'], values['keepalive'],
                     tick=tick, ahead_missing=ahead_missing, **_settings(source, values))


def tune_drive_loop(loop, values):
    """Put a driving node's loop and speed limits (rate, keepalive, its source's timeout and
    share of beams, ahead_half_width, blind_turn, max_linear, max_angular) in force; in the
    loop's own thread."""
    loop.tune(values['rate'], values['keepalive'], **_settings(loop.source, values))
    loop.commander.max_linear = values['max_linear']
    loop.commander.max_angular = values['max_angular']


def take_retuned(params, loop):
    """params.take_update() for a driving node: the values changed since the last call,
    with its loop and clamp already put on them (tune_drive_loop); None if none changed.
    In the loop's own thread, at a reading."""
    values = params.take_update()
    if values is not None:
        tune_drive_loop(loop, values)
    return values


def _settings(source, values):
    """The loop's settings that its source's kind names (params.driving.LoopInput)."""
    names = source.parameters
    return dict(input_timeout=values[names.timeout], ahead_half_width=values['ahead_half_width'],
                ahead_min_known=values[names.min_known] if names.min_known else None,
                blind_turn=values.get('blind_turn'))
