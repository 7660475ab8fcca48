"""One step of the line follower: a camera frame in, a command and what is known ahead out.

The node (nodes/camera/line_follower.py), the benchmark (evaluation/benchmarks/line.py) and
the closed-loop unit tests all run this step, so that what is measured and tested
is what drives. It takes plain values: the frame (a BGR image), the camera's
FloorProjection (vision.floor, in the base's frame), the base's pose in the
odometry frame and the drive loop's half width ahead. Each frame:

1. the image must be the size camera_info gives (vision.image_check);
2. the line's colour is masked (vision.line_image) and the mask judged
   (vision.line_check): a frame that is not a line stops the robot, leaving
   the path remembered and the controller's state as they were, so that a
   search turns only on frames of clear floor;
3. the controller answers (a control.motion.Answer: the command and whether
   the line is known ahead). `pursuit`: the line's pixels are put on the
   floor, into the odometry frame, where vision.line_path remembers the
   line's path and vision.line_pursuit steers the base along it. `pixel_p`:
   the lab's slice centroid steers (vision.pixel_p).

The parameters are the node's (params.camera.line_follower's TABLE: name -> value).
"""
from collections import namedtuple

from wall_follower.control.motion import STOP, Answer
from wall_follower.params import pick
from wall_follower.params.camera.line_follower import PATH, PURSUIT
from wall_follower.vision.image_check import size_problem
from wall_follower.vision.line_check import NOT_A_LINE, LineCheck
from wall_follower.vision.line_image import hsv_bounds, line_mask, line_pixels
from wall_follower.vision.line_path import LinePath
from wall_follower.vision.line_pursuit import LinePursuit, from_base_frame, in_base_frame
from wall_follower.vision.pixel_p import PixelP

PURSUIT_CONTROLLER = 'pursuit'

Step = namedtuple('Step', ['answer', 'problem', 'path', 'state'])
"""What one step gives: the Answer; why it stops the robot for want of a line (None when it
does not); the remembered path ((K, 2), odometry frame) and the pursuit's state (None with
pixel_p, and when the frame was not a line)."""


class LineStep(object):
    """The line follower's state from frame to frame: the path remembered, the controllers."""

    def __init__(self, values):
        self.memory = LinePath(**pick(values, PATH))
        self.pursuit = LinePursuit(**pick(values, PURSUIT))
        self.check = LineCheck(values['line_width'], values['line_width_tolerance'])
        self.reconfigure(values)

    def reconfigure(self, values):
        """Take new parameter values, in force from the next frame on."""
        self.values = values
        self.bounds = hsv_bounds(values)
        self.check.reconfigure(values['line_width'], values['line_width_tolerance'])
        self.memory.reconfigure(**pick(values, PATH))
        self.pursuit.reconfigure(**pick(values, PURSUIT))
        self.pixel_p = PixelP(values['p_speed'], values['p_gain'], values['slice_top'],
                              values['slice_depth'])

    @property
    def needs_base(self):
        """Whether update() needs the base's pose (the pursuit does; pixel_p does not)."""
        return self.values['controller'] == PURSUIT_CONTROLLER

    def restart(self):
        """Forget the path and the controller's state (a clock that moved back)."""
        self.memory.forget()
        self.pursuit = LinePursuit(**pick(self.values, PURSUIT))

    def update(self, image, projection, base, half_width):
        """The Step for one BGR frame seen through projection, the base at (x, y, yaw) in the
        odometry frame (None will do for pixel_p), half_width [rad] either side of straight
        ahead for what counts as known ahead."""
        k = projection.intrinsics
        problem = size_problem(image, k.width, k.height)
        if problem is not None:
            return Step(Answer(STOP, False), problem, None, None)
        verdict = self.check.judge(line_mask(image, self.bounds), projection)
        if verdict.kind == NOT_A_LINE:
            return Step(Answer(STOP, False), 'no line: %s' % verdict.problem, None, None)
        if not self.needs_base:
            return Step(self.pixel_p.update(verdict.mask, projection, half_width), None, None,
                        None)
        margin = self.values['view_margin']

        def in_view(points):
            return projection.sees(in_base_frame(points, base), margin)

        seen = from_base_frame(projection.to_floor(
            line_pixels(verdict.mask, self.values['pixel_stride'])), base)
        path = self.memory.update(seen, in_view, base, lambda point: in_view(point)[0])
        answer = self.pursuit.update(path, self.memory.end_seen, base, half_width)
        return Step(answer, None, path, self.pursuit.state)
