"""The `slam` node: the package's mapper, with gmapping's interface.

Subscribes `scan` and `odom` (nav_msgs/Odometry): the robot's odometry pose
at each scan's stamp is interpolated between the odometry messages around
it, and the laser's mount (base_frame -> the scan's frame) read from tf
once (tf is not listened to after that). Publishes `map`
(nav_msgs/OccupancyGrid, latched) and `map_metadata` every
~map_update_interval seconds of ROS time, and the tf map_frame ->
odom_frame that puts the robot where scan matching found it. Every scan is
processed, in order (a deep queue rather than the newest only), so that a
run in simulated time gives the same map however busy the machine is.

What it cannot trust it says, with a warning, and does not draw: a scan
that control.sensing.scan_check finds malformed or unusable, odometry that
control.course.odom_check finds not finite or with no unit quaternion (a scan
that only such odometry could place is skipped), a scan or odometry
stamped far ahead of the node's clock (control.stamps: a map -> odom
transform broadcast at such a stamp would abort every tf listener, this
node's own included). Odometry whose time went back (a simulator
restarted, a bag looped) starts its history afresh, and one that jumped
further than the robot can drive is warned of: the map is drawn on at the
jumped pose only after the warning.

Parameters: the table in wall_follower.params.mapping.slam. A mapping run is long
and tuned while it runs (`rosrun dynamic_reconfigure dynparam set /slam
map_update_interval 1.0`, or rqt_reconfigure): a change applies at the next
scan, in the scan callback, which alone touches the mapper. The frames and
the grids (READ_AT_START) keep the values they started with.
"""
import bisect
import math
import threading
import time

import rospy
import tf2_ros
from geometry_msgs.msg import TransformStamped
from nav_msgs.msg import MapMetaData, OccupancyGrid, Odometry
from sensor_msgs.msg import LaserScan

import numpy as np

from wall_follower.cfg import SlamConfig
from wall_follower.control.course.odom_check import OdomCheck, odometry_problem
from wall_follower.control.sensing.scan_check import check_scan
from wall_follower.control.stamps import ahead_problem
from wall_follower.mapping.slam import LOOP_CLOSED, NOT_TRUSTED, RELOCATED, Mapper
from wall_follower.nodes.shared.connections import keep_connected
from wall_follower.nodes.shared.messages import pose_message, pose_of, yaw_of
from wall_follower.nodes.shared.parameters import NodeParameters
from wall_follower.nodes.shared.startup import init_node
from wall_follower.nodes.shared.tf_lookup import lookup
from wall_follower.params import pick
from wall_follower.params.mapping.slam import MAPPER, READ_AT_START, RULES, TABLE
from wall_follower.rotation import quaternion_of_yaw, wrap_angle

# Scans waiting to be processed (100 s of a 10 Hz laser): a simulation run flat out may
# outpace the mapper for a while, but not lose it scans; one this far behind drops the oldest.
SCAN_QUEUE = 1000
# Odometry messages kept to interpolate scans' poses from: more than the scans queued.
ODOM_KEPT = 4 * SCAN_QUEUE


def interpolate(before, after, stamp):
    """Pose at stamp between two (stamp, (x, y, yaw)) samples."""
    (t0, p0), (t1, p1) = before, after
    f = 0.0 if t1 == t0 else (stamp - t0) / (t1 - t0)
    return (p0[0] + f * (p1[0] - p0[0]), p0[1] + f * (p1[1] - p0[1]),
            wrap_angle(p0[2] + f * wrap_angle(p1[2] - p0[2])))


def _pose_of(transform):
    t = transform.transform
    return t.translation.x, t.translation.y, yaw_of(t.rotation)


class SlamNode(object):
    def __init__(self):
        self.params = NodeParameters(TABLE, SlamConfig, rules=RULES,
                                     read_at_start=READ_AT_START)
        self.p = self.params.snapshot()
        self.mapper = Mapper(**pick(self.p, MAPPER))   # ValueError on a grid that cannot be
        self.laser_known = False         # the laser's mount is read at the first scan
        self.odom_stamps, self.odom_poses = [], []
        self.odom_check = OdomCheck()
        self.odom_problem = None         # what was wrong with the newest odometry, if anything
        self.odom_arrived = threading.Condition()
        self.buffer = tf2_ros.Buffer()
        self.listener = tf2_ros.TransformListener(self.buffer)
        self.broadcaster = tf2_ros.TransformBroadcaster()
        self.map_pub = rospy.Publisher('map', OccupancyGrid, queue_size=1, latch=True)
        self.meta_pub = rospy.Publisher('map_metadata', MapMetaData, queue_size=1, latch=True)
        self.last_published = None
        self.cpu = 0.0
        keep_connected([rospy.Subscriber('odom', Odometry, self.on_odom, queue_size=SCAN_QUEUE),
                        rospy.Subscriber('scan', LaserScan, self.on_scan, queue_size=SCAN_QUEUE)])

    def on_odom(self, msg):
        p, q = msg.pose.pose.position, msg.pose.pose.orientation
        stamp = msg.header.stamp.to_sec()
        with self.odom_arrived:
            self.odom_problem = ahead_problem(stamp, rospy.get_time()) or odometry_problem(
                p.x, p.y, q.x, q.y, q.z, q.w)
            if self.odom_problem is not None:
                rospy.logwarn_throttle(5.0, 'slam: odometry on %s cannot be trusted: %s; skipped'
                                       % (rospy.resolve_name('odom'), self.odom_problem))
                return
            went_back = bool(self.odom_stamps) and stamp < self.odom_stamps[-1]
            problem = self.odom_check.problem(stamp, p.x, p.y, q.x, q.y, q.z, q.w)
            if problem is not None:
                rospy.logwarn('slam: odometry on %s: %s; %s', rospy.resolve_name('odom'), problem,
                              'its history is dropped' if went_back else
                              'the map is drawn on from the new pose')
            if went_back:
                self.odom_stamps, self.odom_poses = [], []   # time went back: a new run
            self.odom_stamps.append(stamp)
            self.odom_poses.append(pose_of(msg))
            if len(self.odom_stamps) > ODOM_KEPT:
                del self.odom_stamps[:ODOM_KEPT // 2], self.odom_poses[:ODOM_KEPT // 2]
            self.odom_arrived.notify_all()

    def odometry_at(self, stamp):
        """The odometry pose at stamp (s), waiting up to ~odom_timeout wall s for it; None
        if it never comes or is older than what is kept."""
        deadline = time.monotonic() + self.p['odom_timeout']
        with self.odom_arrived:
            while not self.odom_stamps or self.odom_stamps[-1] < stamp:
                left = deadline - time.monotonic()
                if left <= 0.0 or rospy.is_shutdown():
                    return None
                self.odom_arrived.wait(left)
            i = bisect.bisect_left(self.odom_stamps, stamp)
            if self.odom_stamps[i] == stamp:
                return self.odom_poses[i]
            if i == 0:
                return None
            return interpolate((self.odom_stamps[i - 1], self.odom_poses[i - 1]),
                               (self.odom_stamps[i], self.odom_poses[i]), stamp)

    def _laser_mount(self, frame):
        mount, problem = lookup(self.buffer, self.p['base_frame'], frame,
                                wait=self.p['odom_timeout'])
        if mount is None:
            rospy.logwarn_throttle(5.0, 'slam: no transform %s -> %s (%s); scan skipped',
                                   self.p['base_frame'], frame, problem)
        return mount

    def _retune(self):
        """Put the parameters changed since the last scan in force (in the scan callback)."""
        values = self.params.take_update()
        if values is not None:
            self.p = values
            self.mapper.reconfigure(**pick(values, MAPPER))

    def on_scan(self, msg):
        self._retune()
        problem = check_scan(msg).problem
        if problem is not None:
            rospy.logwarn_throttle(5.0, 'slam: the scan on %s is unusable: %s; skipped'
                                   % (rospy.resolve_name('scan'), problem))
            return
        problem = ahead_problem(msg.header.stamp.to_sec(), rospy.get_time())
        if problem is not None:
            rospy.logwarn_throttle(5.0, 'slam: the scan on %s is stale: %s; skipped'
                                   % (rospy.resolve_name('scan'), problem))
            return
        if not self.laser_known:
            mount = self._laser_mount(msg.header.frame_id)
            if mount is None:
                return
            self.mapper.laser = _pose_of(mount)
            self.laser_known = True
            # tf is read no more: a transform stamped far ahead, from any node,
            # would abort this process inside tf2's listener.
            self.listener.unregister()
            rospy.loginfo('slam: mapping at %.3f m per cell, laser at (%.3f, %.3f, %.1f deg) '
                          'on %s', self.p['delta'], *(self.mapper.laser[:2] + (
                              math.degrees(self.mapper.laser[2]), self.p['base_frame'])))
        odom = self.odometry_at(msg.header.stamp.to_sec())
        if odom is None:
            with self.odom_arrived:
                problem = self.odom_problem
            rospy.logwarn_throttle(5.0, 'slam: no odometry at the scan of %.3f s%s; scan skipped'
                                   % (msg.header.stamp.to_sec(), '' if problem is None else
                                      ' (the odometry cannot be trusted: %s)' % problem))
            return
        angles = msg.angle_min + msg.angle_increment * np.arange(len(msg.ranges))
        started = time.process_time()
        pose = self.mapper.add_scan(msg.ranges, angles, msg.range_min, msg.range_max, odom)
        self.cpu += time.process_time() - started
        if pose is None:
            rospy.loginfo_throttle(5.0, 'slam: waiting for the robot to stand still (or to '
                                   'stop turning, after ~start_patience scans) to start the map')
            return
        self._tell(msg.header.stamp.to_sec())
        try:
            self._send_transform(msg.header.stamp)
            if self.last_published is None or (msg.header.stamp - self.last_published).to_sec() \
                    >= self.p['map_update_interval']:
                self.publish_map(msg.header.stamp)
        except rospy.ROSException:
            if not rospy.is_shutdown():
                raise
            # A scan that came as the node shut down: rospy has closed the topics.

    def _tell(self, stamp):
        """What became of the scan of stamp: at debug level always; a match not trusted
        and a relocation as a (throttled) warning, a loop closed at info level."""
        decision, outcome = self.mapper.decision, self.mapper.outcome
        rospy.logdebug('slam: scan of %.3f s: %s', stamp, decision)
        if outcome == NOT_TRUSTED:
            rospy.logwarn_throttle(5.0, 'slam: %s; odometry used, scan not drawn' % decision)
        elif outcome == RELOCATED:
            rospy.logwarn('slam: %s', decision)
        elif outcome == LOOP_CLOSED:
            rospy.loginfo('slam: %s', decision)

    def _send_transform(self, stamp):
        x, y, yaw = self.mapper.map_to_odom()
        t = TransformStamped()
        t.header.stamp = stamp
        t.header.frame_id = self.p['map_frame']
        t.child_frame_id = self.p['odom_frame']
        t.transform.translation.x, t.transform.translation.y = x, y
        t.transform.rotation.z, t.transform.rotation.w = quaternion_of_yaw(yaw)
        self.broadcaster.sendTransform(t)

    def publish_map(self, stamp):
        grid = self.mapper.occupancy_map()
        if grid is None:
            return
        values, origin = grid
        msg = OccupancyGrid()
        msg.header.stamp = stamp
        msg.header.frame_id = self.p['map_frame']
        info = msg.info
        info.map_load_time = stamp
        info.resolution = self.p['delta']
        info.height, info.width = values.shape
        info.origin = pose_message(*origin)
        msg.data = values.reshape(-1).tolist()
        self.map_pub.publish(msg)
        self.meta_pub.publish(info)
        self.last_published = stamp
        rospy.logdebug('slam: map %dx%d after %d scans, %.1f ms CPU per scan', info.width,
                       info.height, self.mapper.scans, 1000.0 * self.cpu / self.mapper.scans)


def main():
    init_node('slam')
    try:
        node = SlamNode()
    except ValueError as err:
        rospy.logfatal('slam: cannot start: %s (check the launch file and config/slam.yaml)',
                       err)
        return 1
    rospy.spin()
    if node.mapper.scans:
        counts = node.mapper.counts
        rospy.loginfo('slam: %d scans, %d drawn into the map, %d matches not trusted, %d '
                      'relocations, %d loops closed, %.1f ms CPU per scan', node.mapper.scans,
                      node.mapper.drawn, counts['not trusted'], counts['relocated'],
                      counts['loops closed'], 1000.0 * node.cpu / node.mapper.scans)
    return 0
