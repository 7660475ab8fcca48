"""LatestScan fed its scans directly: when a scan was taken, and when it has gone stale.

Needs ROS's Python modules but no master: the subscriber is only created,
and its callback is called here, under a ROS clock set by the test.
"""
import pytest
import rospy
from sensor_msgs.msg import LaserScan

from wall_follower.nodes.common import LatestScan


@pytest.fixture
def clock(monkeypatch):
    """A settable ROS clock: clock.now = t (seconds)."""
    class Clock(object):
        now = 0.0
    monkeypatch.setattr(rospy.Time, 'now', staticmethod(lambda: rospy.Time.from_sec(Clock.now)))
    return Clock


def scan_taken_at(stamp):
    msg = LaserScan(angle_min=-3.14, angle_increment=0.0175, range_min=0.12, range_max=3.5,
                    ranges=[1.0] * 360)
    msg.header.stamp = rospy.Time.from_sec(stamp)
    return msg


def test_a_scan_is_timed_by_its_header_stamp_not_its_arrival(clock):
    # In simulation a scan can arrive before the /clock message of its own
    # step: its arrival time is then a step early, its stamp is not.
    scan = LatestScan()
    clock.now = 4.9
    scan._on_scan(scan_taken_at(5.0))
    view, taken = scan.fresh_stamped(0.5)
    assert view is not None and taken == pytest.approx(5.0)


def test_a_scan_without_a_stamp_is_timed_by_its_arrival(clock):
    scan = LatestScan()
    clock.now = 4.9
    scan._on_scan(scan_taken_at(0.0))
    assert scan.fresh_stamped(0.5)[1] == pytest.approx(4.9)


def test_a_scan_goes_stale_by_its_arrival_whatever_the_laser_clock(clock):
    # A laser host whose clock is 7 s behind still delivers fresh scans.
    scan = LatestScan()
    clock.now = 10.0
    scan._on_scan(scan_taken_at(3.0))
    clock.now = 10.4
    assert scan.fresh_stamped(0.5)[1] == pytest.approx(3.0)
    clock.now = 10.6
    assert scan.fresh_stamped(0.5) == (None, None)
    assert scan.fresh(0.5) is None
