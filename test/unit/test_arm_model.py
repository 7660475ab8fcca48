"""The arm's files read into a model: the URDF's chain, limits and shapes, the SRDF's states
and disabled pairs, the joint limits; and each unusable description refused by name."""
import math

import numpy as np
import pytest

from arm_files import limits, model, semantics, text
from wall_follower.arm.model import ModelError, read_acceleration_limits, read_srdf, read_urdf


def test_the_urdf_is_a_chain_of_four_limited_joints_to_the_hand():
    arm = model()
    assert arm.names == ['hip', 'shoulder', 'elbow', 'wrist']
    assert arm.links == ['world', 'base_link', 'torso', 'upper_arm', 'lower_arm', 'hand']
    assert np.allclose(arm.joint('hip').axis, (0, 0, 1))
    assert all(np.allclose(arm.joint(n).axis, (0, 1, 0)) for n in ('shoulder', 'elbow', 'wrist'))
    assert (arm.lower < 0).all() and (arm.upper > 0).all() and (arm.velocity > 0).all()
    assert [s.kind for s in arm.shapes['hand']] == ['box']
    assert arm.shapes['torso'][0].size == (0.05, 0.5)


def test_every_link_has_visual_inertial_and_collision_and_every_joint_a_transmission():
    urdf = text('urdf', 'cougarbot.urdf')
    for link in model().links[1:]:
        block = urdf.split('<link name="%s">' % link)[1].split('</link>')[0]
        assert '<visual>' in block and '<collision>' in block and '<inertial>' in block, link
    transmissions = [block.split('</transmission>')[0] for block in urdf.split('<transmission')[1:]]
    for joint in model().names:
        assert any('<joint name="%s">' % joint in block and 'PositionJointInterface' in block
                   for block in transmissions), joint


def test_the_srdf_names_states_within_the_limits_and_disables_adjacent_pairs():
    arm = model()
    found = semantics(arm)
    assert {'home', 'ready'} <= set(found.states)
    assert found.states['home'] == dict((name, 0.0) for name in arm.names)
    for a, b in zip(arm.links[1:], arm.links[2:]):
        assert frozenset((a, b)) in found.disabled


def test_joint_limits_give_every_joint_an_acceleration():
    arm = model()
    velocity, acceleration = limits(arm)
    assert (acceleration > 0).all() and len(acceleration) == 4
    assert (velocity <= arm.velocity).all()


URDF = text('urdf', 'cougarbot.urdf')


@pytest.mark.parametrize('document, words', [
    ('<robot', 'not well-formed'),
    ('<robt name="x"><link name="a"/></robt>', 'not <robot>'),
    (URDF.replace('type="revolute"', 'type="prismatic"', 1), 'only revolute and fixed'),
    (URDF.replace('lower="-3.1"', 'lower="west"'), 'joint hip limit lower must be 1 numbers'),
    (URDF.replace('lower="-3.1" upper="3.1"', 'lower="3.1" upper="-3.1"'), 'lower < upper'),
    (URDF.replace('<cylinder radius="0.05" length="0.5"/></geometry>\n    </collision>',
                  '<mesh filename="torso.stl"/></geometry>\n    </collision>'), 'only box'),
    (URDF.replace('<link name="world"/>', '<link name="world"/><link name="spare"/>'),
     'one root link'),
    ('<robot name="x"><link name="a"/></robot>', 'no revolute joint'),
])
def test_an_unusable_urdf_is_refused_saying_why(document, words):
    with pytest.raises(ModelError, match=words):
        read_urdf(document)


SRDF = text('config', 'cougarbot.srdf')


@pytest.mark.parametrize('document, words', [
    (SRDF.replace('name="shoulder" value="0.6"', 'name="shoulder" value="2.6"'),
     'group state ready: shoulder at 2.6000 rad is outside'),
    (SRDF.replace('<joint name="wrist" value="0.8"/>', ''), 'gives joints'),
    (SRDF.replace('link2="hand"', 'link2="claw"'), 'unknown link'),
])
def test_an_unusable_srdf_is_refused_saying_why(document, words):
    with pytest.raises(ModelError, match=words):
        read_srdf(document, model())


def test_a_joint_without_an_acceleration_limit_is_refused():
    limits = {'joint_limits': dict((name, {'has_acceleration_limits': True,
                                           'max_acceleration': 1.0})
                                   for name in ('hip', 'shoulder', 'elbow'))}
    with pytest.raises(ModelError, match='joint wrist'):
        read_acceleration_limits(limits, model())
    limits['joint_limits']['wrist'] = {'has_acceleration_limits': True,
                                       'max_acceleration': math.inf * 0}
    with pytest.raises(ModelError, match='joint wrist'):
        read_acceleration_limits(limits, model())
