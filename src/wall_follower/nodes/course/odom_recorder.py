"""The record_odom action server: records the robot's path for one lap.

Each goal starts a fresh LapRecorder at the goal's stamp. The odometry
callback feeds it every pose (so the distance is integrated at the odometry
rate), and the poses heard lately are replayed to it first: odometry stamped
after the goal may have come before the goal did. On wall time the goal's
stamp is moved onto the odometry's clock, which on a robot is another
machine's and need not agree with this one's. The goal's own
loop publishes feedback and the growing path whenever a point is added, and
ends the goal when the lap closes (succeeded), when the client cancels
(preempted, with the points so far) or when odometry stops coming
(aborted, with the points so far).

What the node survives, with one warning each: odometry that jumps (a
simulator's reset_positions, a robot's odometry reset) is not counted as
travel (see wall_follower.control.course.lap); a pose that is not finite or whose
orientation is no unit quaternion is skipped, and so is one stamped far
ahead of this node's clock (control.stamps: heard before a goal, it would
move the recording's start decades ahead, and recorded, it would be the
last point sampled); and ROS time moving backwards (a simulator
restarted, a bag looped) drops every pose heard on the old clock, aborts
the goal recorded on it, and the node goes on serving: its goal status
keeps coming, and the next goal starts from fresh odometry.

Each point is a geometry_msgs/Point holding x and y (m) in the odometry
frame and, in z, the yaw (rad): the course's (x, y, theta).
"""
import threading
import time
from collections import deque, namedtuple

import actionlib
import rospy
from actionlib.server_goal_handle import ServerGoalHandle
from geometry_msgs.msg import Point, PoseStamped
from nav_msgs.msg import Odometry, Path

from wall_follower.cfg import OdomRecorderConfig
from wall_follower.control.course.lap import LapRecorder
from wall_follower.control.course.odom_check import odometry_problem
from wall_follower.control.stamps import ahead_problem
from wall_follower.msg import OdomRecordAction, OdomRecordFeedback, OdomRecordResult
from wall_follower.nodes.shared.connections import keep_connected
from wall_follower.nodes.shared.messages import pose_message, pose_of
from wall_follower.nodes.shared.parameters import NodeParameters
from wall_follower.nodes.shared.startup import init_node
from wall_follower.params import pick
from wall_follower.params.course.odom_recorder import RECORDING, TABLE

# Odometry messages held while the node is busy: a minute and a half at 10 Hz.
ODOM_QUEUE = 1000
# Poses kept for a goal that comes after odometry stamped since it: ten seconds
# of the TurtleBot3's 30 Hz odometry.
RECENT_POSES = 300
# Seconds between the odometry's clock and this machine's past which a goal warns.
CLOCK_WARNING = 1.0
# Seconds (ROS time) between two warnings about malformed odometry.
MALFORMED_WARNING_PERIOD = 5.0


class RecordOdomServer(actionlib.SimpleActionServer):
    """A SimpleActionServer that can forget the goal it last served.

    It takes a goal only if stamped no earlier than the goals it took last
    (current and next, which stay set once done): once ROS time has moved
    backwards, every new goal would be refused for as long as the jump.
    before_goal() is called as each goal arrives, before that check, so
    that the node can forget the goals of the old clock.
    """

    def __init__(self, name, action_spec, execute_cb, before_goal):
        self._before_goal = before_goal
        actionlib.SimpleActionServer.__init__(self, name, action_spec, execute_cb=execute_cb,
                                              auto_start=False)

    def internal_goal_callback(self, goal):
        self._before_goal()
        actionlib.SimpleActionServer.internal_goal_callback(self, goal)

    def forget_finished_goal(self):
        """Forget the goals served, and the cancel requests; False while one is active or due."""
        with self.lock:
            if self.is_active() or self.is_new_goal_available():
                return False
            self.current_goal = ServerGoalHandle()
            self.next_goal = ServerGoalHandle()
            self.action_server.last_cancel = rospy.Time()
            return True


class OdomRecorderNode(object):
    """Serves record_odom: one recording per goal, fed from the odom topic."""

    def __init__(self):
        self.settings = NodeParameters(TABLE, OdomRecorderConfig)
        self.params = self.settings.snapshot()   # those in force for the current goal
        self._lock = threading.Lock()
        self._recording = None
        self._frame_id = ''
        # ROS time and wall time (monotonic) at which the recording last took a pose.
        self._last_odom_time = None
        self._last_odom_wall = None
        # The latest ROS time read, to see it move backwards.
        self._latest_time = None
        # How far (s) ROS time moved back under the current recording, if it did.
        self._time_moved_back = None
        # True from ROS time moving back until the goal served on the old clock is forgotten.
        self._goal_on_old_clock = False
        # (stamp, pose, lag behind this node's clock on arrival) of the latest poses.
        self._recent = deque(maxlen=RECENT_POSES)
        # On simulated time every node, the odometry's publisher too, reads /clock.
        self._one_clock = rospy.get_param('/use_sim_time', False)
        self.path_pub = rospy.Publisher('record_odom/path', Path, queue_size=1, latch=True)
        # Every pose counts toward the distance and may be the one a sample is due at;
        # a fast simulator can outrun this node for a while, and a full queue drops some.
        self.odom_sub = rospy.Subscriber('odom', Odometry, self._on_odom, queue_size=ODOM_QUEUE)
        keep_connected([self.odom_sub])
        self.server = RecordOdomServer('record_odom', OdomRecordAction, self._execute,
                                       self._before_goal)
        self.server.start()
        self._restart_status_timer()
        rospy.on_shutdown(self._stop_status_timer)
        rospy.loginfo('record_odom: ready (a point every %.1f s)', self.params['sample_period'])

    def _restart_status_timer(self):
        """Publish the goal status on a timer that survives ROS time moving backwards.

        actionlib's own timer is a rospy.Timer that raises on a backward
        jump: its thread ends, the status stops for good, and clients take
        the server for gone. With reset, it starts its period again instead.
        """
        server = self.server.action_server
        if server.status_timer is None:
            return
        server.status_timer.shutdown()
        server.status_timer = rospy.Timer(rospy.Duration(1.0 / server.status_frequency),
                                          server.publish_status_async, reset=True)

    def _stop_status_timer(self):
        """Stop actionlib's goal-status timer before rospy closes the topics.

        Its thread checks for shutdown and then publishes; a tick caught
        between the two raises "publish() to a closed topic" there, which
        prints a traceback as the node ends. Shutdown hooks run before the
        topics close, and holding the server's lock waits out a tick that
        is already publishing.
        """
        server = self.server.action_server
        if server.status_timer is not None:
            server.status_timer.shutdown()
        with server.lock:
            pass  # a tick that was publishing has now finished

    def _on_odom(self, msg):
        position, orientation = msg.pose.pose.position, msg.pose.pose.orientation
        problem = odometry_problem(position.x, position.y, orientation.x, orientation.y,
                                   orientation.z, orientation.w)
        if problem is not None:
            rospy.logwarn_throttle(MALFORMED_WARNING_PERIOD, 'record_odom: odometry on %s '
                                   'skipped: %s' % (rospy.resolve_name('odom'), problem))
            return
        pose = pose_of(msg)
        with self._lock:
            now = self._now()
            stamp = msg.header.stamp.to_sec() or now
            ahead = ahead_problem(stamp, now)
            if ahead is not None:
                rospy.logwarn_throttle(MALFORMED_WARNING_PERIOD, 'record_odom: odometry on %s '
                                       'skipped: %s' % (rospy.resolve_name('odom'), ahead))
                return
            self._frame_id = msg.header.frame_id
            self._recent.append((stamp, pose, now - stamp))
            if self._recording is not None:
                self._take(stamp, pose)

    def _now(self):
        """ROS time in seconds; when it has moved backwards, forget the old clock (lock held).

        Poses heard before are stamped on the old clock: replayed to a goal
        on the new one, they would be taken as recorded since it. The
        recording in progress started on the old clock and is ended by its
        goal's loop.
        """
        now = rospy.get_time()
        if self._latest_time is not None and now < self._latest_time:
            back = self._latest_time - now
            rospy.logwarn('record_odom: ROS time moved back %.2f s (a simulator restarted, a '
                          'bag looped?); forgetting the odometry heard before%s', back,
                          '; the goal in progress ends' if self._recording is not None else '')
            self._recent.clear()
            self._last_odom_time = self._last_odom_wall = None
            self._goal_on_old_clock = True
            if self._recording is not None:
                self._time_moved_back = back
        self._latest_time = now
        return now

    def _before_goal(self):
        """As a goal arrives: see whether ROS time moved back, and forget the old clock's goal."""
        with self._lock:
            self._now()
            if self._goal_on_old_clock and self.server.forget_finished_goal():
                self._goal_on_old_clock = False

    def _take(self, stamp, pose):
        """Feed the recording a pose if it is stamped since the goal (lock held)."""
        recording = self._recording
        if not recording.takes(stamp):
            return
        self._last_odom_time = self._latest_time
        self._last_odom_wall = time.monotonic()
        jumps = len(recording.jumps)
        recording.add(stamp, *pose)
        if len(recording.jumps) > jumps:
            _, distance = recording.jumps[-1]
            rospy.logwarn('record_odom: odometry on %s jumped %.2f m at %.2f s, further than '
                          'the robot can drive (~max_speed %.2f m/s); not counted as travel, '
                          'recording on from (%.2f, %.2f) with the lap\'s start kept (a reset?)',
                          rospy.resolve_name('odom'), distance, stamp, self.params['max_speed'],
                          pose[0], pose[1])

    def _recording_start(self):
        """When the goal was sent, on the odometry's clock (lock held).

        The goal's stamp is on the client's clock, taken to be this node's
        (the same machine, or synchronized ones); a goal sent without one
        starts now. On wall time the odometry may be stamped by a robot whose
        clock is off by seconds or hours. Its poses would then be skipped
        until its clock reached the goal's stamp, or replayed from long
        before the goal; so the stamp is shifted by the odometry's least lag
        behind this clock on arrival: the clocks' offset, plus the smallest
        delivery delay.
        """
        start = self.server.current_goal.get_goal_id().stamp.to_sec() or self._now()
        if self._one_clock or not self._recent:
            return start
        offset = min(lag for _, _, lag in self._recent)
        if abs(offset) > CLOCK_WARNING:
            rospy.logwarn('record_odom: odometry on %s is stamped %.1f s %s this clock; '
                          'recording from the goal by this clock (synchronize the clocks, '
                          'e.g. with chrony, for tf and rviz)', rospy.resolve_name('odom'),
                          abs(offset), 'behind' if offset > 0.0 else 'ahead of')
        return start - offset

    def _new_recording(self, start):
        return LapRecorder(self.params['sample_period'], start=start,
                           **pick(self.params, RECORDING))

    def _execute(self, _goal):
        self.params = self.settings.snapshot()
        with self._lock:
            self._now()
            recording = self._new_recording(self._recording_start())
            self._recording = recording
            self._time_moved_back = None
            for stamp, pose, _ in self._recent:
                self._take(stamp, pose)
        rospy.loginfo('record_odom: recording started')
        try:
            self._serve(recording)
        except rospy.ROSInterruptException:
            with self._lock:
                points = list(recording.points)
            self.server.set_aborted(_result(points), 'shutting down')
        finally:
            with self._lock:
                self._recording = None
                self._time_moved_back = None

    def _serve(self, recording):
        """Publish progress until the goal ends, and end it the way it ended."""
        started, started_wall = rospy.get_time(), time.monotonic()
        published = 0
        # reset: ROS time moving back is seen and answered below, not raised here.
        rate = rospy.Rate(self.params['rate'], reset=True)
        while True:
            with self._lock:
                now = self._now()
                # Silent in wall time too: a simulation running faster than real time
                # can outrun this node's odometry queue for a few simulated seconds.
                progress = _Progress(
                    list(recording.points), recording.total_distance, recording.closed,
                    self._time_moved_back, self._frame_id,
                    min(_silence(now, started, self._last_odom_time),
                        _silence(time.monotonic(), started_wall, self._last_odom_wall)))
            if len(progress.points) > published:
                published = len(progress.points)
                self.server.publish_feedback(OdomRecordFeedback(current_total=progress.total))
                self.path_pub.publish(_path(progress.points, progress.frame_id))
            if self._ended(progress, recording.start):
                return
            rate.sleep()

    def _ended(self, progress, start):
        """End the goal if its lap closed, its clock moved back, it was cancelled or its
        odometry fell silent for ~timeout; True if it did."""
        points, total = progress.points, progress.total
        if progress.closed:
            rospy.loginfo('record_odom: lap complete: %d points, %.2f m', len(points), total)
            self.server.set_succeeded(_result(points), 'lap complete: %.2f m' % total)
        elif progress.time_moved_back is not None:
            text = ('ROS time moved back %.2f s: the recording is on the old clock; '
                    'send a new goal' % progress.time_moved_back)
            rospy.loginfo('record_odom: aborted: %s', text)  # warned of already
            self.server.set_aborted(_result(points), text)
        elif self.server.is_preempt_requested():
            rospy.loginfo('record_odom: cancelled after %d points, %.2f m', len(points), total)
            self.server.set_preempted(_result(points), 'cancelled after %.2f m' % total)
        elif progress.silent > self.params['timeout']:
            text = 'no odometry on %s stamped since the goal (%.1f s) for %.1f s' % (
                rospy.resolve_name('odom'), start, self.params['timeout'])
            rospy.logerr('record_odom: aborted: %s', text)
            self.server.set_aborted(_result(points), text)
        else:
            return False
        return True


_Progress = namedtuple('_Progress', 'points total closed time_moved_back frame_id silent')
"""A goal's recording as its loop sees it at one pass; silent: seconds since the last pose."""


def _silence(now, started, last):
    """Seconds since the pose last taken at `last`, or since the goal `started` without one."""
    return now - (started if last is None or last < started else last)


def _result(points):
    return OdomRecordResult(list_of_odoms=[Point(x, y, yaw) for x, y, yaw in points])


def _path(points, frame_id):
    """The recorded points as a nav_msgs/Path, for rviz."""
    path = Path()
    path.header.stamp = rospy.Time.now()
    path.header.frame_id = frame_id
    path.poses = [PoseStamped(header=path.header, pose=pose_message(x, y, yaw))
                  for x, y, yaw in points]
    return path


def main():
    init_node('odom_recorder')
    OdomRecorderNode()
    rospy.spin()
