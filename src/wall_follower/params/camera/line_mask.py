"""Parameters of the line_mask node (the lab's colour filter and line finder): the line's
HSV bounds and the lab's slice, which the line follower takes too."""
from wall_follower.params import Parameter as P, Section

IMAGE = (
    Section('image', (
        P('compressed', False, 'read sensor_msgs/CompressedImage on image/compressed (the '
          "real Waffle Pi's raspicam) instead of sensor_msgs/Image on image"),
    )),
)
"""How the camera's frames come (nodes.shared.latest_image), for every node that reads them."""

HSV = (
    Section('colour', (
        P('hue_low', 20, 'lowest hue of the line, OpenCV scale (0-179); above hue_high the '
          'range wraps round through 0 (red)', 0, 179),
        P('hue_high', 40, 'highest hue of the line, OpenCV scale (0-179)', 0, 179),
        P('saturation_low', 100, 'lowest saturation of the line (0-255)', 0, 255),
        P('saturation_high', 255, 'highest saturation of the line (0-255)', 0, 255),
        P('value_low', 100, 'lowest value (brightness) of the line (0-255)', 0, 255),
        P('value_high', 255, 'highest value (brightness) of the line (0-255)', 0, 255),
    )),
)
"""The line's colour (vision.line_image.hsv_bounds): yellow by default."""

SLICE = (
    Section('slice', (
        P('slice_top', 0.75, "top of the lab's thin slice of the image, as a share of its "
          'height from the top row', 0.0, 1.0),
        P('slice_depth', 0.0833, "height of the lab's slice, as a share of the image's height "
          '(the lab: 20 rows of 240)', 0.001, 1.0),
    )),
)
"""The lab's slice, where the centroid is found (vision.line_image.slice_centroid)."""


def _bounds_ordered(values):
    for channel in ('saturation', 'value'):
        if values[channel + '_low'] > values[channel + '_high']:
            return '%s_low (%r) must not be above %s_high (%r)' % (
                channel, values[channel + '_low'], channel, values[channel + '_high'])
    return None


RULES = (_bounds_ordered,)
"""What the bounds must satisfy together (params.checked's rules); the hue may wrap."""

NODE = (
    Section('node', (
        P('dot_radius', 5, 'radius of the red dot marking the centroid in the debug image [px]',
          1, 50),
    )),
)

TABLE = NODE + IMAGE + HSV + SLICE
