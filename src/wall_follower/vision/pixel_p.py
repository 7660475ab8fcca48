"""The lab's line follower (follower_p.py) as a baseline: a turn rate proportional to the pixel
offset of the slice centroid from the image's middle, at a constant speed.

Its gain is per pixel, so its behaviour changes with the camera's
resolution; it cuts every bend, as it steers the camera, not the base,
onto the line. Unlike the lab's, it stops when the slice holds no line
(the lab's drives on blind with its last command), and it says the line
is known ahead only where the centroid lies on the floor ahead of the
base, within the drive loop's half width of its heading.
"""
import math

from wall_follower.control.motion import STOP, Answer, Command
from wall_follower.vision.line_image import slice_centroid


class PixelP(object):
    """speed [m/s]; gain [rad/s per pixel]; top, depth: the slice (line_image.slice_rows)."""

    def __init__(self, speed, gain, top, depth):
        self.speed = speed
        self.gain = gain
        self.top = top
        self.depth = depth

    def update(self, mask, projection, half_width):
        """The Answer for a line mask (uint8 array, rows top-down) seen through a projection
        (vision.floor.FloorProjection, in the base's frame): the command, and whether the
        centroid is on the floor within half_width [rad] of straight ahead."""
        centroid = slice_centroid(mask, self.top, self.depth)
        if centroid is None:
            return Answer(STOP, False)
        error = centroid[0] - mask.shape[1] / 2.0
        floor = projection.to_floor([centroid])
        known = len(floor) > 0 and floor[0][0] > 0.0 and abs(
            math.atan2(floor[0][1], floor[0][0])) <= half_width
        return Answer(Command(self.speed, -self.gain * error), bool(known))
