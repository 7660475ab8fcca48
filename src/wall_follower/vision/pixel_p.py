"""The lab's line follower (follower_p.py) as a baseline: a turn rate proportional to the pixel
offset of the slice centroid from the image's middle, at a constant speed.

Its gain is per pixel, so its behaviour changes with the camera's
resolution; it cuts every bend, as it steers the camera, not the base,
onto the line. Unlike the lab's, it stops when the slice holds no line
(the lab's drives on blind with its last command).
"""
from wall_follower.control.motion import STOP, Command
from wall_follower.vision.line_image import slice_centroid


class PixelP(object):
    """speed [m/s]; gain [rad/s per pixel]; top, depth: the slice (line_image.slice_rows)."""

    def __init__(self, speed, gain, top, depth):
        self.speed = speed
        self.gain = gain
        self.top = top
        self.depth = depth

    def update(self, mask):
        """The Command for a line mask (uint8 array, rows top-down)."""
        centroid = slice_centroid(mask, self.top, self.depth)
        if centroid is None:
            return STOP
        error = centroid[0] - mask.shape[1] / 2.0
        return Command(self.speed, -self.gain * error)
