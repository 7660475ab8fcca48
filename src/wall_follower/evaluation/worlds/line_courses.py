"""Random line courses from a seed: the unseen courses of `grade --task line`.

A course is a yellow line on the floor (a course file of
wall_follower.evaluation.scoring.line_track: straights and arcs from a start
pose) and the camera of the robot that follows it. The kind of course cycles
with its index, so any three in a row hold one of each:

- 'loop': a closed loop round a rectangle whose sides are drawn from
  `room`, corners of 0.45-0.75 m radius, and on some sides an S-bend (two
  bends one way, two the other) of 0.45-0.8 m radius and 30-60 degrees;
- 'tight': the same with every bend 0.35-0.40 m (the tightest that the
  limits let a robot take at a mean of 0.15 m/s: 0.49 rad/s x 0.35 m =
  0.17 m/s on a bend) and S-bends of 60-90 degrees on most sides (less
  where a side is too short; none under MIN_S_BEND);
- 'open': a line with a start and an end: a straight, three or four bends
  of 0.35-0.6 m and 45-120 degrees either way, a straight to its end.

The camera sits on a Waffle's mast (DESIGN.md, "Stage's camera": Stage
draws from the robot's centre at the body's height plus the camera's z,
and draws the robot's own body): a resolution of RESOLUTIONS, a
horizontal field of view of 50-75 degrees (the vertical one of square
pixels), 0.12-0.20 m above the body, tilted down so that the top of the
image sees the floor 0.7-1.5 m ahead, and its lowest row the floor just
beyond the body's front (never the body itself).

Every course passes course_problems (closed exactly, no part of the line
within CLEARANCE of another part more than SEPARATION along it, a closed
line's best mean speed within the limits at least LEAST_SPEED_BOUND); a
draw that fails is drawn again from the same random stream, so that
(seed, index) names one course on every machine (a random.Random of its
own, no global state). line_world draws its world.
"""
import math
import os
import random
import shutil
from collections import namedtuple

import numpy as np
import yaml
from scipy.spatial import cKDTree

from wall_follower.control.motion import MAX_ANGULAR, MAX_LINEAR
from wall_follower.evaluation.scoring.line import speed_bound
from wall_follower.evaluation.scoring.line_track import CourseError, centreline_of
from wall_follower.evaluation.worlds import line_world
from wall_follower.evaluation.worlds.generator import GenerationError

KINDS = ('loop', 'tight', 'open')
# (corner radius, S-bend radius, S-bend angle [deg], share of sides with an S-bend).
LOOP_BENDS = {'loop': ((0.45, 0.75), (0.45, 0.8), (30.0, 60.0), 0.5),
              'tight': ((0.35, 0.40), (0.35, 0.40), (60.0, 90.0), 0.75)}
OPEN_BENDS = ((0.35, 0.6), (45.0, 120.0))
LINE_WIDTH = 0.045
# The robot starts this far along the line [m], on its first straight.
START_ALONG = 0.3
# A straight before a bend is at least this long [m]; the first one leaves room to start.
MIN_STRAIGHT = 0.15
FIRST_STRAIGHT = START_ALONG + 0.2
# An S-bend narrower than this [deg] is left out (the side is too short for more).
MIN_S_BEND = 30.0
CLEARANCE = 0.4
SEPARATION = 1.0
SAMPLE = 0.02
LEAST_SPEED_BOUND = 0.17
RESOLUTIONS = ((320, 240), (424, 240), (480, 360), (640, 480))
HFOV = (50.0, 75.0)
MAST = (0.12, 0.20)
FAR = (0.7, 1.5)
# The Waffle's body (worlds/waffle.inc): its height [m], which Stage adds to the camera's
# z, and how far its front stands ahead of the robot's centre, where Stage draws from [m].
BODY_HEIGHT = 0.141
BODY_FRONT = 0.0765
# The image's lowest row sees the floor at least this far beyond the body's front [m].
BODY_CLEARANCE = 0.01
ATTEMPTS = 200
DEFAULT_ROOM = (1.6, 3.0)

LineCourse = namedtuple('LineCourse', 'name kind course camera')
LineCourse.__doc__ = """name: file name stem; kind: one of KINDS; course: the course file's
keys (start, closed, width, path, robot); camera: a line_world.Camera."""


class LineGenerationError(GenerationError):
    """No valid course within ATTEMPTS draws: the settings cannot be met."""


def course_name(seed, index):
    return 'line_s%d_%03d' % (seed, index)


def kind_of(index):
    return KINDS[index % len(KINDS)]


def _s_bend(rng, radius, angle):
    """An S-bend: its four arcs (net turn 0, net sideways 0) and its length along the side."""
    side = rng.choice((1.0, -1.0))
    arcs = [['arc', radius, side * angle], ['arc', radius, -side * angle],
            ['arc', radius, -side * angle], ['arc', radius, side * angle]]
    return arcs, 4.0 * radius * math.sin(math.radians(angle))


def _side(rng, extent, bends, first):
    """The pieces of one side of a loop, `extent` [m] of straight line between its corners."""
    _, (r_low, r_high), (a_low, a_high), share = bends
    lead = FIRST_STRAIGHT if first else MIN_STRAIGHT
    if rng.random() < share:
        radius = round(rng.uniform(r_low, r_high), 3)
        # As sharp as drawn, or as the side leaves room for.
        fits = (extent - lead - MIN_STRAIGHT) / (4.0 * radius)
        widest = math.degrees(math.asin(fits)) if fits < 1.0 else 90.0
        angle = math.floor(min(rng.uniform(a_low, a_high), widest) * 10.0) / 10.0
        if angle >= MIN_S_BEND:
            arcs, length = _s_bend(rng, radius, angle)
            before = lead + rng.uniform(0.0, extent - length - lead - MIN_STRAIGHT)
            return [['straight', before]] + arcs + [['straight', extent - length - before]]
    return [['straight', extent]]


def _loop(rng, room, kind):
    """A closed loop's course keys: its sides are exact, so it closes to rounding."""
    bends = LOOP_BENDS[kind]
    width, height = (round(rng.uniform(*room), 3) for _ in range(2))
    radii = [round(rng.uniform(*bends[0]), 3) for _ in range(4)]
    # Straight extents of the bottom, right, top and left sides; corner k follows side k.
    extents = [width - radii[3] - radii[0], height - radii[0] - radii[1],
               width - radii[1] - radii[2], height - radii[2] - radii[3]]
    path = []
    for k, extent in enumerate(extents):
        if extent < FIRST_STRAIGHT + MIN_STRAIGHT:
            return None
        path += _side(rng, extent, bends, first=(k == 0))
        path.append(['arc', radii[k], 90.0])
    start = [-width / 2.0 + radii[3], -height / 2.0, 0.0]
    course = {'start': start, 'closed': True, 'width': LINE_WIDTH, 'path': path,
              'robot': [round(start[0] + START_ALONG, 6), start[1], 0.0]}
    return _mirrored(course) if rng.random() < 0.5 else course


def _mirrored(course):
    """The course mirrored in the x axis: a loop driven clockwise, its corners to the right."""
    def flip(pose):
        return [pose[0], -pose[1], 0.0 - pose[2]]
    path = [[piece[0], piece[1], -piece[2]] if piece[0] == 'arc' else piece
            for piece in course['path']]
    return dict(course, start=flip(course['start']), robot=flip(course['robot']), path=path)


def _open(rng, room):
    """An open line's course keys: a straight, bends either way, a straight to its end."""
    (r_low, r_high), (a_low, a_high) = OPEN_BENDS
    heading = round(rng.uniform(0.0, 360.0), 1)
    path = [['straight', round(rng.uniform(FIRST_STRAIGHT, FIRST_STRAIGHT + 0.3), 3)]]
    side = rng.choice((1.0, -1.0))
    for _ in range(rng.randint(3, 4)):
        # Mostly alternating, now and then the same way again.
        side = side if rng.random() < 0.25 else -side
        path.append(['arc', round(rng.uniform(r_low, r_high), 3),
                     side * round(rng.uniform(a_low, a_high), 1)])
        path.append(['straight', round(rng.uniform(MIN_STRAIGHT, 0.2 * room[0]), 3)])
    path[-1][1] = round(rng.uniform(0.4, 0.6), 3)
    rad = math.radians(heading)
    return {'start': [0.0, 0.0, heading], 'closed': False, 'width': LINE_WIDTH, 'path': path,
            'robot': [round(START_ALONG * math.cos(rad), 6), round(START_ALONG * math.sin(rad), 6),
                      heading]}


def steepest(mast):
    """The steepest a camera on a mast [m] may look down [deg] and still see the floor
    clear of the robot's own body (Stage draws the body; DESIGN.md, "Stage's camera")."""
    return math.degrees(math.atan(mast / (BODY_FRONT + BODY_CLEARANCE)))


def _camera(rng):
    """A camera on the mast whose image sees the floor from clear of the body to FAR at
    its top; None when the draw cannot (too tall a field of view for the mast)."""
    width, height = rng.choice(RESOLUTIONS)
    hfov = round(rng.uniform(*HFOV), 1)
    vfov = round(math.degrees(2.0 * math.atan(math.tan(math.radians(hfov) / 2.0)
                                              * height / width)), 1)
    mast = round(rng.uniform(*MAST), 3)
    far = rng.uniform(*FAR)
    tilt = round(vfov / 2.0 + math.degrees(math.atan((BODY_HEIGHT + mast) / far)), 1)
    if tilt + vfov / 2.0 > steepest(mast):
        return None
    return line_world.Camera((width, height), (hfov, vfov), mast, tilt)


def course_problems(course):
    """Why a course's line is unfit to follow or grade, in words; [] when it is fit."""
    try:
        centreline = centreline_of(course)
    except CourseError as err:
        return [str(err)]
    problems = []
    along = np.arange(0.0, centreline.length, SAMPLE)
    points = np.column_stack([np.interp(along, centreline.along, axis)
                              for axis in centreline.points.T])
    for i, j in cKDTree(points).query_pairs(CLEARANCE):
        apart = abs(along[j] - along[i])
        if centreline.closed:
            apart = min(apart, centreline.length - apart)
        if apart > SEPARATION:
            problems.append('the line passes within %.2f m of itself at (%.2f, %.2f)'
                            % (CLEARANCE, points[i][0], points[i][1]))
            break
    if centreline.closed:
        bound = speed_bound(centreline, MAX_LINEAR, MAX_ANGULAR)
        if bound < LEAST_SPEED_BOUND:
            problems.append('its best mean speed within the limits is %.3f m/s (%.2f at least)'
                            % (bound, LEAST_SPEED_BOUND))
    return problems


def generate_line(seed, index, room=DEFAULT_ROOM, attempts=ATTEMPTS):
    """Course number index of seed: a LineCourse that passes course_problems.

    room: (shortest, longest) side of a loop's rectangle [m]; an open
    line's straights grow with the shortest. Raises LineGenerationError
    when none of `attempts` draws passes.
    """
    rng = random.Random(seed * 1000003 + index)
    kind = kind_of(index)
    for _ in range(attempts):
        course = _open(rng, room) if kind == 'open' else _loop(rng, room, kind)
        camera = _camera(rng)
        if course is None or camera is None or course_problems(course):
            continue
        return LineCourse(course_name(seed, index), kind, course, camera)
    raise LineGenerationError('seed %d, line course %d (%s): no draw passed the checks in %d '
                              'attempts' % (seed, index, kind, attempts))


_HEADER = """# {name}.world -- generated by wall_follower.evaluation.worlds.line_courses
# from {name}.course.yaml (seed {seed}, course {index}: {course_kind}).
#
# A yellow line {width_cm:g} cm wide, {kind}, {length:.2f} m long, painted on the floor of a
# room with free space x in [{x0:g}, {x1:g}], y in [{y0:g}, {y1:g}] m. A TurtleBot3 Waffle
# starts on the line at ({rx:g}, {ry:g}), yaw {ryaw:g} deg, with a camera on a mast:
# {camera}.
"""


def describe_camera(camera):
    """A camera in words: resolution, field of view, height and tilt."""
    return '%dx%d camera, %g x %g deg, %.3f m above the body, tilted %g deg down' % (
        camera.resolution + camera.fov + (camera.height, camera.tilt))


def write_line_world(line_course, directory, worlds, seed, index):
    """Write the course's NAME.world, NAME_line.png and NAME.course.yaml into directory,
    beside copies of the robot models it includes (from worlds, the package's worlds/).
    Returns the .world path."""
    if not os.path.isdir(directory):
        os.makedirs(directory)
    for include in line_world.INCLUDES:
        shutil.copyfile(os.path.join(worlds, include), os.path.join(directory, include))
    name = line_course.name
    notes = {'seed': seed, 'index': index, 'course_kind': line_course.kind,
             'camera': describe_camera(line_course.camera)}
    files = line_world.world_files(name, line_course.course, _HEADER, line_course.camera,
                                   path=name, notes=notes)
    for file_name, (data, _) in files.items():
        with open(os.path.join(directory, file_name), 'wb') as out:
            out.write(data)
    with open(os.path.join(directory, name + '.course.yaml'), 'w') as out:
        out.write('# %s: generated by wall_follower.evaluation.worlds.line_courses (seed %d, '
                  'course %d: %s); line_track reads it, %s.world is drawn from it.\n'
                  % (name, seed, index, line_course.kind, name))
        yaml.safe_dump(dict(line_course.course, kind=line_course.kind,
                            camera=camera_keys(line_course.camera)),
                       out, default_flow_style=None, sort_keys=False)
    return os.path.join(directory, name + '.world')


def camera_keys(camera):
    """The camera as a course file holds it (plain lists and numbers)."""
    return {'resolution': list(camera.resolution), 'fov': list(camera.fov),
            'height': camera.height, 'tilt': camera.tilt}


def camera_from_keys(keys):
    """The Camera a course file's `camera` holds; None when it holds none."""
    if not isinstance(keys, dict):
        return None
    return line_world.Camera(tuple(keys['resolution']), tuple(keys['fov']), keys['height'],
                             keys['tilt'])
