"""Where the laser sits on the robot: ~laser_x if set, else read once from tf.

The controllers plan their arcs about the robot's rotation centre (base_link
on a TurtleBot3 and in Stage), so they need the laser's position ahead of
it: 32 mm behind it on a Burger, 64 mm on a Waffle. The real TurtleBot3
(robot_state_publisher: base_link -> base_scan) and both simulators
(base_link -> base_laser_link) publish that offset, so it is read from the
transform between the scan's own frame and base_link, and a Waffle works
with nothing set. The first scan names the frame; both waits are in wall
time, so a paused or frozen simulated clock cannot stall them. With no
scan or no transform in time, the Burger's value is used, with a warning;
so a node fed scans but no tf (a test's synthetic scans) is given ~laser_x,
lest it wait for a transform that never comes.
"""
import math
from collections import namedtuple

import rospy
import tf2_ros
from sensor_msgs.msg import LaserScan

from wall_follower.nodes.shared.messages import yaw_of
from wall_follower.nodes.shared.tf_lookup import lookup
from wall_follower.params import defaults
from wall_follower.params.course.wall_following import FOLLOWER

__all__ = ['laser_x', 'mount_of', 'choose_laser_x']

BASE_FRAME = 'base_link'
# The parameter's default: a TurtleBot3 Burger's.
BURGER_LASER_X = defaults(FOLLOWER)['laser_x']
# Wall seconds to wait for the first scan (a simulator may start paused) and
# then for the transform (tf's publishers still connecting).
SCAN_WAIT = 30.0
TF_WAIT = 5.0
POLL = 0.05    # wall s between two looks for the transform
# A laser turned further than this from base_link's heading is warned about:
# the controllers take the scan's 0 rad as straight ahead.
TURNED_LIMIT = math.radians(1.0)

Mount = namedtuple('Mount', ['x', 'y', 'yaw'])


def laser_x(scan_topic='scan', base_frame=BASE_FRAME, scan_wait=SCAN_WAIT, tf_wait=TF_WAIT):
    """The laser's position ahead of the rotation centre [m], logged with its source.

    Called once when a node starts; blocks until a scan and the transform
    have come, at most scan_wait + tf_wait wall seconds.
    """
    name = rospy.get_name()
    if rospy.has_param('~laser_x'):
        value = rospy.get_param('~laser_x')
        try:
            value = float(value)
        except (TypeError, ValueError):
            rospy.logerr('%s: ~laser_x=%r is not a number; reading the laser mount from tf',
                         name, value)
        else:
            rospy.loginfo('%s: laser_x %.3f m (set by ~laser_x)', name, value)
            return value
    frame = _scan_frame(rospy.resolve_name(scan_topic), scan_wait)
    mount = None
    if frame:
        buffer = tf2_ros.Buffer()
        listener = tf2_ros.TransformListener(buffer)
        transform, _ = lookup(buffer, base_frame, frame, wait=tf_wait, poll=POLL)
        listener.unregister()
        mount = mount_of(transform)
    value, warning = choose_laser_x(mount, frame, base_frame, tf_wait)
    if warning:
        rospy.logwarn('%s: %s', name, warning)
    if mount is not None:
        rospy.loginfo('%s: laser_x %.3f m (from tf %s -> %s)', name, value, base_frame, frame)
    return value


def _scan_frame(topic, wait):
    """frame_id of the first scan on topic, '' if it is empty, None if none came."""
    try:
        return rospy.wait_for_message(topic, LaserScan, timeout=wait).header.frame_id
    except rospy.ROSException:
        rospy.logwarn('%s: no scan on %s within %.0f s to name the laser frame',
                      rospy.get_name(), topic, wait)
        return None


def mount_of(transform):
    """The Mount (x, y, yaw) of a geometry_msgs/TransformStamped, None for None."""
    if transform is None:
        return None
    t = transform.transform
    return Mount(t.translation.x, t.translation.y, yaw_of(t.rotation))


def choose_laser_x(mount, frame, base_frame=BASE_FRAME, tf_wait=TF_WAIT):
    """(laser_x, warning or None) from what tf gave: the mount's x, else the Burger's.

    mount: a Mount, or None when none was found; frame: the scan's frame_id
    ('' when the scan had none, None when no scan came).
    """
    if mount is None:
        if frame is None:
            why = 'no scan came'
        elif not frame:
            why = 'the scan has no frame_id'
        else:
            why = 'no transform %s -> %s within %.0f s' % (base_frame, frame, tf_wait)
        return BURGER_LASER_X, ("%s; assuming a TurtleBot3 Burger's laser_x %.3f m "
                                "(set ~laser_x to override)" % (why, BURGER_LASER_X))
    if abs(mount.yaw) > TURNED_LIMIT:
        return mount.x, ('the laser frame %s is turned %.0f deg from %s; the scan is read '
                         'as if its 0 rad pointed straight ahead'
                         % (frame, math.degrees(mount.yaw), base_frame))
    return mount.x, None
