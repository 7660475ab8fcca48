"""Where the arm's links are for given joint positions, and the joint positions that put
the origin of the tool frame (the last link, `hand`) on a point.

Inverse kinematics is closed form for an arm built as cougarbot is: a first joint
about the vertical, then joints about parallel horizontal axes (y), each link's
next joint straight along its z. The first joint turns the arm's plane towards
the point (or away from it, reaching over the top); the two joints after it are
a planar two-link problem (elbow up or down); the last joint turns only the
hand about its own origin, so it is redundant for a point goal: it is chosen
by the caller (move_arm keeps it where it is, see wall_follower.arm.planning).
"""
import collections
import math

import numpy as np

from wall_follower.arm.model import ModelError
from wall_follower.rotation import axis_angle_matrix

# Positions (m) and angles (rad) closer than this are the same.
EPSILON = 1e-9


def rotation(axis, angle):
    """The 4x4 transform of a rotation by angle about a unit axis."""
    matrix = np.eye(4)
    matrix[:3, :3] = axis_angle_matrix(axis, angle)
    return matrix


def link_frames(model, positions):
    """link name -> its 4x4 transform in the root's frame, for joint positions given in
    model.names' order."""
    frames = {model.root: np.eye(4)}
    values = dict(zip(model.names, positions))
    current = np.eye(4)
    for joint in model.chain:
        current = current.dot(joint.origin)
        if joint.kind != 'fixed':
            current = current.dot(rotation(joint.axis, values[joint.name]))
        frames[joint.child] = current
    return frames


def tool_position(model, positions):
    """The origin of the last link (the tool frame) in the root's frame [m]."""
    return link_frames(model, positions)[model.links[-1]][:3, 3]


Planar = collections.namedtuple('Planar', 'height upper lower')
"""The arm's dimensions for the closed form: the height of the second joint above the
root [m] and the lengths of the two links after it (second joint to third, third to
the tool origin) [m]."""


def planar_dimensions(model):
    """The closed form's dimensions of model; ModelError if it is not built for it."""
    if len(model.joints) != 4:
        raise ModelError('closed-form inverse kinematics needs four joints, not %d'
                         % len(model.joints))
    zero = link_frames(model, np.zeros(4))
    first = model.joints[0]
    if not np.allclose(first.axis, (0.0, 0.0, 1.0)):
        raise ModelError('joint %s must turn about z' % first.name)
    points = []
    for joint in model.joints[1:]:
        frame = zero[joint.parent].dot(joint.origin)
        if not np.allclose(joint.axis, (0.0, 1.0, 0.0)) or \
                not np.allclose(frame[:3, :3], np.eye(3)):
            raise ModelError('joint %s must turn about y, its frame square to the root\'s'
                             % joint.name)
        points.append(frame[:3, 3])
    points.append(zero[model.links[-1]][:3, 3])
    if not np.allclose([p[:2] for p in points], 0.0):
        raise ModelError('the joints after %s must stand on its axis' % first.name)
    heights = [p[2] for p in points]
    if not (heights[0] < heights[1] < heights[2] and abs(heights[3] - heights[2]) < EPSILON):
        raise ModelError('the tool origin must lie on the last joint, each joint above the last')
    return Planar(heights[0], heights[1] - heights[0], heights[2] - heights[1])


def arm_solutions(dimensions, point, hip_now):
    """Every (first, second, third) joint triple that puts the tool origin on point,
    limits not yet applied; [] if the point is out of reach. On the vertical axis the first
    joint is free and stays at hip_now."""
    x, y, z = point
    horizontal = math.hypot(x, y)
    rise = z - dimensions.height
    upper, lower = dimensions.upper, dimensions.lower
    distance2 = horizontal * horizontal + rise * rise
    cosine = (distance2 - upper * upper - lower * lower) / (2.0 * upper * lower)
    if cosine > 1.0 + EPSILON or cosine < -1.0 - EPSILON:
        return []
    bend = math.acos(max(-1.0, min(1.0, cosine)))
    if horizontal < EPSILON:
        turns = [(hip_now, 0.0)]
    else:
        toward = math.atan2(y, x)
        turns = [(toward, horizontal), (toward + math.pi, -horizontal)]
    solutions = []
    for hip, reach in turns:
        for elbow in ((bend, -bend) if bend > EPSILON else (bend,)):
            shoulder = math.atan2(reach, rise) - math.atan2(lower * math.sin(elbow),
                                                            upper + lower * math.cos(elbow))
            solutions.append((hip, shoulder, elbow))
    return solutions


def inverse(model, dimensions, point, current):
    """Joint positions (model.names' order) that put the tool origin on point, within the
    limits, nearest first: ordered by the time the slowest joint needs to get there from
    current at its speed limit. The last joint stays at its current position.
    Returns (solutions, reason): reason says why there is none."""
    current = np.asarray(current, dtype=float)
    wrist = current[3]
    triples = arm_solutions(dimensions, point, current[0])
    if not triples:
        reach = dimensions.upper + dimensions.lower
        return [], 'out of reach: %.3f m from the %s joint, which reaches %.3f m' % (
            math.sqrt(math.hypot(point[0], point[1]) ** 2 + (point[2] - dimensions.height) ** 2),
            model.names[1], reach)
    solutions = []
    for hip, shoulder, elbow in triples:
        hip = _nearest_turn(hip, current[0], model.lower[0], model.upper[0])
        if hip is None:
            continue
        positions = np.array([hip, shoulder, elbow, wrist])
        if not model.outside_limits(positions):
            solutions.append(positions)
    if not solutions:
        return [], 'out of the joint limits: every arm pose reaching it bends a joint too far'
    solutions.sort(key=lambda q: (np.max(np.abs(q - current) / model.velocity),
                                  np.sum(np.abs(q - current))))
    return solutions, None


def _nearest_turn(angle, now, lower, upper):
    """angle plus the multiple of a turn within [lower, upper] nearest now, or None."""
    best = None
    base = angle + 2.0 * math.pi * round((now - angle) / (2.0 * math.pi))
    for candidate in (base - 2.0 * math.pi, base, base + 2.0 * math.pi):
        if lower - EPSILON <= candidate <= upper + EPSILON and (
                best is None or abs(candidate - now) < abs(best - now)):
            best = min(max(candidate, lower), upper)
    return best
