"""LatestScan fed its scans directly: when a scan was taken, and when it has gone stale.

Needs ROS's Python modules but no master: the subscriber is only created,
and its callback is called here, under a ROS clock set by the test.
"""
import pytest
import rospy
from sensor_msgs.msg import LaserScan

from wall_follower.nodes.shared.latest_scan import LatestScan


def scan_taken_at(stamp):
    msg = LaserScan(angle_min=-3.14, angle_max=3.14, angle_increment=6.28 / 359,
                    range_min=0.12, range_max=3.5, ranges=[1.0] * 360)
    msg.header.stamp = rospy.Time.from_sec(stamp)
    return msg


def test_a_scan_is_timed_by_its_header_stamp_not_its_arrival(clock):
    # In simulation a scan can arrive before the /clock message of its own
    # step: its arrival time is then a step early, its stamp is not.
    scan = LatestScan()
    clock.now = 4.9
    scan._on_scan(scan_taken_at(5.0))
    reading = scan.latest(0.5)
    assert reading.view is not None and reading.taken == pytest.approx(5.0)


def test_a_scan_without_a_stamp_is_timed_by_its_arrival(clock):
    scan = LatestScan()
    clock.now = 4.9
    scan._on_scan(scan_taken_at(0.0))
    assert scan.latest(0.5).taken == pytest.approx(4.9)


@pytest.mark.parametrize('laser_clock', [-7.0, 0.5])
def test_a_scan_goes_stale_by_its_arrival_whatever_the_laser_clock(clock, laser_clock):
    # A laser host whose clock is 7 s behind still delivers fresh scans; on
    # wall time, one whose clock runs 0.5 s ahead proves nothing by its stamps.
    scan = LatestScan()
    clock.now = 10.0
    scan._on_scan(scan_taken_at(10.0 + laser_clock))
    clock.now = 10.4
    assert scan.latest(0.5).taken == pytest.approx(10.0 + laser_clock)
    clock.now = 10.6
    reading = scan.latest(0.5)
    assert reading.view is None and reading.taken is None
    assert reading.problem == 'no scan on /scan for 0.5 s'


def test_on_simulated_time_a_scan_that_came_while_the_clock_lagged_is_aged_from_its_stamp(
        clock, monkeypatch):
    # A node starved of CPU: its /clock messages queued while scans still came.
    # Dated by its clock, the scan of 6.8 s came at 6.3 s, and looked 0.6 s old
    # once the clock caught up: a driving node stood for a step in lockstep.
    monkeypatch.setattr(rospy.rostime, 'is_wallclock', lambda: False)
    scan = LatestScan()
    clock.now = 6.3
    scan._on_scan(scan_taken_at(6.8))
    clock.now = 6.9
    assert scan.latest(0.5).taken == pytest.approx(6.8)
    clock.now = 7.4
    assert scan.latest(0.5).problem == 'no scan on /scan for 0.5 s'


def test_an_unusable_scan_is_held_with_what_is_wrong(clock):
    scan = LatestScan()
    msg = scan_taken_at(3.0)
    msg.ranges = [0.0] * 360
    scan._on_scan(msg)
    reading = scan.latest(0.5)
    assert reading.view is None and reading.check is not None
    assert reading.problem == ('the scan on /scan is unusable: none of its 360 readings is '
                               'usable (360 0.0)')


def test_a_forgotten_scan_is_no_scan(clock):
    scan = LatestScan()
    scan._on_scan(scan_taken_at(3.0))
    scan.forget()
    assert scan.latest(0.5).check is None


def test_a_scan_that_came_before_the_clock_started_is_aged_from_its_start(clock):
    # On simulated time ROS time reads 0 until this node's first /clock, which
    # may come a second after the first scans.
    scan = LatestScan()
    scan._on_scan(scan_taken_at(0.9))
    clock.now = 1.1
    reading = scan.latest(1.0)
    assert reading.view is not None and reading.taken == pytest.approx(0.9)
    clock.now = 2.2
    assert scan.latest(1.0).view is None


@pytest.mark.parametrize('secs, nsecs, words', [
    (4102444800, 0, 'over 73 years'), (2 ** 32 - 1, 999999999, 'over 79 years')])
def test_a_scan_stamped_far_ahead_of_the_clock_is_stale_saying_so(clock, secs, nsecs, words):
    """A laser on a clock set to 2100, or a header's largest stamp: no view to drive on."""
    scan = LatestScan()
    clock.now = 1795878000.0
    msg = scan_taken_at(0.0)
    msg.header.stamp = rospy.Time(secs, nsecs)
    scan._on_scan(msg)
    reading = scan.latest(0.5)
    assert reading.view is None and reading.taken is None and reading.check is not None
    assert reading.problem == ("the scan on /scan is stale: it is stamped %s ahead of this "
                               "node's clock" % words)


def test_a_scan_stamped_an_hour_ahead_is_used(clock):
    """A laser host whose clock runs an hour ahead of this one."""
    scan = LatestScan()
    clock.now = 1795878000.0
    scan._on_scan(scan_taken_at(1795878000.0 + 3600.0))
    assert scan.latest(0.5).taken == pytest.approx(1795878000.0 + 3600.0)
