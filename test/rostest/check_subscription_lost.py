#!/usr/bin/env python3
"""rostest: a scan subscription that rospy never connected is connected again.

rospy loses the master's news of a publisher when it comes while a
subscriber of its topic is registering (wall_follower/action_registration.py
says how). The race needs a loaded machine; its outcome is made here instead:
the news of the scan's publisher is dropped before rospy queues it. The
master then lists the publisher, and the subscription has no connection.
LatestScan's ConnectionKeeper must connect it, and scans must come through.
"""
import sys
import threading
import unittest

import rospy
import rospy.impl.registration as registration
import rostest
from sensor_msgs.msg import LaserScan

from synthetic_scans import wall_on_the_right
from waiting import wait_until
from wall_follower.nodes.shared.connections import PERIOD
from wall_follower.nodes.shared.latest_scan import LatestScan

TOPIC = '/lost_scan'
SCAN_PERIOD = 0.1    # wall s
# Wall seconds for the keeper's two looks at the master, and the connection after them.
WAIT_LIMIT = 4.0 * PERIOD + 10.0


class NewsDropped(object):
    """Drops the first news of publishers of TOPIC that rospy's registration gets."""

    def __init__(self):
        self.dropped = threading.Event()
        self._update = registration.RegManager.publisher_update
        dropping = self

        def publisher_update(manager, name, uris):
            if name == TOPIC and uris and not dropping.dropped.is_set():
                dropping.dropped.set()
                return
            dropping._update(manager, name, uris)

        registration.RegManager.publisher_update = publisher_update


class SubscriptionLost(unittest.TestCase):

    def test_a_lost_publisher_is_connected_again(self):
        news = NewsDropped()
        scans = LatestScan(TOPIC)
        probe = rospy.Subscriber(TOPIC, LaserScan)   # shares the scan reader's connections
        publisher = rospy.Publisher(TOPIC, LaserScan, queue_size=1)
        self.assertTrue(news.dropped.wait(WAIT_LIMIT), 'no news of the publisher came')
        self.assertEqual(probe.get_num_connections(), 0,
                         'connected anyway: the test proves nothing')
        timer = rospy.Timer(rospy.Duration(SCAN_PERIOD),
                            lambda _: publisher.publish(wall_on_the_right(0.25)))
        try:
            self.assertTrue(wait_until(lambda: scans.taken() is not None, WAIT_LIMIT),
                            'the lost subscription was never connected')
        finally:
            timer.shutdown()


if __name__ == '__main__':
    rospy.init_node('check_subscription_lost')
    rostest.rosrun('wall_follower', 'check_subscription_lost', SubscriptionLost, sys.argv)
