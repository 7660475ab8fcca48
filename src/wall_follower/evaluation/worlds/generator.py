"""Random, valid Stage worlds from a seed: the unseen courses of the grader and benchmark.

A world is a room (a rectangle with chamfered corners, so some walls run
at angles other than 90 degrees), one or two wings joined to it (a wing
may be tilted; where it joins the room the walls make convex and concave
corners), pillars and islands standing in it, and a start pose with a
random heading. Its floorplan is drawn by wall_follower.evaluation.worlds.floorplan
and must pass every check of wall_follower.evaluation.worlds.checks; a
layout that fails is drawn again, from the same random stream, so a seed
still names one world.

The same (seed, index) gives the same world on every machine: every draw
comes from one random.Random of its own (no global random state, no hash
order), and the pixels are decided in integer centimetres.
"""
import math
import os
import random
import shutil
from collections import namedtuple

import numpy as np

from wall_follower.evaluation.worlds import checks as world_checks
from wall_follower.evaluation.worlds.floorplan import (METRES_PER_PIXEL, WALL, Canvas,
                                                       crop_to_free, png_bytes, to_centimetres)

# Layouts drawn before a world is given up as impossible with these settings.
ATTEMPTS = 200

Settings = namedtuple('Settings', 'room min_width start_clearance follow_distance')
Settings.__new__.__defaults__ = ((2.4, 4.0), world_checks.MIN_WIDTH,
                                 world_checks.START_CLEARANCE, world_checks.FOLLOW_DISTANCE)
Settings.__doc__ = """room: (shortest, longest) side of the main room [m]; min_width: the
narrowest corridor allowed [m]; start_clearance: the least distance from the start to any
wall [m]; follow_distance: the middle of the band a follower keeps [m]."""

GeneratedWorld = namedtuple('GeneratedWorld', 'name image size centre start features')
GeneratedWorld.__doc__ = """name: file name stem; image: the floorplan (PIL, mode L); size,
centre: the floorplan's [m]; start: (x, y, yaw rad); features: counts of what it holds
(chamfers, wings, tilted, pillars, islands)."""


class GenerationError(Exception):
    """No valid world within ATTEMPTS layouts: the settings cannot be met."""


def _rectangle(cx, cy, length, width, angle):
    """Corners (counter-clockwise) of a rectangle centred at (cx, cy), long side along angle."""
    c, s = math.cos(angle), math.sin(angle)
    half = ((-1, -1), (1, -1), (1, 1), (-1, 1))
    return [(cx + c * hx * length / 2 - s * hy * width / 2,
             cy + s * hx * length / 2 + c * hy * width / 2) for hx, hy in half]


def _chamfered_room(rng, settings, features):
    """The main room: a rectangle centred on the origin with one or two corners cut at a slant."""
    low, high = settings.room
    width, height = rng.uniform(low, high), rng.uniform(low, high)
    corners = [(-width / 2, -height / 2), (width / 2, -height / 2),
               (width / 2, height / 2), (-width / 2, height / 2)]
    cut = set(rng.sample(range(4), rng.randint(1, 2)))
    outline = []
    for index, (x, y) in enumerate(corners):
        if index not in cut:
            outline.append((x, y))
            continue
        before, after = corners[index - 1], corners[(index + 1) % 4]
        # Two different cut lengths: the slanted wall is not at 45 degrees either.
        a = rng.uniform(0.3, 0.45) * min(width, height)
        b = rng.uniform(0.5, 1.5) * a
        outline.append(_towards((x, y), before, a))
        outline.append(_towards((x, y), after, b))
    features['chamfers'] = len(cut)
    return outline, width, height


def _towards(point, target, distance):
    dx, dy = target[0] - point[0], target[1] - point[1]
    length = math.hypot(dx, dy)
    return point[0] + dx * distance / length, point[1] + dy * distance / length


def _wing(rng, width, height, settings, features):
    """A rectangle joined to one side of the room, reaching out of it, perhaps tilted."""
    side = rng.randrange(4)
    normal = (0.0, -math.pi / 2, math.pi, math.pi / 2)[side] + math.pi / 2
    along = (width, height, width, height)[side]
    across = (height, width, height, width)[side]
    tilt = 0.0 if rng.random() < 0.4 else rng.choice((-1, 1)) * math.radians(rng.uniform(15, 35))
    wing_width = rng.uniform(settings.min_width + 0.3, settings.min_width + 0.9)
    reach = rng.uniform(0.8, 1.6)
    offset = rng.uniform(-0.25, 0.25) * along
    overlap = 0.3
    # The wing's axis starts `overlap` inside the room's side and runs out along its normal.
    direction = normal + tilt
    base_x = math.cos(normal) * (across / 2 - overlap) - math.sin(normal) * offset
    base_y = math.sin(normal) * (across / 2 - overlap) + math.cos(normal) * offset
    length = reach + overlap
    cx = base_x + math.cos(direction) * length / 2
    cy = base_y + math.sin(direction) * length / 2
    features['tilted'] = features.get('tilted', 0) + (tilt != 0.0)
    return _rectangle(cx, cy, length, wing_width, direction)


def _place(rng, space, radius, settings):
    """A point of free space with room for something of `radius` and a corridor round it."""
    needed = radius + settings.min_width + 2 * METRES_PER_PIXEL
    rows, cols = np.nonzero(space.clearance >= needed)
    if not len(rows):
        return None
    pick = rng.randrange(len(rows))
    return tuple(space.xy(rows[pick:pick + 1], cols[pick:pick + 1])[0])


def _layout(rng, settings, canvas_half):
    """One drawn layout: (canvas, free mask, features); not yet checked."""
    features = {}
    room, width, height = _chamfered_room(rng, settings, features)
    wings = [_wing(rng, width, height, settings, features) for _ in range(rng.randint(1, 2))]
    features['wings'] = len(wings)
    half = to_centimetres(canvas_half)
    canvas = Canvas(-half, -half, half, half)
    free = canvas.polygon(room)
    for wing in wings:
        free |= canvas.polygon(wing)
    space = _space(canvas, free)
    features['pillars'] = features['islands'] = 0
    for _ in range(rng.randint(1, 3)):
        if rng.random() < 0.5:
            radius = rng.uniform(0.06, 0.15)
            at = _place(rng, space, radius, settings)
            if at is None:
                continue
            free &= ~canvas.disc(at[0], at[1], radius)
            features['pillars'] += 1
        else:
            length, breadth = rng.uniform(0.3, 0.8), rng.uniform(0.15, 0.45)
            at = _place(rng, space, math.hypot(length, breadth) / 2, settings)
            if at is None:
                continue
            free &= ~canvas.polygon(_rectangle(at[0], at[1], length, breadth,
                                               rng.uniform(0.0, math.pi)))
            features['islands'] += 1
        space = _space(canvas, free)
    return canvas, free, space, features


def _space(canvas, free):
    pixel = METRES_PER_PIXEL
    return world_checks.FreeSpace(free, pixel, canvas.x[0, 0] / 100.0, canvas.y[0, 0] / 100.0)


def _start(rng, space, settings):
    """A start pose (x, y, yaw) at least start_clearance (and a pixel) from every wall."""
    rows, cols = np.nonzero(space.clearance >= settings.start_clearance + METRES_PER_PIXEL)
    if not len(rows):
        return None
    pick = rng.randrange(len(rows))
    x, y = space.xy(rows[pick:pick + 1], cols[pick:pick + 1])[0]
    return round(float(x), 3), round(float(y), 3), rng.uniform(-math.pi, math.pi)


def world_name(seed, index):
    return 'gen_s%d_%03d' % (seed, index)


def generate(seed, index, settings=Settings(), attempts=ATTEMPTS):
    """World number index of seed: a GeneratedWorld that passes every check.

    Raises GenerationError when none of `attempts` layouts passes.
    """
    rng = random.Random(seed * 1000003 + index)
    canvas_half = settings.room[1] / 2.0 + 2.0 + 1.6 + WALL
    for _ in range(attempts):
        canvas, free, space, features = _layout(rng, settings, canvas_half)
        if not (features['pillars'] or features['islands']):
            continue
        start = _start(rng, space, settings)
        if start is None:
            continue
        if world_checks.world_problems(space, start, settings.min_width,
                                       settings.start_clearance, settings.follow_distance):
            continue
        image, size, centre = crop_to_free(canvas, free)
        return GeneratedWorld(world_name(seed, index), image, size, centre, start, features)
    raise GenerationError('seed %d, world %d: no layout passed the checks in %d attempts'
                          % (seed, index, attempts))


def free_space_of(world):
    """The world_checks.FreeSpace of a generated world's floorplan image."""
    free = np.asarray(world.image) > 127
    rows, cols = free.shape
    x0 = world.centre[0] - world.size[0] / 2.0 + METRES_PER_PIXEL / 2.0
    y0 = world.centre[1] + world.size[1] / 2.0 - METRES_PER_PIXEL / 2.0
    return world_checks.FreeSpace(free, METRES_PER_PIXEL, x0, y0)


_WORLD_FILE = """\
# {name}.world -- generated by wall_follower.evaluation.worlds.generator
# (seed {seed}, world {index}): {summary}.
# {name}.png: {columns} x {rows} px at {pixel} m/px, black outside the free
# space and to the image edges, so Stage scales it to size [{sx:.3f} {sy:.3f}]
# centred on the floorplan pose. Start: ({x:.3f}, {y:.3f}), yaw {yaw_deg:.1f} deg.

include "burger.inc"

resolution {pixel}
interval_sim 100
speedup 1
paused 0
quit_time 0

window
(
  size [ 560 500 ]
  scale 100
  center [ {cx:.3f} {cy:.3f} ]
  rotate [ 0 0 ]
  show_data 1
)

define floorplan model
(
  color "gray30"
  boundary 0
  gui_nose 0
  gui_grid 0
  gui_move 0
  gui_outline 0
  gripper_return 0
  fiducial_return 0
  ranger_return 1
  obstacle_return 1
)

floorplan
(
  name "{name}"
  bitmap "{name}.png"
  size [ {sx:.3f} {sy:.3f} 0.500 ]
  pose [ {cx:.3f} {cy:.3f} 0.000 0.000 ]
)

turtlebot3_burger
(
  name "turtlebot3"
  pose [ {x:.3f} {y:.3f} 0.000 {yaw_deg:.3f} ]
)
"""


def write_world(world, directory, robot_include, seed, index):
    """Write world's NAME.png and NAME.world into directory, beside a copy of robot_include.

    robot_include: the burger.inc the world file includes (the package's
    worlds/burger.inc). Returns the .world path.
    """
    if not os.path.isdir(directory):
        os.makedirs(directory)
    shutil.copyfile(robot_include, os.path.join(directory, os.path.basename(robot_include)))
    with open(os.path.join(directory, world.name + '.png'), 'wb') as out:
        out.write(png_bytes(world.image))
    summary = ', '.join('%d %s' % (count, what) for what, count in sorted(world.features.items()))
    text = _WORLD_FILE.format(
        name=world.name, seed=seed, index=index, summary=summary, columns=world.image.width,
        rows=world.image.height, pixel=METRES_PER_PIXEL, sx=world.size[0], sy=world.size[1],
        cx=world.centre[0], cy=world.centre[1], x=world.start[0], y=world.start[1],
        yaw_deg=math.degrees(world.start[2]))
    path = os.path.join(directory, world.name + '.world')
    with open(path, 'w') as out:
        out.write(text)
    return path
