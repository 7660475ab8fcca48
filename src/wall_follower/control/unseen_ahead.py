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
A way it finds at the end of a wall, past which the room is out of reach,
shows in a few beams only, on the wall's side; a follower that turned back
to the wall's heading would lose it at once and creep on, a step at a time,
between the two turns. So the way found is kept: while the view is narrow
(fewer than KEPT_VIEW times the share needed), the robot goes straight on
instead of turning away from the wall, and if the way is lost again it is
looked for where it was found, until a command turns toward the wall, or
turns away from it in place, which gives that way up; so does one that turns
away from the wall while the wall reads nearer than KEPT_CLEARANCE, for each
look turns the robot further into its wall, and held straight on it closes
on it.
Backward motion (find_wall's slide, a teleop user's reverse) is held by the
same rule on the sector behind, with no turn: nothing drives backward for
want of a view.
"""
import math

from wall_follower.control.motion import STOP, Command
from wall_follower.control.sensing.observation import second_smallest
from wall_follower.control.sensing.scan import LEFT, RIGHT

BLIND_TURN_LIMIT = math.pi
"""How far [rad] a BlindTurn turns without the way ahead coming into view before it stops:
half a turn toward the followed wall has pointed the sector ahead at that wall, so a laser
that still shows nothing there is blind, not facing open space."""

KEPT_VIEW = 2.0
"""How many times the share of valid beams needed to drive the sector ahead must show before
a way a BlindTurn found is in view well enough to turn away from again."""

KEPT_CLEARANCE = 0.215
"""How near [m] the wall a BlindTurn looks toward may read before a command that turns away from
it gives up the way kept: the course's band begins at 0.2 m, and the turn away has the rest to
bring the robot round in."""

WALL_SECTOR = math.radians(30.0)
"""Where the wall a BlindTurn looks toward is read: within this angle [rad] either side of
straight toward it, the course's own reading of the wall on the right."""


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


def narrow_ahead(view, half_width, min_known):
    """Whether a ScanView shows the way ahead by fewer than KEPT_VIEW times min_known of the
    beams within half_width [rad] of straight ahead (held_back's narrow)."""
    known, beams = view.known_share_in_sector(0.0, half_width)
    return known < KEPT_VIEW * min_known * beams


def held_back(command, problem, blind_turn, now, narrow=False, near=False):
    """What a loop sends for command when the way it drives is as problem says (unseen_ahead's
    answer for that way; None: in view), at ROS time now; narrow: the way is in view, but
    by fewer than KEPT_VIEW times the share needed; near: the wall the BlindTurn looks toward
    reads nearer than its clearance (BlindTurn.wall_near).

    A command that turns in place goes as it is; backward motion into an unseen way goes
    without its backward part. Forward motion into an unseen way
    goes without its forward part: the command's own turn, in place, or, with a BlindTurn,
    that turn while the command turns slower (its_own_turn): a node that only asked to go
    on would stand for good, one that turns knows where it is going (a left turn onto a
    dark wall ahead, which an LDS-01 reads as 0.0, goes on in place). A way in view ends
    the turn under way, and a way it found is kept in view while it is narrow
    (BlindTurn.seen) until the command itself turns in place away from it
    (BlindTurn.turned_in_place), or away from a wall that is near.
    """
    if command.linear < 0.0:
        return command if problem is None else Command(0.0, command.angular)
    if command.linear == 0.0:
        if blind_turn is not None:
            blind_turn.turned_in_place(command)
        return command
    if problem is None:
        return command if blind_turn is None else blind_turn.seen(command, narrow, near)
    if its_own_turn(command, blind_turn):
        return Command(0.0, command.angular)
    return blind_turn.turn(now)


def its_own_turn(command, blind_turn):
    """Whether a command held back for want of a view ahead turns in place at its own rate:
    with no BlindTurn, or one no faster than the command's turn that is not keeping a way
    it found (which is looked for again the way it was found) nor under way.

    A blind turn under way goes on until the way is in view: round a wall's
    end into a room deeper than the laser reaches, the arc round the tip
    asked for a left turn now slower, now faster than the blind turn, and
    each faster one undid it; the robot turned to and fro on the spot.
    """
    return blind_turn is None or (abs(command.angular) >= abs(blind_turn.rate)
                                  and not blind_turn.keeping and not blind_turn.turning)


class BlindTurn(object):
    """An in-place turn at `rate` [rad/s, positive left] while the way ahead is unseen.

    turn(now) gives the command for each reading that shows nothing ahead
    (now: its ROS time in s), seen() ends the turn when one shows the way. A
    turn of more than `limit` [rad] without the way coming into view gives
    STOP: the laser is taken to be blind there. clearance [m]: how near the
    wall on the turn's side may read while a way found is kept (wall_near).
    """

    def __init__(self, rate, limit=BLIND_TURN_LIMIT, clearance=KEPT_CLEARANCE):
        self.rate = rate
        self.limit = limit
        self.clearance = clearance
        self._since = None     # ROS time the turn began
        self._keeping = False  # the way the last turn found is kept in view

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

    def seen(self, command, narrow, near=False):
        """The command to send for a forward command while the way ahead is in view; narrow:
        by fewer than KEPT_VIEW times the share needed; near: the wall on the turn's side
        reads nearer than clearance. The next unseen stretch starts a new turn. While the way
        a turn found is kept (keeping), a command that turns away from the side the turn
        looked to goes straight on instead where the view is narrow, and as it is where it is
        wider.

        A command that turns away from a near wall gives the way up. At the
        end of a wall the view shrinks as the robot goes on, and each look
        for it again turned the robot further into its wall: held straight
        on at 12 degrees to it, the robot came from 0.23 to 0.16 m of it
        while the follower asked to turn away at its full rate (generated
        world 35 of seed 109, LDS-01).
        """
        if self._since is not None:
            self._keeping = True
        self._since = None
        turning_away = command.angular * self.rate < 0.0
        if command.angular * self.rate > 0.0 or (near and turning_away):
            self._keeping = False
        if self._keeping and narrow and turning_away:
            return Command(command.linear, 0.0)
        return command

    def wall_near(self, view):
        """Whether the wall the turn looks toward reads nearer than clearance on a ScanView:
        its second-nearest hit within WALL_SECTOR of that side (one spurious beam does not
        count)."""
        side = LEFT if self.rate > 0.0 else RIGHT
        hits = view.ranges[view.in_sector(side, WALL_SECTOR) & view.valid]
        return second_smallest(hits) < self.clearance

    def turned_in_place(self, command):
        """Note a command that turns in place at its own will: one that turns away from the
        side the turn looks to gives up the way the last turn found.

        Crept up to the end of its wall, the robot faced that wall's tip in
        its lane and turned away from it in place; the kept way then held the
        first forward step, the turn looked for the way toward the wall again
        and faced the tip, and the two turns took turns on the spot for a
        minute (generated world 35 of seed 109, LDS-01).
        """
        if command.angular * self.rate < 0.0:
            self._keeping = False

    @property
    def turning(self):
        """Whether a turn is under way: from the first reading that showed nothing ahead until
        one shows the way."""
        return self._since is not None

    @property
    def keeping(self):
        """Whether the way the last turn found is kept: from the reading that showed it until
        a command in view turns to the side the turn looked to."""
        return self._keeping
