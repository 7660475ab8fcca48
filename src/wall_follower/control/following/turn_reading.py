"""What the wall on the right reads along a planned left turn, flown through an ideal corner.

The course reads the wall on the right as the nearest range within a sector
around the right. Through an inner corner that reading is the nearer of two
walls seen through the sector's edges: the wall being left, which swings
behind the right, through the back edge, and the wall ahead, which comes
round from ahead, through the front edge. Both read farther than they
stand, and where the turn hands over from its tight arc to its wide end
the two are about equally far: that is where the reading peaks. How high
depends on where the turn began (a robot that starts it at the band's far
edge, with no room to ride nearer first, is carried off the wall it leaves
by the tight arc) and on the plan, so a plan is checked against it before
it is flown (peak_reading).

The corner is ideal: two straight walls, met by a robot flying the plan
exactly as LeftTurn.radius_within sets it, with no noise and no delay.
Sampled every STEP, the peak reads at most a couple of millimetres short.
"""
import math

from wall_follower.rotation import wrap_angle

# Steps in which the turn is flown, and read [rad].
STEP = math.radians(2.0)


def peak_reading(turn, right, ahead, landing, laser_x, sector):
    """The farthest that the wall on the right reads while turn (a LeftTurn) is flown [m].

    right and ahead: the wall on the right and the wall ahead where the turn
    begins, as Lines seen from the rotation centre; the turn is onto the
    wall ahead, through its angle. landing: the centre's distance from the
    wall ahead where the turn is to end [m]; laser_x: the laser's position
    ahead of the centre [m]; sector: half the width of the sector around the
    right that the reading is taken from [rad].
    """
    walls = (_wall(right), _wall(ahead))
    x = y = heading = 0.0
    peak = _reading(walls, x, y, heading, laser_x, sector)
    remaining = ahead.angle
    while remaining > 0.0:
        step = min(STEP, remaining)
        gap = _distance(walls[1], x, y) - landing
        radius = turn.radius_within(gap, remaining)
        x += radius * (math.sin(heading + step) - math.sin(heading))
        y += radius * (math.cos(heading) - math.cos(heading + step))
        heading += step
        remaining -= step
        peak = max(peak, _reading(walls, x, y, heading, laser_x, sector))
    return peak


def _wall(line):
    """line (a Line on the right of the origin, its angle turned towards ahead) as a point on
    it and its unit normal towards the origin, in the frame of the turn's start: the rotation
    centre at the origin, heading along x."""
    sine, cosine = math.sin(line.angle), math.cos(line.angle)
    return (line.distance * sine, -line.distance * cosine), (-sine, cosine)


def _distance(wall, x, y):
    """How far (x, y) lies from wall, on the side its normal points to (< 0 beyond it)."""
    (px, py), (nx, ny) = wall
    return (x - px) * nx + (y - py) * ny


def _reading(walls, x, y, heading, laser_x, sector):
    """The nearest range within sector of the right, from the laser of a robot at (x, y, heading).

    A wall a distance d off, whose normal lies an angle delta from the
    right, reads d / cos(delta - sector) on the sector's nearer edge, and d
    where the normal lies within the sector.
    """
    lx, ly = x + laser_x * math.cos(heading), y + laser_x * math.sin(heading)
    right = heading - math.pi / 2
    nearest = float('inf')
    for wall in walls:
        distance = _distance(wall, lx, ly)
        (nx, ny) = wall[1]
        off = abs(float(wrap_angle(math.atan2(-ny, -nx) - right))) - sector
        if off < math.pi / 2:
            nearest = min(nearest, distance / math.cos(max(0.0, off)))
    return nearest
