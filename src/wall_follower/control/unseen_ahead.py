"""Motion held back while the laser does not show the way it goes, and the turn that looks
for the way ahead.

A laser's scan shows the way ahead when enough of the beams within a sector
either side of straight ahead read a hit or a proven no-return; a dropout
(0.0, NaN) proves nothing, as the laser may be blind there. An LDS-01 also
writes 0.0 beyond its reach (3.5 m), so a robot that faces a room deeper than
that sees nothing ahead, and a node that only asked to go straight would
stand there for good. A wall follower knows which side its wall is on: a
BlindTurn turns it in place toward that side, where the wall is near, until
the way ahead comes into view, and stops it if half a turn has not shown it.
Backward motion (find_wall's slide, a teleop user's reverse) is held by the
same rule on the sector behind, with no turn: nothing drives backward for
want of a view.
"""
import math

from wall_follower.control.motion import STOP, Command

BLIND_TURN_LIMIT = math.pi
"""How far [rad] a BlindTurn turns without the way ahead coming into view before it stops:
half a turn toward the followed wall has pointed the sector ahead at that wall, so a laser
that still shows nothing there is blind, not facing open space."""


def unseen_ahead(view, half_width, min_known, backward=False):
    """Why a ScanView does not show the way ahead (behind, when backward) well enough to
    drive into; None if it does.

    half_width: rad either side of straight ahead (behind); min_known: the share of the
    beams there that must read a hit or a proven no-return.
    """
    known, beams = view.known_share_in_sector(math.pi if backward else 0.0, half_width)
    where = '%.0f deg %s' % (math.degrees(half_width), 'behind' if backward else 'ahead')
    if known == 0:
        return 'no valid reading within %s' % where
    if known < min_known * beams:
        return ('only %d of the %d beams within %s read valid (%.0f%% needed)'
                % (known, beams, where, 100.0 * min_known))
    return None


def held_back(command, problem, blind_turn, now):
    """What a loop sends for command when the way it drives is as problem says (unseen_ahead's
    answer for that way; None: in view), at ROS time now.

    A command that turns in place goes as it is; backward motion into an unseen way goes
    without its backward part. Forward motion into an unseen way
    goes without its forward part: the command's own turn, in place, or, with a BlindTurn,
    that turn while the command turns slower (its_own_turn): a node that only asked to go
    on would stand for good, one that turns knows where it is going (a left turn onto a
    dark wall ahead, which an LDS-01 reads as 0.0, goes on in place). A way in view ends
    the turn under way.
    """
    if command.linear < 0.0:
        return command if problem is None else Command(0.0, command.angular)
    if command.linear == 0.0:
        return command
    if problem is None:
        if blind_turn is not None:
            blind_turn.seen()
        return command
    if its_own_turn(command, blind_turn):
        return Command(0.0, command.angular)
    return blind_turn.turn(now)


def its_own_turn(command, blind_turn):
    """Whether a command held back for want of a view ahead turns in place at its own rate:
    with no BlindTurn, or one no faster than the command's turn."""
    return blind_turn is None or abs(command.angular) >= abs(blind_turn.rate)


class BlindTurn(object):
    """An in-place turn at `rate` [rad/s, positive left] while the way ahead is unseen.

    turn(now) gives the command for each reading that shows nothing ahead
    (now: its ROS time in s), seen() ends the turn when one shows the way. A
    turn of more than `limit` [rad] without the way coming into view gives
    STOP: the laser is taken to be blind there.
    """

    def __init__(self, rate, limit=BLIND_TURN_LIMIT):
        self.rate = rate
        self.limit = limit
        self._since = None   # ROS time the turn began

    def turn(self, now):
        """The command at ROS time now while the way ahead is unseen: the turn, or STOP once
        it has turned `limit` (a clock that moved back starts the turn afresh)."""
        if self._since is None or now < self._since:
            self._since = now
        return STOP if self.turned(now) >= self.limit else Command(0.0, self.rate)

    def turned(self, now):
        """How far [rad] the turn has gone by ROS time now: 0 when none is under way, and no
        farther than `limit`, where it stops."""
        if self._since is None:
            return 0.0
        return min(self.limit, abs(self.rate) * (now - self._since))

    def seen(self):
        """The way ahead is in view: the next unseen stretch starts a new turn."""
        self._since = None
