"""The newest laser scan, checked, for every node that reads the laser."""
import threading
from collections import namedtuple

import rospy
from sensor_msgs.msg import LaserScan

from wall_follower.control.sensing.scan_check import check_scan
from wall_follower.control.stamps import ahead_problem, arrival_time
from wall_follower.nodes.shared.connections import keep_connected
from wall_follower.params.driving import LASER_INPUT

Reading = namedtuple('Reading', ['check', 'view', 'taken', 'problem'])
"""What LatestScan holds: the ScanCheck (None before any scan), and either a
usable scan's view and time taken [s] or, both None, what is wrong."""


def arrived(stamp):
    """The ROS time a message stamped `stamp` (rospy.Time) arrives at, now, for its age:
    control.stamps.arrival_time on this node's clock."""
    return rospy.Time.from_sec(arrival_time(rospy.Time.now().to_sec(), stamp.to_sec(),
                                            not rospy.rostime.is_wallclock()))


class LatestScan(object):
    """Keeps the newest scan, checked by check_scan, and knows when it has gone stale.

    Age is measured in ROS time from the scan's arrival, so it follows
    simulated time in simulation and does not depend on the laser host's
    clock (arrived(): on simulated time, no earlier than its stamp). The
    time a scan was taken is its header stamp: the arrival time would race
    the /clock message of the same simulated step, and jitter by a step.
    """

    parameters = LASER_INPUT   # the node's parameters that set a DriveLoop on it

    def __init__(self, topic='scan'):
        self._latest = (None, None, None)   # (ScanCheck, arrival, taken), replaced as one
        self._arrived = threading.Condition()
        self._sub = rospy.Subscriber(topic, LaserScan, self._on_scan, queue_size=1)
        keep_connected([self._sub])

    def _on_scan(self, msg):
        arrival = arrived(msg.header.stamp)
        taken = msg.header.stamp if not msg.header.stamp.is_zero() else arrival
        with self._arrived:
            self._latest = (check_scan(msg), arrival, taken)
            self._arrived.notify_all()

    @property
    def topic(self):
        """The scan topic's resolved name."""
        return self._sub.resolved_name

    def taken(self):
        """When the newest scan was taken (rospy.Time), usable or not; None before any."""
        return self._latest[2]

    def forget(self):
        """Drop the scan held, e.g. one that arrived on a clock that has since moved back."""
        self._latest = (None, None, None)

    def wait_for_newer(self, seen, timeout):
        """Wait until a scan newer than `seen` (a Reading's check) comes, at most timeout wall s.

        Lets a controller answer each scan as soon as it arrives instead of
        at its next timer tick: in lockstep simulation a command that merely
        repeats the last one would let the world step on a stale decision.
        """
        with self._arrived:
            if self._latest[0] is seen:
                self._arrived.wait(timeout)

    def _arrival_dated(self, now):
        """The newest (check, arrival, taken), a scan that came before this node's
        clock first ran dated from now.

        On simulated time ROS time reads 0 until the node's first /clock,
        which may come a second after its first scans: aged from 0, such a
        scan would look a second old the moment the clock starts, and a
        node with patience would give up on a laser that works.
        """
        with self._arrived:
            check, arrival, taken = self._latest
            if check is not None and arrival.is_zero() and not now.is_zero():
                arrival, taken = now, (now if taken.is_zero() else taken)
                self._latest = (check, arrival, taken)
            return check, arrival, taken

    def latest(self, timeout):
        """The newest scan as a Reading: its view and time taken [s] if usable and fresh,
        else None for both and the problem, in words.

        A scan stamped far ahead of this node's clock (control.stamps) is
        stale, however fresh its arrival: its stamp would time a controller's
        work on a moment that never comes.
        """
        now = rospy.Time.now()
        check, arrival, taken = self._arrival_dated(now)
        if check is None or (now - arrival).to_sec() > timeout:
            problem = 'no scan on %s for %.1f s' % (self.topic, timeout)
            return Reading(check, None, None, problem)
        if check.view is None:
            problem = 'the scan on %s is unusable: %s' % (self.topic, check.problem)
            return Reading(check, None, None, problem)
        ahead = ahead_problem(taken.to_sec(), now.to_sec())
        if ahead is not None:
            return Reading(check, None, None, 'the scan on %s is stale: %s' % (self.topic, ahead))
        return Reading(check, check.view, taken.to_sec(), None)
