"""What a solution commanded on cmd_vel, as grading judges it: never what it meant to.

Safety judges every command sent: a non-finite one (inf or NaN, which a
real base would take as its limit or as nothing at all) is noted with
when it came, and never lost in a maximum. And a simulator (Stage, and
the built-in one) stops the robot when no command has come for its
watchdog's time (0.2 simulated s): a command that was the last one for
longer than that was cut short; one followed exactly that long later ran
in full. A command is timed when grading hears it, by a clock that may
already show a later step (by more than one on a busy machine): a late
one may count a cut there was not, or hide one there was. A solution whose
moving commands are mostly cut so sends each once instead of continuously,
and the reasons say so.
"""
import math

# A solution "sends each command once" when at least this share of its moving
# commands were cut by the watchdog.
CUT_SHARE = 0.5
# Simulated times come as float seconds: two steps a watchdog apart read a few
# 1e-15 s more than that apart [s].
TIME_ROUNDING = 1e-6


def non_finite_text(value):
    """'inf', '-inf' or 'nan': how a record keeps a non-finite number (JSON has none)."""
    if value != value:
        return 'nan'
    return 'inf' if value > 0 else '-inf'


class CommandLog(object):
    """The commands of a run, at their simulated times (s); watchdog: the simulator's [s]."""

    def __init__(self, watchdog=0.2):
        self.watchdog = watchdog
        self.count = 0
        self.moving = 0
        self.cut = 0
        self.non_finite = None
        self._last = None

    def add(self, time, linear, angular):
        """A cmd_vel (linear.x, angular.z) heard at time."""
        self._close(time)
        self.count += 1
        if self.non_finite is None:
            for field, value in (('linear.x', linear), ('angular.z', angular)):
                if not math.isfinite(value):
                    self.non_finite = {'field': field, 'value': non_finite_text(value),
                                       'time': time}
                    break
        moving = linear != 0.0 or angular != 0.0
        self.moving += int(moving)
        self._last = (time, moving)

    def finish(self, time):
        """The run ended at time: the last command, if moving, may have been cut too."""
        self._close(time)
        self._last = None

    def _close(self, time):
        if (self._last is not None and self._last[1]
                and time - self._last[0] > self.watchdog + TIME_ROUNDING):
            self.cut += 1

    def record(self):
        return {'count': self.count, 'moving': self.moving, 'cut_by_watchdog': self.cut,
                'watchdog': self.watchdog, 'non_finite': self.non_finite}


def watchdog_note(commands):
    """Why the robot stopped, when it was the watchdog; '' when it was not."""
    if not commands or not commands.get('moving'):
        return ''
    moving, cut = commands['moving'], commands.get('cut_by_watchdog', 0)
    if cut < max(1, CUT_SHARE * moving):
        return ''
    watchdog = commands.get('watchdog', 0.2)
    if cut == moving:
        return ("each command was sent once and stopped by the simulator's %g s watchdog: "
                "publish cmd_vel continuously" % watchdog)
    return ("%d of the %d moving commands were sent once and stopped by the simulator's %g s "
            "watchdog: publish cmd_vel continuously" % (cut, moving, watchdog))
