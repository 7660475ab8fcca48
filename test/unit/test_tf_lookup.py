"""nodes.shared.tf_lookup: tf asked again until a wait counted on its own clock (wall time) is
over, never at a stamp out of the buffer's reach."""
import math

import pytest
import rospy
import tf2_ros
from geometry_msgs.msg import TransformStamped

from fake_clock import FakeClock
from wall_follower.nodes.shared.laser_mount import mount_of
from wall_follower.nodes.shared.tf_lookup import lookup


def transform(x, y=0.0, yaw=0.0):
    t = TransformStamped()
    t.transform.translation.x, t.transform.translation.y = x, y
    t.transform.rotation.z, t.transform.rotation.w = math.sin(yaw / 2), math.cos(yaw / 2)
    return t


class FakeBuffer(object):
    """A tf2 buffer that has the transform from its `ready_after`-th look on."""

    def __init__(self, ready_after, found=None):
        self.ready_after = ready_after
        self.found = found if found is not None else transform(-0.064)
        self.asked = []

    def lookup_transform(self, target, source, stamp):
        self.asked.append(stamp)
        if self.ready_after is None or len(self.asked) <= self.ready_after:
            raise tf2_ros.LookupException('"%s" passed to lookupTransform argument target_frame '
                                          'does not exist.' % target)
        return self.found


def test_the_transform_is_waited_for_in_the_given_clock():
    clock = FakeClock()
    found, problem = lookup(FakeBuffer(ready_after=10), 'base_link', 'base_scan', wait=5.0,
                            poll=0.05, clock=clock, sleep=clock.sleep)
    assert problem is None and mount_of(found).x == pytest.approx(-0.064)
    assert clock.now == pytest.approx(0.5)


def test_a_transform_that_never_comes_ends_the_wait_at_its_bound():
    clock = FakeClock()
    found, problem = lookup(FakeBuffer(ready_after=None), 'base_link', 'base_scan', wait=2.0,
                            poll=0.05, clock=clock, sleep=clock.sleep)
    assert found is None and 'base_link' in problem
    assert clock.now == pytest.approx(2.0, abs=0.06)


def test_no_stamp_asks_for_the_latest(clock):
    buffer = FakeBuffer(ready_after=0)
    assert lookup(buffer, 'odom', 'base_link')[1] is None
    assert buffer.asked == [rospy.Time(0)]


@pytest.mark.parametrize('stamp', [rospy.Time(4102444800), rospy.Time(2 ** 32 - 1),
                                   rospy.Time(0, 1)])
def test_a_stamp_out_of_reach_is_refused_without_asking_tf(clock, stamp):
    """tf2's C++ core aborts the process on a stamp some decades from its data."""
    clock.now = 1000.0
    buffer = FakeBuffer(ready_after=0)
    found, problem = lookup(buffer, 'odom', 'base_link', stamp)
    assert found is None and 'stamped more than 10 s' in problem
    assert buffer.asked == []


def test_a_stamp_within_reach_is_asked_for(clock):
    clock.now = 1000.0
    buffer = FakeBuffer(ready_after=0)
    assert lookup(buffer, 'odom', 'base_link', rospy.Time(999, 500000000))[1] is None
    assert buffer.asked == [rospy.Time(999, 500000000)]
