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

# A clearance [m] less than minus this is a contact (rounding aside, touching is clear).
CONTACT_TOLERANCE = 1e-9


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
        self.reach = _reaches(model)

    def _gaps(self, positions):
        """(clearance beyond its margin [m], link, other link or None for the floor, lowest
        point [m] or None) of every link checked against the floor and every pair checked."""
        frames = link_frames(self.model, positions)
        for link in self.floor_links:
            for shape in self.model.shapes[link]:
                low = lowest_point(shape, frames[link])
                yield low - self.floor_margin, link, None, low
        capsules = dict((link, [capsule(link, shape, frames[link])
                                for shape in self.model.shapes[link]])
                        for link in set(itertools.chain(*self.pairs)))
        for a, b in self.pairs:
            gap = min(segment_distance(one.start, one.end, other.start, other.end) -
                      one.radius - other.radius
                      for one, other in itertools.product(capsules[a], capsules[b]))
            yield gap - self.self_margin, a, b, None

    def contacts(self, positions):
        """Sentences naming each contact at positions (model.names' order): [] if clear."""
        return _sentences(list(self._gaps(positions)))

    def path_contacts(self, start, goal, step):
        """The first contact on the straight joint-space line from start to goal, as
        (fraction of the way, [sentences]); None if the whole line is clear.

        From each position checked the next is as far along as its clearance proves clear
        (no point of the arm moves further than the joints' turns times their reach, and two
        links close in on each other at most twice as fast), but never further than `step`
        rad of the joint moving most past where the clearance is too small to prove more.
        """
        start, goal = np.asarray(start, dtype=float), np.asarray(goal, dtype=float)
        delta = goal - start
        widest = float(np.max(np.abs(delta)))
        sweep = 2.0 * float(np.dot(np.abs(delta), self.reach))   # m per unit of the way
        least = 1.0 if widest == 0.0 else min(1.0, step / widest)
        fraction = 0.0
        while True:
            gaps = list(self._gaps(start + delta * fraction))
            found = _sentences(gaps)
            if found:
                return fraction, found
            if fraction >= 1.0:
                return None
            clearance = min([gap[0] for gap in gaps] or [math.inf])
            fraction = min(1.0, fraction + max(least, clearance / sweep if sweep else 1.0))


def _sentences(gaps):
    """The contacts among _gaps' answers, in words."""
    found = []
    for gap, link, other, low in gaps:
        if gap >= -CONTACT_TOLERANCE:
            continue
        if other is not None:
            found.append('%s touches %s' % (link, other))
        else:
            found.append('%s %.3f m below the floor' % (link, -low) if low < 0.0 else
                         '%s %.3f m above the floor' % (link, low))
    return found


def _reaches(model):
    """For each joint, the farthest any point of the links it carries can be from it [m]:
    the lengths of the joint offsets after it plus the farthest shape of a link from that
    link's frame (a bound of how fast the arm's points move as the joint turns)."""
    extents = {}
    for link, shapes in model.shapes.items():
        extents[link] = max([np.linalg.norm(shape.origin[:3, 3]) + _radius(shape)
                             for shape in shapes] or [0.0])
    reaches = []
    for joint in model.joints:
        index = model.chain.index(joint)
        reach, farthest = 0.0, extents.get(joint.child, 0.0)
        for later in model.chain[index + 1:]:
            reach += np.linalg.norm(later.origin[:3, 3])
            farthest = max(farthest, reach + extents.get(later.child, 0.0))
        reaches.append(farthest)
    return np.array(reaches)


def _radius(shape):
    """The radius of the sphere round a shape, about its origin."""
    if shape.kind == 'sphere':
        return shape.size[0]
    if shape.kind == 'cylinder':
        return math.hypot(shape.size[0], shape.size[1] / 2.0)
    return float(np.linalg.norm(shape.size)) / 2.0
