"""What a solution commanded on cmd_vel, as grading judges it: never what it meant to.

Safety judges every command sent: a non-finite one (inf or NaN, which a
real base would take as its limit or as nothing at all) is noted with
when it came, and never lost in a maximum.

And a simulator (Stage, and the built-in one) stops the robot when no
command has come for its watchdog's time (0.2 simulated s). Whether it did
is read from what the simulator says it applied, never from when grading
heard the commands: grading's own clock, on a busy machine, hears them
steps late or in bursts, and a gap between two commands heard so would
count a cut of a solution that was never cut. Both simulators publish,
every step, odometry stamped with the step's simulated time whose twist
is the velocity in force (stageros' is its model's velocity, which its
watchdog sets to zero; the built-in simulator's is the command its
watchdog zeroes). So a cut is a stop that odometry shows: a step that
applied no velocity right after one that applied some (one moving command
cut short, however long the robot then stands), which the solution did
not command itself. Its own stop is a zero command sent once the step
that moved was stamped, to apply from the next: heard within the watchdog
of that stamp, it tells the two apart even when grading hears it late.
A step that shows motion is never a cut, whenever its commands were
heard. Nor is a robot stalled against a wall: odometry's twist stays at
the command while the robot pushes (ground truth's twist, a difference of
poses, reads zero then, and stageros publishes no stall). What is left
misjudged is a zero command heard more than the watchdog away from its
stop, and one sent at once after a cut, which reads as the solution's own.

A solution whose moving commands are mostly cut so sends each once
instead of continuously, and the reasons say so.
"""
import bisect
import math

# A solution "sends each command once" when at least this share of its moving
# commands were cut by the watchdog.
CUT_SHARE = 0.5


def non_finite_text(value):
    """'inf', '-inf' or 'nan': how a record keeps a non-finite number (JSON has none)."""
    if value != value:
        return 'nan'
    return 'inf' if value > 0 else '-inf'


def _is_moving(linear, angular):
    """Whether a velocity (linear.x, angular.z) moves the robot; a NaN one counts as moving."""
    return linear != 0.0 or angular != 0.0


class CommandLog(object):
    """The commands of a run, at the simulated times grading heard them (s), and the velocity
    the simulator applied in each step; watchdog: the simulator's [s]."""

    def __init__(self, watchdog=0.2):
        self.watchdog = watchdog
        self.count = 0
        self.moving = 0
        self.non_finite = None
        self._zero_heard = []
        # The stamp of the last step that moved, before each stop odometry showed.
        self._stops = []
        self._moved = None

    def add(self, time, linear, angular):
        """A cmd_vel (linear.x, angular.z) heard at time."""
        self.count += 1
        if self.non_finite is None:
            for field, value in (('linear.x', linear), ('angular.z', angular)):
                if not math.isfinite(value):
                    self.non_finite = {'field': field, 'value': non_finite_text(value),
                                       'time': time}
                    break
        if _is_moving(linear, angular):
            self.moving += 1
        else:
            self._zero_heard.append(time)

    def applied(self, stamp, linear, angular):
        """The velocity (linear.x, angular.z) the simulator applied in its step stamped stamp:
        odometry's twist."""
        if _is_moving(linear, angular):
            self._moved = stamp
        elif self._moved is not None:
            self._stops.append(self._moved)
            self._moved = None

    @property
    def cut(self):
        """The stops odometry showed that no zero command heard near them explains."""
        heard = sorted(self._zero_heard)
        return sum(1 for moved in list(self._stops)
                   if not self._heard_near(heard, moved))

    def _heard_near(self, heard, moved):
        """Whether a zero command (heard: their times, sorted) came within the watchdog of
        moved, the stamp of the last step that moved before a stop."""
        first = bisect.bisect_right(heard, moved - self.watchdog)
        return first < len(heard) and heard[first] <= moved + self.watchdog

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
