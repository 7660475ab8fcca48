"""A line world drawn from a course: the line's bitmap, and the Stage world it lies in.

A course (see wall_follower.evaluation.scoring.line_track) defines a yellow
line by its centreline. This draws

- the line at LINE_PIXEL metres per pixel, black where a pixel's centre
  lies within half the line's width of the centreline, cropped to its
  black pixels (Stage scales their bounding box to the model's `size`), and
- the world: a room whose walls stand MARGIN beyond the line, the line as a
  floor marking (a flat yellow model that lasers and collisions ignore,
  obstacle_return 0, ranger_return -1) with the size and pose that put
  every pixel where the course says, and a TurtleBot3 with a camera at the
  course's `robot` pose: the Waffle Pi of worlds/waffle_pi.inc, or a
  Waffle carrying the Camera given.

The shipped line worlds (tools/make_line_worlds.py) and the grader's
generated line courses (line_courses.py) are both drawn here, so a
generated course is scored against exactly the line its camera sees.
"""
import io
import math
from collections import namedtuple

import numpy as np
from PIL import Image

from wall_follower.evaluation.scoring.line_track import centreline_of

LINE_PIXEL = 0.005
TIE = 1e-9         # m: a pixel centre this near the line's edge is a tie (line_raster)
MARGIN = 0.5
WALL = 0.1
MARKING_HEIGHT = 0.001
# The robot models a line world's file includes (worlds/; a generated world gets copies).
INCLUDES = ('burger.inc', 'waffle.inc', 'waffle_pi.inc')

Camera = namedtuple('Camera', 'resolution fov height tilt')
Camera.__doc__ = """A Stage camera on a Waffle's mast: resolution (width, height) [px], fov
(horizontal, vertical) [deg], height: its pose's z above the body's top [m] (Stage draws
from the robot's centre at the body's height plus this), tilt: down from level [deg]."""

BODY = """
include "burger.inc"
include "waffle.inc"
include "waffle_pi.inc"

resolution 0.02
interval_sim 100
speedup 1
paused 0
quit_time 0

# Real Stage draws the camera in this window and caps its resolution at the window's
# drawing area: large enough for a 640x480 camera.
window
(
  size [ 800 650 ]
  scale 120
  center [ {cx:.3f} {cy:.3f} ]
  rotate [ 0 0 ]
  show_data 1
)

define wall model
(
  color "gray30"
  boundary 0
  gui_nose 0
  gui_grid 0
  gui_move 0
  gui_outline 0
  ranger_return 1
  obstacle_return 1
)

define floor_line model
(
  color "yellow"
  obstacle_return 0
  ranger_return -1
  gripper_return 0
  fiducial_return 0
  gui_move 0
  gui_outline 0
)

wall( name "wall_south" size [ {wall_x:.3f} {thick:.3f} 0.5 ] pose [ {cx:.3f} {south:.3f} 0 0 ] )
wall( name "wall_north" size [ {wall_x:.3f} {thick:.3f} 0.5 ] pose [ {cx:.3f} {north:.3f} 0 0 ] )
wall( name "wall_west" size [ {thick:.3f} {wall_y:.3f} 0.5 ] pose [ {west:.3f} {cy:.3f} 0 0 ] )
wall( name "wall_east" size [ {thick:.3f} {wall_y:.3f} 0.5 ] pose [ {east:.3f} {cy:.3f} 0 0 ] )

floor_line
(
  name "line"
  bitmap "{bitmap}"
  size [ {lx:.3f} {ly:.3f} {lz:.3f} ]
  pose [ {px:.4f} {py:.4f} 0 0 ]
)
"""

WAFFLE_PI = """
turtlebot3_waffle_pi
(
  name "turtlebot3"
  pose [ {rx:.3f} {ry:.3f} 0 {ryaw:.3f} ]
)
"""

WAFFLE_WITH_CAMERA = """
turtlebot3_waffle
(
  name "turtlebot3"
  camera
  (
    resolution [ {width:d} {height:d} ]
    range [ 0.05 8.0 ]
    fov [ {hfov:.1f} {vfov:.1f} ]
    pantilt [ 0 {tilt:.1f} ]
    size [ 0.025 0.025 0.010 ]
    color "black"
    pose [ 0.000 0.000 {z:.3f} 0.000 ]
  )
  pose [ {rx:.3f} {ry:.3f} 0 {ryaw:.3f} ]
)
"""


def line_raster(centreline):
    """(black pixels, ties, x of column 0's left edge, y of row 0's top edge): the line
    drawn on a grid of LINE_PIXEL aligned to multiples of it, cropped to its black pixels.

    ties: the pixels whose centre lies on the line's edge, to rounding: which way they
    fall depends on the last bit of a distance, and so on numpy's version (1.17 and
    1.24 part on a few dozen), so a check of the files does not judge them."""
    half = centreline.width / 2.0
    lower = np.floor((centreline.points.min(axis=0) - half) / LINE_PIXEL) - 2
    upper = np.ceil((centreline.points.max(axis=0) + half) / LINE_PIXEL) + 2
    cols = int(upper[0] - lower[0])
    rows = int(upper[1] - lower[1])
    xs = (lower[0] + np.arange(cols) + 0.5) * LINE_PIXEL
    ys = (upper[1] - np.arange(rows) - 0.5) * LINE_PIXEL
    gx, gy = np.meshgrid(xs, ys)
    distance = centreline.distance(gx, gy, within=half + LINE_PIXEL)
    black = distance <= half
    ties = np.abs(distance - half) <= TIE
    used_rows = np.nonzero(black.any(axis=1))[0]
    used_cols = np.nonzero(black.any(axis=0))[0]
    r0, r1, c0, c1 = used_rows[0], used_rows[-1] + 1, used_cols[0], used_cols[-1] + 1
    return (black[r0:r1, c0:c1], ties[r0:r1, c0:c1], (lower[0] + c0) * LINE_PIXEL,
            (upper[1] - r0) * LINE_PIXEL)


def world_files(name, course, header, camera=None, path='course', notes=None):
    """{file name: (bytes, pixels a check may not judge (ties) or None)} of the world
    NAME.world and its bitmap NAME_line.png drawn from a parsed course.

    header: the world file's opening comment, a format string that may use the
    values of the world (name, width_cm, kind, length, x0, x1, y0, y1, rx, ry, ryaw);
    camera: a Camera on a Waffle, or None for the Waffle Pi; path: the course's
    name in errors (line_track.CourseError); notes: more values for the header.
    """
    centreline = centreline_of(course, path)
    black, ties, left, top = line_raster(centreline)
    rows, cols = black.shape
    image = Image.fromarray(np.where(black, 0, 255).astype(np.uint8), mode='L')
    png = io.BytesIO()
    image.save(png, format='PNG', optimize=True)
    lower = centreline.points.min(axis=0) - MARGIN
    upper = centreline.points.max(axis=0) + MARGIN
    x0, y0 = (math.floor(v * 10) / 10.0 for v in lower)
    x1, y1 = (math.ceil(v * 10) / 10.0 for v in upper)
    rx, ry, ryaw = (float(v) for v in course.get('robot', course['start']))
    bitmap = '%s_line.png' % name
    values = dict(
        name=name, width_cm=centreline.width * 100, length=centreline.length,
        kind='a closed loop' if centreline.closed else 'open (it has an end)',
        x0=x0, x1=x1, y0=y0, y1=y1, rx=rx, ry=ry, ryaw=ryaw,
        cx=(x0 + x1) / 2.0, cy=(y0 + y1) / 2.0, thick=WALL,
        wall_x=x1 - x0 + 2 * WALL, wall_y=y1 - y0 + 2 * WALL,
        south=y0 - WALL / 2.0, north=y1 + WALL / 2.0, west=x0 - WALL / 2.0,
        east=x1 + WALL / 2.0, bitmap=bitmap,
        lx=cols * LINE_PIXEL, ly=rows * LINE_PIXEL, lz=MARKING_HEIGHT,
        px=left + cols * LINE_PIXEL / 2.0, py=top - rows * LINE_PIXEL / 2.0)
    if camera is None:
        robot = WAFFLE_PI.format(**values)
    else:
        robot = WAFFLE_WITH_CAMERA.format(
            width=camera.resolution[0], height=camera.resolution[1], hfov=camera.fov[0],
            vfov=camera.fov[1], tilt=camera.tilt, z=camera.height, **values)
    text = header.format(**dict(values, **(notes or {}))) + BODY.format(**values) + robot
    return {name + '.world': (text.encode(), None), bitmap: (png.getvalue(), ties)}
