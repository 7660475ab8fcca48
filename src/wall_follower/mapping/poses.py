"""2-D rigid transforms (x, y, yaw) as tuples: the mapper's frames chained by hand."""
import math

from wall_follower.rotation import wrap_angle

__all__ = ['compose', 'inverse', 'between']


def compose(a, b):
    """a then b: the pose b, given in frame a, expressed in a's parent frame."""
    c, s = math.cos(a[2]), math.sin(a[2])
    return (a[0] + c * b[0] - s * b[1], a[1] + s * b[0] + c * b[1], wrap_angle(a[2] + b[2]))


def inverse(a):
    """The transform that undoes a."""
    c, s = math.cos(a[2]), math.sin(a[2])
    return (-c * a[0] - s * a[1], s * a[0] - c * a[1], wrap_angle(-a[2]))


def between(a, b):
    """b seen from a: the motion that takes pose a to pose b."""
    return compose(inverse(a), b)
