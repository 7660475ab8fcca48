"""The find-wall behaviour: turn to the nearest wall, approach it, put it on the right.

A plain state machine fed one ScanView at a time, free of ROS so that it can
be driven by unit tests, by the simulator in a closed loop, or by the
find_wall service node alike:

    IDLE -> start() -> CHOOSE_WALL -> ROTATE_TO_WALL -> APPROACH -> ALIGN -> DONE
                        |  |    |                                    +-> SLIDE -> ALIGN -> DONE
                        |  |    +-> ALIGN (already beside the wall)
                        |  |    +-> DONE (already in place: parallel at wall_distance)
                        |  +-> FAILED (no wall in range, or the wall kept getting lost)
                        +-> NEARER -> CHOOSE_WALL (no wall seen straight across from here)
    (a chosen wall lost from sight for a while: back to CHOOSE_WALL)

Every state re-measures the chosen wall on every scan (closed loop): the
turns end when the wall's normal is where it should be, not after a time.
The robot is steered by the wall's fitted line, not by single rays, which
makes both distance and heading far steadier than the shortest ray would.
Once aligned, it checks what a user's node will read: the wall on every
beam around straight right. Beside a wall's end it is not so, and the robot
slides along the wall, away from the end, until it is (SLIDE). It checks
too that the lap can begin there: in a corner sharper than a right angle,
or with a wall across the way just ahead, the follower's first move is a
left turn in place, which would bring the reference point nearer the next
wall than the band allows, so the robot slides back until it has the room.
"""
import math

import numpy as np

from wall_follower.control.motion import STOP, Command
from wall_follower.control.sensing.scan import RIGHT
from wall_follower.control.sensing.walls import (
    closest_match, extract_walls, nearest_seen_point, path_is_clear, path_to_is_clear, refine)
from wall_follower.control.unseen_ahead import unseen_ahead
from wall_follower.params import checked
from wall_follower.params.course.wall_finder import FINDER
from wall_follower.rotation import wrap_angle

CHOOSE_WALL = 'CHOOSE_WALL'
ROTATE_TO_WALL = 'ROTATE_TO_WALL'
APPROACH = 'APPROACH'
ALIGN = 'ALIGN'
SLIDE = 'SLIDE'
NEARER = 'NEARER'
DONE = 'DONE'
FAILED = 'FAILED'
IDLE = 'IDLE'

# A beam reads the chosen wall when its hit lies within this of the wall's line [m]: a
# noisy laser, or Stage's grid seen at a slant, spreads a wall's hits over a few centimetres.
WALL_GATE = 0.05
# Beams in a row at one edge of right_sector that may miss the wall without a slide: a
# spurious reading or a dropout there.
STRAY_BEAMS = 1


class WallFinder(object):
    """Find-wall state machine: call start(), then update(scan) until done.

    Its parameters (keyword arguments; their defaults, ranges and meanings
    are the FINDER table) are the defaults overridden by those given.
    Turns and the approach aim for half of distance_tolerance and
    heading_tolerance, so that what the robot still moves after a stop
    command keeps it within them; the approach and the last straighten-up
    accept the whole band once they have crossed the target, as Stage's grid
    moves the measured distance in steps of up to a cell and the fitted
    wall's angle in steps of a degree or more.
    """

    def __init__(self, **params):
        self.reconfigure(**params)
        self._reset(IDLE)

    def reconfigure(self, **params):
        """Go on under these parameters (the defaults, overridden) from the next update on.

        A search in progress goes on where it is.
        """
        self.params = checked(FINDER, params)

    @property
    def done(self):
        return self.state in (DONE, FAILED)

    @property
    def success(self):
        return self.state == DONE

    def start(self):
        """Forget any previous run and begin by choosing a wall."""
        self._reset(CHOOSE_WALL)

    def _reset(self, state):
        self.state = state
        self.failure_reason = None
        self.wall = None
        self._last = STOP
        self._remaining = None
        self._crossings = 0
        self._lost = 0
        self._reacquired = 0
        self._settled = 0
        self._heading = None
        self._slid = False

    def update(self, view):
        """Advance on one scan (a ScanView) and return the Command to drive."""
        handler = {
            CHOOSE_WALL: self._choose_wall,
            ROTATE_TO_WALL: self._rotate_to_wall,
            APPROACH: self._approach,
            ALIGN: self._align,
            SLIDE: self._slide,
            NEARER: self._nearer,
        }.get(self.state)
        command = handler(view) if handler is not None else STOP
        self._last = command
        return command

    # States

    def _choose_wall(self, view):
        p = self.params
        seen = extract_walls(view, min_length=p['min_wall_length'])
        walls = self._across(view, seen)
        in_place = [wall for wall in walls if self._in_place(wall)]
        if in_place:
            # Where a search ends: nothing to do, and turning to look for the
            # nearest wall could only leave the robot less well placed.
            self.wall = in_place[0]
            self.state = DONE
            return STOP
        # Ending near a wall's end leaves the robot at a corner, with another
        # wall on its right as soon as it moves: choose such a wall only if
        # there is nothing better.
        walls = [wall for wall in walls if self._ends_inside(wall)] or walls
        if not walls:
            return self._go_nearer(view, seen)
        self.wall = walls[0]
        self._lost = 0
        if (abs(self._heading_error(RIGHT)) <= p['approach_heading']
                and abs(self.wall.distance - p['wall_distance']) <= p['distance_tolerance']):
            # Already beside the wall at the right distance: only straighten up.
            return self._start_align(view)
        self.state = ROTATE_TO_WALL
        return self._rotate_to_wall(view)

    def _across(self, view, walls):
        """The walls whose point straight across from the laser was seen, with nothing on
        the way there from the rotation centre."""
        return [wall for wall in walls if wall.foot_inside()
                and path_is_clear(view, wall, self.params['corridor_half_width'],
                                  origin=self._centre)]

    def _go_nearer(self, view, walls):
        """No wall is seen straight across (every one's nearest point lies round its end or
        behind something, as among slanted walls and islands): drive towards the nearest
        point seen of the nearest wall with a clear way there, until one is."""
        p = self.params
        targets = [(wall, nearest_seen_point(wall, p['end_margin'])) for wall in walls]
        reachable = [(wall, target) for wall, target in targets
                     if path_to_is_clear(view, target, p['corridor_half_width'], wall=wall,
                                         origin=self._centre)]
        if not reachable:
            return self._fail('no wall in range: no clear, straight run of hits at least '
                              '%.2f m long in the scan' % p['min_wall_length'])
        self.wall = min(reachable, key=lambda pair: math.hypot(*pair[1]))[0]
        self._lost = 0
        self.state = NEARER
        return self._nearer(view, tracked=True)

    def _rotate_to_wall(self, view):
        if not self._track(view):
            return self._on_lost()
        heading_error = self._heading_error(0.0)
        if abs(heading_error) <= self.params['approach_heading']:
            self.state = APPROACH
            return self._approach(view, tracked=True)
        return Command(0.0, self._turn(heading_error))

    def _approach(self, view, tracked=False):
        p = self.params
        if not tracked and not self._track(view):
            return self._on_lost()
        heading_error = self._heading_error(0.0)
        remaining = self.wall.distance - (p['wall_distance'] - p['laser_x'])
        crossed = self._remaining is not None and remaining * self._remaining <= 0.0
        jump = abs(remaining - self._remaining) if crossed else 0.0
        self._remaining = remaining
        self._crossings += crossed
        # Aim for the middle of the tolerance band; but a coarse laser (Stage
        # measures in 2 cm steps) may jump right over the middle, and then
        # having crossed the target inside the band has to do. Seen at a
        # slant, a wall's reading may step by more than the whole band: once
        # the target has been crossed back and forth, a reading on the side of
        # it nearer than the other does.
        if abs(remaining) <= p['distance_tolerance'] / 2.0 or (
                crossed and abs(remaining) <= p['distance_tolerance']) or (
                self._crossings >= 2 and abs(remaining) <= jump / 2.0):
            return self._start_align(view)
        return self._drive(remaining, heading_error)

    def _nearer(self, view, tracked=False):
        """Towards the nearest seen point of the chosen wall until some wall is seen straight
        across with end_margin of it either side, then choose again; at wall_distance from
        that point, choose any wall seen straight across, and with none give up.

        A wall seen straight across just inside its end is no place to stop
        driving: the search would end beside that end, where the grader's
        sector, ahead of the right, reads past it.
        """
        p = self.params
        across = []
        if not tracked:
            across = self._across(view, extract_walls(view, min_length=p['min_wall_length']))
            if any(self._ends_inside(wall) for wall in across):
                return self._choose_again(view)
            if not self._track(view):
                return self._choose_again(view) if across else self._on_lost()
        target = nearest_seen_point(self.wall, p['end_margin'])
        remaining = math.hypot(*target) - p['wall_distance']
        if remaining <= p['distance_tolerance']:
            if across:
                return self._choose_again(view)
            return self._fail('no wall seen straight across even %.2f m from the nearest one'
                              % p['wall_distance'])
        return self._drive(remaining, math.atan2(target[1], target[0]))

    def _choose_again(self, view):
        self.state = CHOOSE_WALL
        return self._choose_wall(view)

    def _start_align(self, view):
        self.state = ALIGN
        self._heading = None
        return self._align(view, tracked=True)

    def _align(self, view, tracked=False):
        p = self.params
        if not tracked and not self._track(view):
            return self._on_lost()
        heading_error = self._heading_error(RIGHT)
        crossed = self._heading is not None and heading_error * self._heading <= 0.0
        self._heading = heading_error
        within = abs(heading_error) <= p['heading_tolerance']
        if within and crossed:
            # Turns aim for the middle of the tolerance; but where Stage's
            # grid makes the fitted wall jump by a degree or more as the
            # robot turns a fraction of that, the middle is never read, and
            # the robot would turn to and fro across it: having turned
            # across it inside the tolerance has to do, as in the approach.
            return self._aligned(view)
        if within and self._last == STOP:
            self._settled += 1
            if self._settled >= p['settle_updates']:
                return self._aligned(view)
            return STOP
        self._settled = 0
        return Command(0.0, self._turn(heading_error))

    def _aligned(self, view):
        """Done; or, beside a wall's end or short of room ahead the first time aligned, first
        the slide away from there."""
        if self._slid or not self._slide_direction(view):
            self.state = DONE
            return STOP
        self._slid = True
        self.state = SLIDE
        return self._slide(view, tracked=True)

    def _slide(self, view, tracked=False):
        """Along the wall, away from the side of the right where it does not read, until it
        reads all round the right, it does not read on either side, or something lies within
        corridor_half_width of the way, up to twice that ahead of the rotation centre; then
        straighten up once more."""
        if not tracked and not self._track(view):
            return self._on_lost()
        direction = self._slide_direction(view)
        if not direction or not self._way_open(view, direction):
            return self._start_align(view)
        p = self.params
        return Command(direction * p['slide_speed'], self._turn(self._heading_error(RIGHT)))

    def _way_open(self, view, direction):
        """True when the scan shows the way of a slide in direction (+1 forward, -1 back) and
        nothing lies within corridor_half_width of it, up to twice that from the rotation
        centre.

        Shows it as the drive loop judges it, by the same ahead_half_width and
        ahead_min_known: a way it does not show (a laser with no beams behind,
        say) the loop would hold the robot from for good.
        """
        p = self.params
        if unseen_ahead(view, p['ahead_half_width'], p['ahead_min_known'],
                        backward=direction < 0):
            return False
        way = (-p['laser_x'] + direction * 2.0 * p['corridor_half_width'], 0.0)
        return path_to_is_clear(view, way, p['corridor_half_width'], margin=0.0,
                                origin=self._centre)

    def _slide_direction(self, view):
        """+1 (forward) where the chosen wall does not read on the beams behind the right,
        within right_sector, -1 (back) where it does not read ahead of it or where there is
        no room ahead (_cornered), 0 where it reads on both sides or on neither, or where
        there is no room ahead and it does not read behind.

        A beam misses the wall when it reads nothing, or a hit more than
        WALL_GATE off the wall's line: past the wall's end, the wall beyond
        it or nothing at all. Past an end every beam misses, out to the
        sector's edge, so only the misses in a row from each edge count: a
        dropout among beams that read the wall is no end, and over a sector
        a few tens of beams wide an LDS-01 drops a few such at once.
        """
        angles, points, valid = view.beams(RIGHT, self.params['right_sector'])
        with np.errstate(invalid='ignore'):
            reads = valid & (np.abs(self.wall.line.offsets(points)) <= WALL_GATE)
        offsets = wrap_angle(angles - RIGHT)
        order = np.argsort(offsets)
        misses, offsets = ~reads[order], offsets[order]
        behind = _leading(misses[offsets < 0.0]) > STRAY_BEAMS
        ahead = _leading(misses[offsets > 0.0][::-1]) > STRAY_BEAMS or self._cornered(view)
        return float(behind) - float(ahead)

    def _cornered(self, view):
        """True when a hit off the chosen wall lies ahead of the rotation centre, within
        turn_room of it.

        The lap begins from here, and a wall that near ahead is turned onto
        at once, in place: the laser swings round the centre and ends about
        as far from that wall as the centre is. The chosen wall's own hits
        (within WALL_GATE of its line) are no such wall, however near the
        corner they lie.
        """
        hits = view.points(0.0, math.pi / 2.0)
        off_wall = hits[np.abs(self.wall.line.offsets(hits)) > WALL_GATE] - self._centre
        ahead = off_wall[off_wall[:, 0] > 0.0]
        return bool((np.hypot(ahead[:, 0], ahead[:, 1]) < self.params['turn_room']).any())

    # Helpers

    def _track(self, view):
        """Re-measure the chosen wall on this scan; False if it cannot be found.

        Any straight piece close to where the wall was will do (noise can
        break a wall into pieces shorter than min_wall_length); the wall is
        then refitted to all the hits along that piece's line.
        """
        p = self.params
        match = closest_match(extract_walls(view), self.wall, p['track_angle'], p['track_distance'])
        if match is None:
            return False
        self.wall = refine(view, match)
        self._lost = 0
        return True

    def _on_lost(self):
        """Stand still while the wall is out of sight; choose again if it stays away."""
        self._lost += 1
        if self._lost >= self.params['lost_updates']:
            if self._reacquired >= self.params['max_reacquire']:
                return self._fail('lost sight of the chosen wall %d times' % (self._reacquired + 1))
            self._reacquired += 1
            self.state = CHOOSE_WALL
        return STOP

    def _fail(self, reason):
        self.state = FAILED
        self.failure_reason = reason
        return STOP

    def _in_place(self, wall):
        """True when wall is on the right, parallel and at wall_distance, within the tolerances
        (in_place_tolerance on the distance)."""
        p = self.params
        return (abs(float(wrap_angle(wall.angle - RIGHT))) <= p['heading_tolerance']
                and abs(wall.distance - p['wall_distance']) <= p['in_place_tolerance'])

    def _ends_inside(self, wall):
        """True when the laser, once the search ends beside wall, has end_margin of wall seen
        on either side of it.

        That is not where the laser's own foot is now. The robot drives to
        the wall from its rotation centre, which the laser does not share,
        and the quarter turn at the wall leaves the laser laser_x along the
        wall from the centre, in the direction the robot then faces: the
        positive way along the wall, which is to the robot's left as it
        faces the wall. Beside a wall's end, those few centimetres decide
        whether the wall still fills the right of the laser.
        """
        arrival = wall.along_of(self._centre) + self.params['laser_x']
        return wall.seen_around(arrival, self.params['end_margin'])

    @property
    def _centre(self):
        """(x, y) of the rotation centre in the laser frame: where the way to a wall starts.

        The robot turns on the spot to face a wall before it drives there, which
        leaves its centre where it was and carries the laser round it: the
        corridor that must be clear runs from the centre.
        """
        return (-self.params['laser_x'], 0.0)

    def _heading_error(self, target):
        """Angle (rad) by which the wall's normal lies left of where it should be.

        Turning left by that much puts it there, so it is also the signed
        turn still to make.
        """
        return float(wrap_angle(self.wall.angle - target))

    def _drive(self, remaining, heading_error):
        """Forward by remaining (m), slowing as it runs out, while turning heading_error (rad)
        away: driving while still turned away would reach the wall at an angle."""
        p = self.params
        linear = _speed(remaining, p['max_linear'], p['linear_gain'], p['min_linear'])
        linear *= max(0.0, 1.0 - abs(heading_error) / p['approach_heading'])
        return Command(linear, self._turn(heading_error))

    def _turn(self, heading_error):
        """Turn rate that brings heading_error to the middle of the tolerance band."""
        p = self.params
        if abs(heading_error) <= p['heading_tolerance'] / 2.0:
            return 0.0
        return _speed(heading_error, p['max_angular'], p['angular_gain'], p['min_angular'])


def _leading(flags):
    """How many of flags (booleans) are true in a row from the first one."""
    return len(flags) if flags.all() else int(np.argmin(flags))


def _speed(remaining, max_speed, gain, min_speed):
    """Signed speed proportional to what remains, between min_speed and max_speed."""
    speed = min(max_speed, max(min_speed, gain * abs(remaining)))
    return math.copysign(speed, remaining)
