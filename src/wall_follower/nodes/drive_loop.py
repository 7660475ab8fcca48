"""The loop every node that drives from the laser runs, and the stops it makes.

One answer per scan, as soon as the scan arrives: in lockstep simulation a
command that merely repeats the last one would let the world step on a
stale decision. Between scans the last command is sent again after
`keepalive`, so that the robot's cmd_vel watchdog (stageros: 0.2 s) does
not stop it mid-turn. The robot is stopped, with a throttled warning that
says why, whenever the newest scan is older than `scan_timeout` or
unusable (check_scan), and it goes on by itself once usable scans return.
No command drives forward while fewer than `ahead_min_known` of the beams
within `ahead_half_width` of straight ahead are valid readings (a hit or a
proven no-return): a laser that sees nothing there, or a beam or two of
the sector, may be blind, not looking at free space. A clock that jumps
back (a simulator restarted, a bag looped) drops the scan held and lets
the node reset what it timed on the old clock.

A node whose commands change between scans (keyboard teleop) can ask for a
steady beat instead: `tick` answers on a fixed ROS-time schedule with the
newest usable scan, however often the laser sends one (an LDS-01 sends 5).
"""
import math

import rospy

from wall_follower.control.motion import STOP, Command
from wall_follower.params.driving import AHEAD_MIN_KNOWN

FINISHED_NO_SCAN = 'no scan'
WARNING_PERIOD = 5.0   # ROS s between repeats of one warning
TICK_SLACK = 0.01      # share of a tick by which an answer may come early (clock rounding)


class DriveLoop(object):
    """Answers scans with commands through a VelocityCommander.

    scan: a LatestScan; commander: a VelocityCommander; name: the prefix
    of every log line. rate: how often (Hz) the loop looks at the clock
    while it waits for scans. keepalive, scan_timeout: ROS seconds.
    ahead_half_width: rad either side of straight ahead; ahead_min_known: the
    share of its beams that must be valid to drive forward. tick: None to
    answer each new scan once; else answer every tick ROS seconds, on a
    steady schedule, with the newest usable scan. ahead_known(view,
    half_width): whether the view shows what lies ahead, within half_width
    rad of straight ahead; None for a laser's (the share of valid beams
    above). A node that drives from another sensor (the line follower's
    camera) passes what its own sensor knows, with its own kind of view,
    and names what it lacks in ahead_missing, for the warning.
    """

    def __init__(self, name, scan, commander, rate, keepalive, scan_timeout,
                 ahead_half_width=math.radians(30.0), ahead_min_known=AHEAD_MIN_KNOWN, tick=None,
                 ahead_known=None, ahead_missing='nothing seen'):
        self.name = name
        self.scan = scan
        self.commander = commander
        self.tune(rate, keepalive, scan_timeout, ahead_half_width, ahead_min_known)
        self.tick = tick
        self._ahead_known = ahead_known
        self._ahead_missing = ahead_missing
        self._warned = (None, None)   # (text, ROS time) of the last warning
        # ROS times, set by run(): of this pass, of the last answer (or the start), of
        # the last command sent, and of the next tick.
        self._now = self._started = self._sent = self._due_at = None

    def tune(self, rate, keepalive, scan_timeout, ahead_half_width, ahead_min_known):
        """Take new settings (as in the constructor); call it between two scans, from answer()."""
        self.period = 1.0 / rate
        self.keepalive = keepalive
        self.scan_timeout = scan_timeout
        self.ahead_half_width = ahead_half_width
        self.ahead_min_known = ahead_min_known

    def run(self, answer, finished=lambda: None, patience=None, on_clock_reset=None):
        """Drive until shutdown or finished() returns something other than None.

        answer(view, taken) -> Command for each new usable scan (taken: its
        stamp in s). finished: checked before each pass and right after
        each answer; what it returns ends the loop and is returned.
        patience: without a usable scan for this long [ROS s] the loop ends
        with FINISHED_NO_SCAN; None waits for ever, stopped.
        on_clock_reset(): called when ROS time has moved backwards.
        Returns None on shutdown. The robot is stopped on every way out.
        """
        seen = None
        self._now = self._started = self._sent = self._due_at = rospy.get_time()
        try:
            while not rospy.is_shutdown():
                outcome = finished()
                if outcome is not None:
                    return outcome
                self._read_clock(on_clock_reset)
                reading = self.scan.latest(self.scan_timeout)
                if reading.view is None:
                    if self._stop_without_scan(reading, patience):
                        return FINISHED_NO_SCAN
                elif self._due(reading.check is not seen):
                    self._answer(answer, reading)
                    outcome = finished()
                    if outcome is not None:
                        return outcome
                elif self._now - self._sent >= self.keepalive:
                    self._send(self.commander.last)
                seen = reading.check
                self.scan.wait_for_newer(seen, self.period)
            return None
        finally:
            self.commander.stop()

    def _read_clock(self, on_clock_reset):
        """Take the time of this pass; on a clock that moved back, start timing afresh."""
        previous, self._now = self._now, rospy.get_time()
        if self._now < previous:
            self._clock_moved_back(previous, self._now, on_clock_reset)
            self._started = self._sent = self._due_at = self._now

    def _stop_without_scan(self, reading, patience):
        """Stop for want of a usable scan, warning why; True once patience has run out."""
        if patience is not None and self._now - self._started > patience:
            rospy.logwarn('%s: %s; giving up', self.name, reading.problem)
            return True
        self._send(STOP)
        if reading.check is not None or self._now - self._started > self.scan_timeout:
            self._warn('%s; stopped' % reading.problem, self._now)
        return False

    def _answer(self, answer, reading):
        """Send answer's command for a usable scan, made safe."""
        self._started = self._now
        self._due_at = self._next_due(self._due_at, self._now)
        self._send(self._safe(answer(reading.view, reading.taken), reading.view, self._now))

    def _send(self, command):
        self.commander.send(command)
        self._sent = self._now

    def _due(self, fresh):
        """Whether to answer now: at each new scan, or with a tick, once the tick is due."""
        if self.tick is None:
            return fresh
        return self._now >= self._due_at - TICK_SLACK * self.tick

    def _next_due(self, due, now):
        """When the next tick falls: a steady beat, restarted from now if it fell behind."""
        if self.tick is None:
            return due
        return due + self.tick if now < due + self.tick else now + self.tick

    def _safe(self, command, view, now):
        """command, with no forward motion into a sector ahead that the sensor cannot see."""
        if command.linear <= 0.0:
            return command
        problem = self._unseen_ahead(view)
        if problem is None:
            return command
        self._warn(problem + '; not driving forward', now)
        return Command(0.0, command.angular)

    def _unseen_ahead(self, view):
        """Why the view does not show enough of what lies ahead to drive into; None if it does."""
        half_width = math.degrees(self.ahead_half_width)
        if self._ahead_known is not None:
            if self._ahead_known(view, self.ahead_half_width):
                return None
            return '%s within %.0f deg ahead' % (self._ahead_missing, half_width)
        known, beams = view.known_share_in_sector(0.0, self.ahead_half_width)
        if known == 0:
            return 'no valid reading within %.0f deg ahead' % half_width
        if known < self.ahead_min_known * beams:
            return ('only %d of the %d beams within %.0f deg ahead read valid (%.0f%% needed)'
                    % (known, beams, half_width, 100.0 * self.ahead_min_known))
        return None

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
        self.scan.forget()
        if on_clock_reset is not None:
            on_clock_reset()
