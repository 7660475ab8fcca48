"""Parameters of the line_follower node: its loop and clamp, the camera, the line's colour, the
path memory, and the two controllers (the pursuit and the lab's pixel-P baseline)."""
import math

from wall_follower.params import Parameter as P, Section, driving
from wall_follower.params.camera.line_mask import HSV, IMAGE, RULES as HSV_RULES, SLICE

CONTROLLERS = ('pursuit', 'pixel_p')
CONVENTIONS = ('auto', 'optical', 'stageros')
"""The choices of controller and frame_convention (vision.floor names them AUTO, OPTICAL,
STAGEROS)."""

NODE = (
    driving.camera_loop(image_timeout=0.3),
    driving.LIMITS,
    Section('camera', (
        P('controller', 'pursuit', "pursuit: follow the line's remembered path with the base; "
          "pixel_p: the lab's follower_p.py (a baseline, it cuts bends)",
          choices=CONTROLLERS),
        P('frame_convention', 'auto', "the camera frame's tf: optical (REP 103), stageros (as "
          'stageros publishes it), or auto (optical if its name says so)',
          choices=CONVENTIONS),
        P('floor_frame', 'base_footprint', 'the frame whose z = 0 plane is the floor, on the '
          "robot's base"),
        P('odom_frame', 'odom', 'the frame in which the path is remembered'),
        P('tf_timeout', 0.2, 'wait at most this long for the tf of a frame [s]', 0.0, 5.0),
        P('max_distance', 1.5, 'line pixels seen farther than this on the floor are not used '
          '[m]', 0.1, 10.0),
        P('pixel_stride', 2, 'use every n-th pixel of the mask in each direction', 1, 16),
        P('view_margin', 3.0, 'the floor within this of the image border counts as out of view '
          '[px]', 0.0, 100.0),
    )),
)
"""The node's own parameters (wall_follower.nodes.camera.line_follower)."""

CHECK = (
    Section('line', (
        P('line_width', 0.045, "width of the course's line on the floor [m] (the line worlds': "
          '4.5 cm): line colour is acted on only where it is about this wide', 0.005, 0.5),
        P('line_width_tolerance', 2.0, 'line colour from line_width / this to line_width x '
          'this wide counts as the line; a wider patch stops the robot (not a line), a '
          'narrower thread is left out', 1.2, 10.0),
    )),
)
"""What counts as the line (vision.line_check.LineCheck)."""

PATH = (
    Section('path', (
        P('step', 0.02, 'tracing step along the line [m]', 0.005, 0.2),
        P('radius', 0.04, 'line points within this of the next step make its centre [m]; '
          'above half the line width', 0.005, 0.3),
        P('max_length', 1.5, 'the path is traced at most this far [m]', 0.1, 10.0),
        P('first_reach', 0.6, 'from a standing start, the line may begin this far ahead [m]',
          0.0, 5.0),
        P('cell', 0.01, 'line points are thinned to one per square of this side [m]',
          0.001, 0.1),
        P('keep_behind', 0.1, 'the path is kept this far behind the base [m]', 0.0, 1.0),
    )),
)
"""The path memory (vision.line_path.LinePath)."""

PURSUIT = (
    Section('pursuit', (
        P('speed', 0.19, 'cruising speed [m/s] (the clamp holds it to max_linear)', 0.0, 1.0),
        P('turn_rate', 0.49, 'the highest turn rate it plans with [rad/s] (the clamp holds it '
          'to max_angular)', 0.01, 3.0),
        P('lookahead', 0.1, 'the target is the first point of the path at least this far '
          'from the base [m]', 0.02, 2.0),
        P('lookahead_time', 0.8, 'and at least as far as the planned speed goes in this time '
          '[s]', 0.0, 10.0),
        P('preview', 0.3, 'slow down for the sharpest bend within this far ahead [m]',
          0.0, 3.0),
        P('bend_share', 0.9, 'take bends at this share of turn_rate, keeping the rest for '
          'corrections', 0.1, 1.0),
        P('decel', 0.3, 'braking toward the line\'s end [m/s^2]', 0.01, 5.0),
        P('stop_distance', 0.05, "stop for good once the base is this near the line's end [m]",
          0.0, 1.0),
        P('min_ahead', 0.05, 'less known path than this ahead of the base and no end seen: '
          'the line is lost [m]', 0.0, 1.0),
        P('max_bearing', 1.0, 'a target farther off the heading than this is turned to in '
          'place [rad]', 0.1, math.pi),
        P('search_rate', 0.3, 'turn rate of the search in place for a lost line [rad/s]',
          0.0, 3.0),
        P('search_angle', 2.0 * math.pi, 'the search turns this far at most, then waits '
          'stopped [rad]', 0.0, 4.0 * math.pi),
    )),
)
"""The pursuit controller (vision.line_pursuit.LinePursuit)."""

PIXEL_P = (
    Section('pixel_p', (
        P('p_speed', 0.2, "the lab's forward speed [m/s] (the clamp holds it to max_linear)",
          0.0, 1.0),
        P('p_gain', 0.01, "the lab's turn rate per pixel of the centroid's offset "
          '[rad/s per px]', 0.0, 1.0),
    )),
)
"""The lab's baseline (vision.pixel_p.PixelP), on the lab's slice
(params.camera.line_mask.SLICE)."""

RULES = HSV_RULES

TABLE = NODE + IMAGE + HSV + SLICE + CHECK + PATH + PURSUIT + PIXEL_P
