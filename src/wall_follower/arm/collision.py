"""Whether the arm touches the floor (z = 0 in the root's frame) or itself.

The floor test is exact for the URDF's boxes, cylinders and spheres (their
lowest point). Between links each shape is taken as the capsule round it (a
cylinder: the segment between its end centres, swept by its radius; a box: its
longest axis swept by its half cross-section diagonal; a sphere: a point swept
by its radius), so that a pair said clear is clear, at the price of seeing
contact up to a radius early near flat ends. Pairs the SRDF disables (links
joined by a joint, or never near each other) are not checked.
"""
import collections
import itertools
import math

import numpy as np

from wall_follower.arm.kinematics import link_frames

Capsule = collections.namedtuple('Capsule', 'link start end radius')


def lowest_point(shape, frame):
    """The lowest z [m] of a collision shape whose link is at frame (4x4)."""
    placed = frame.dot(shape.origin)
    centre, rotation = placed[:3, 3], placed[:3, :3]
    if shape.kind == 'sphere':
        return centre[2] - shape.size[0]
    if shape.kind == 'cylinder':
        radius, length = shape.size
        axis = rotation[:, 2]
        across = math.sqrt(max(0.0, 1.0 - axis[2] * axis[2]))
        return centre[2] - abs(axis[2]) * length / 2.0 - radius * across
    half = np.asarray(shape.size) / 2.0
    return centre[2] - float(np.abs(rotation[2, :]).dot(half))


def capsule(link, shape, frame):
    """The Capsule round a collision shape whose link is at frame."""
    placed = frame.dot(shape.origin)
    centre, rotation = placed[:3, 3], placed[:3, :3]
    if shape.kind == 'sphere':
        return Capsule(link, centre, centre, shape.size[0])
    if shape.kind == 'cylinder':
        radius, length = shape.size
        half = rotation[:, 2] * length / 2.0
        return Capsule(link, centre - half, centre + half, radius)
    size = np.asarray(shape.size)
    longest = int(np.argmax(size))
    others = [size[i] / 2.0 for i in range(3) if i != longest]
    half = rotation[:, longest] * size[longest] / 2.0
    return Capsule(link, centre - half, centre + half, math.hypot(*others))


def segment_distance(p1, q1, p2, q2):
    """The shortest distance between segments p1-q1 and p2-q2 (3-vectors)."""
    d1, d2, r = q1 - p1, q2 - p2, p1 - p2
    a, e, f = d1.dot(d1), d2.dot(d2), d2.dot(r)
    tiny = 1e-12
    if a <= tiny and e <= tiny:
        return float(np.linalg.norm(r))
    if a <= tiny:
        s, t = 0.0, min(max(f / e, 0.0), 1.0)
    else:
        c = d1.dot(r)
        if e <= tiny:
            s, t = min(max(-c / a, 0.0), 1.0), 0.0
        else:
            b = d1.dot(d2)
            denominator = a * e - b * b
            s = min(max((b * f - c * e) / denominator, 0.0), 1.0) if denominator > tiny else 0.0
            t = (b * s + f) / e
            if t < 0.0:
                s, t = min(max(-c / a, 0.0), 1.0), 0.0
            elif t > 1.0:
                s, t = min(max((b - c) / a, 0.0), 1.0), 1.0
    return float(np.linalg.norm(p1 + d1 * s - p2 - d2 * t))


def _rising_links(model):
    """The links from the first joint that tilts on: those before it stand on the floor or
    only turn about the vertical, at a height no joint changes (and a floor margin above
    them must not count as contact)."""
    frames = link_frames(model, np.zeros(len(model.names)))
    for joint in model.joints:
        axis = frames[joint.parent].dot(joint.origin)[:3, :3].dot(joint.axis)
        if not np.allclose(np.cross(axis, (0.0, 0.0, 1.0)), 0.0):
            return model.links[model.links.index(joint.child):]
    return []


class CollisionChecker(object):
    """Contacts of one arm (an ArmModel) at given joint positions.

    disabled: frozensets of link pairs not checked (the SRDF's); floor_margin,
    self_margin [m]: the least clearance counted as clear. The floor is checked
    against the links whose height can change (see _rising_links).
    """

    def __init__(self, model, disabled=(), floor_margin=0.0, self_margin=0.0):
        self.model = model
        self.floor_margin = floor_margin
        self.self_margin = self_margin
        shaped = [link for link in model.links if model.shapes.get(link)]
        self.floor_links = [link for link in _rising_links(model) if link in shaped]
        self.pairs = [(a, b) for a, b in itertools.combinations(shaped, 2)
                      if frozenset((a, b)) not in set(disabled)]

    def contacts(self, positions):
        """Sentences naming each contact at positions (model.names' order): [] if clear."""
        frames = link_frames(self.model, positions)
        found = []
        for link in self.floor_links:
            for shape in self.model.shapes[link]:
                low = lowest_point(shape, frames[link])
                if low < self.floor_margin - 1e-9:
                    found.append('%s %.3f m below the floor' % (link, -low) if low < 0.0 else
                                 '%s %.3f m above the floor' % (link, low))
        capsules = dict((link, [capsule(link, shape, frames[link])
                                for shape in self.model.shapes[link]])
                        for link in set(itertools.chain(*self.pairs)))
        for a, b in self.pairs:
            for one, other in itertools.product(capsules[a], capsules[b]):
                gap = segment_distance(one.start, one.end, other.start, other.end) - \
                    one.radius - other.radius
                if gap < self.self_margin:
                    found.append('%s touches %s' % (a, b))
                    break
        return found

    def path_contacts(self, start, goal, step):
        """The first contact on the straight joint-space line from start to goal, as
        (fraction of the way, [sentences]), checked every `step` rad of the joint moving most;
        None if the whole line is clear."""
        start, goal = np.asarray(start, dtype=float), np.asarray(goal, dtype=float)
        count = max(1, int(math.ceil(np.max(np.abs(goal - start)) / step)))
        for index in range(count + 1):
            fraction = index / float(count)
            found = self.contacts(start + (goal - start) * fraction)
            if found:
                return fraction, found
        return None
