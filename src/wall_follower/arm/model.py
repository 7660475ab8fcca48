"""The arm's description read from its files: the URDF (joints, limits, collision shapes),
the SRDF (named states, link pairs never checked) and MoveIt's joint_limits.yaml.

Read with xml.etree: urdf_parser_py is not packaged on every system the
package runs on, and the part of the format used here is small. Anything
that cannot be used raises ModelError with a sentence saying what.
"""
import collections
import math
import xml.etree.ElementTree as ElementTree

import numpy as np

from wall_follower.rotation import rpy_matrix


class ModelError(ValueError):
    """A description that cannot be used, with the reason in words."""


Limits = collections.namedtuple('Limits', 'lower upper velocity effort')
"""A joint's position range [rad], its speed limit [rad/s] and effort limit [N m]."""

Joint = collections.namedtuple('Joint', 'name kind parent child origin axis limits')
"""A URDF joint; origin is the 4x4 transform from the parent link's frame to the joint's,
axis a unit 3-vector in the joint's frame, limits None for a fixed joint."""

Shape = collections.namedtuple('Shape', 'kind size origin')
"""A collision shape: kind 'box' (size: x, y, z lengths), 'cylinder' (radius, length,
along z) or 'sphere' (radius,); origin its 4x4 transform in the link's frame."""


def transform(xyz=(0.0, 0.0, 0.0), rpy=(0.0, 0.0, 0.0)):
    """The 4x4 homogeneous transform of a URDF origin (fixed-axis roll, pitch, yaw)."""
    matrix = np.eye(4)
    matrix[:3, :3] = rpy_matrix(*rpy)
    matrix[:3, 3] = xyz
    return matrix


def _numbers(text, count, what):
    try:
        values = [float(word) for word in text.split()]
    except ValueError:
        values = []
    if len(values) != count or not all(math.isfinite(v) for v in values):
        raise ModelError('%s must be %d numbers, not %r' % (what, count, text))
    return values


def _origin(element, what):
    origin = element.find('origin')
    if origin is None:
        return np.eye(4)
    return transform(_numbers(origin.get('xyz', '0 0 0'), 3, what + ' origin xyz'),
                     _numbers(origin.get('rpy', '0 0 0'), 3, what + ' origin rpy'))


class ArmModel(object):
    """A serial arm: its links from the root, the joints between them, their collision shapes.

    joints: the movable joints from the root to the tip, in chain order (fixed joints are
    folded into the origins around them); names: their names; links: every link name from
    the root, in chain order.
    """

    def __init__(self, name, root, chain, shapes):
        self.name = name
        self.root = root
        self.chain = chain          # every joint from the root, fixed ones included
        self.shapes = shapes        # link -> [Shape]
        self.joints = [joint for joint in chain if joint.kind != 'fixed']
        self.names = [joint.name for joint in self.joints]
        self.links = [root] + [joint.child for joint in chain]
        self.lower = np.array([joint.limits.lower for joint in self.joints])
        self.upper = np.array([joint.limits.upper for joint in self.joints])
        self.velocity = np.array([joint.limits.velocity for joint in self.joints])

    def joint(self, name):
        for joint in self.joints:
            if joint.name == name:
                return joint
        raise KeyError(name)

    def outside_limits(self, positions, tolerance=1e-9):
        """Sentences naming each joint of positions (in self.names' order) outside its range."""
        return ['%s at %.4f rad is outside [%.4f, %.4f]' % (name, q, low, high)
                for name, q, low, high in zip(self.names, positions, self.lower, self.upper)
                if not (low - tolerance <= q <= high + tolerance)]


def read_urdf(text):
    """An ArmModel from a URDF document (a string): one chain from the root to its one tip."""
    try:
        robot = ElementTree.fromstring(text)
    except ElementTree.ParseError as error:
        raise ModelError('the URDF is not well-formed XML: %s' % error)
    if robot.tag != 'robot':
        raise ModelError('the URDF has <%s> at its root, not <robot>' % robot.tag)
    links = [link.get('name') for link in robot.findall('link')]
    if not links:
        raise ModelError('the URDF has no link')
    joints = [_read_joint(element) for element in robot.findall('joint')]
    by_parent = collections.defaultdict(list)
    for joint in joints:
        by_parent[joint.parent].append(joint)
    children = set(joint.child for joint in joints)
    roots = [link for link in links if link not in children]
    if len(roots) != 1:
        raise ModelError('the URDF must have one root link, not %s' % (roots or 'none'))
    chain, link = [], roots[0]
    while by_parent[link]:
        if len(by_parent[link]) > 1:
            raise ModelError('link %s branches (joints %s): only a serial arm is read' % (
                link, ', '.join(joint.name for joint in by_parent[link])))
        chain.append(by_parent[link][0])
        link = chain[-1].child
    if not any(joint.kind != 'fixed' for joint in chain):
        raise ModelError('the URDF\'s chain from %s has no revolute joint' % roots[0])
    shapes = dict((element.get('name'), _read_shapes(element))
                  for element in robot.findall('link'))
    return ArmModel(robot.get('name'), roots[0], chain, shapes)


def _read_joint(element):
    name = element.get('name')
    kind = element.get('type')
    if kind not in ('fixed', 'revolute', 'prismatic', 'continuous'):
        raise ModelError('joint %s has type %r, which this reader does not know' % (name, kind))
    if kind in ('prismatic', 'continuous'):
        raise ModelError('joint %s is %s: only revolute and fixed joints are read' % (name, kind))
    try:
        parent = element.find('parent').get('link')
        child = element.find('child').get('link')
    except AttributeError:
        raise ModelError('joint %s needs a <parent link=...> and a <child link=...>' % name)
    axis_element = element.find('axis')
    axis = np.array(_numbers(axis_element.get('xyz'), 3, 'joint %s axis' % name)
                    if axis_element is not None else [1.0, 0.0, 0.0])
    limits = None
    if kind == 'revolute':
        limit = element.find('limit')
        if limit is None:
            raise ModelError('revolute joint %s has no <limit>' % name)
        values = [_numbers(limit.get(key, ''), 1, 'joint %s limit %s' % (name, key))[0]
                  for key in ('lower', 'upper', 'velocity', 'effort')]
        limits = Limits(*values)
        if limits.lower >= limits.upper or limits.velocity <= 0.0:
            raise ModelError('joint %s needs lower < upper and a positive velocity limit' % name)
        norm = np.linalg.norm(axis)
        if norm == 0.0:
            raise ModelError('joint %s has a zero axis' % name)
        axis = axis / norm
    return Joint(name, kind, parent, child, _origin(element, 'joint %s' % name), axis, limits)


def _read_shapes(link):
    shapes = []
    for collision in link.findall('collision'):
        geometry = collision.find('geometry')
        what = 'link %s collision' % link.get('name')
        if geometry is None or len(geometry) != 1:
            raise ModelError('%s needs one <geometry>' % what)
        shape = geometry[0]
        if shape.tag == 'box':
            size = _numbers(shape.get('size', ''), 3, what + ' box size')
        elif shape.tag == 'cylinder':
            size = (_numbers(shape.get('radius', ''), 1, what + ' radius')[0],
                    _numbers(shape.get('length', ''), 1, what + ' length')[0])
        elif shape.tag == 'sphere':
            size = _numbers(shape.get('radius', ''), 1, what + ' radius')
        else:
            raise ModelError('%s is a %s: only box, cylinder and sphere are read' % (
                what, shape.tag))
        shapes.append(Shape(shape.tag, tuple(size), _origin(collision, what)))
    return shapes


Semantics = collections.namedtuple('Semantics', 'states disabled')
"""From an SRDF: states, name -> {joint: position} of the group states; disabled, a set of
frozensets {link, link} never checked for collision."""


def read_srdf(text, model, group='arm'):
    """The named states of group and the disabled collision pairs, held to the model:
    a state must give every joint of the model, within its limits."""
    try:
        robot = ElementTree.fromstring(text)
    except ElementTree.ParseError as error:
        raise ModelError('the SRDF is not well-formed XML: %s' % error)
    states = {}
    for state in robot.findall('group_state'):
        if state.get('group') != group:
            continue
        name = state.get('name')
        values = dict((joint.get('name'), _numbers(joint.get('value', ''), 1, 'state %s joint %s'
                                                   % (name, joint.get('name')))[0])
                      for joint in state.findall('joint'))
        if sorted(values) != sorted(model.names):
            raise ModelError('group state %s gives joints %s, not the arm\'s %s' % (
                name, sorted(values), sorted(model.names)))
        problems = model.outside_limits([values[n] for n in model.names])
        if problems:
            raise ModelError('group state %s: %s' % (name, '; '.join(problems)))
        states[name] = values
    disabled = set()
    for pair in robot.findall('disable_collisions'):
        links = (pair.get('link1'), pair.get('link2'))
        unknown = [link for link in links if link not in model.links]
        if unknown:
            raise ModelError('disable_collisions names unknown link(s) %s' % ', '.join(
                str(link) for link in unknown))
        disabled.add(frozenset(links))
    return Semantics(states, disabled)


def read_acceleration_limits(limits, model):
    """Each joint's acceleration limit [rad/s^2], in model.names' order, from MoveIt's
    joint_limits.yaml (a mapping with `joint_limits`); every joint must have one."""
    entries = (limits or {}).get('joint_limits', {}) if isinstance(limits, dict) else {}
    accelerations = []
    for name in model.names:
        entry = entries.get(name) or {}
        value = entry.get('max_acceleration')
        if not entry.get('has_acceleration_limits') or not isinstance(value, (int, float)) \
                or not value > 0.0:
            raise ModelError('joint_limits has no positive acceleration limit for joint %s' % name)
        accelerations.append(float(value))
    return np.array(accelerations)


def read_velocity_limits(limits, model):
    """Each joint's speed limit [rad/s]: the URDF's, lowered where joint_limits.yaml has less."""
    entries = (limits or {}).get('joint_limits', {}) if isinstance(limits, dict) else {}
    velocity = model.velocity.copy()
    for index, name in enumerate(model.names):
        entry = entries.get(name) or {}
        value = entry.get('max_velocity')
        if entry.get('has_velocity_limits') and isinstance(value, (int, float)) and value > 0.0:
            velocity[index] = min(velocity[index], float(value))
    return velocity
