"""The wall_following node: find_wall, then record_odom, then follow the right wall.

The controller answers each scan through the DriveLoop that every driving
node shares: at once, re-sent after ~keepalive, and stopped while the scan
is stale or unusable or the way ahead unseen. Every command leaves through
VelocityCommander, which clamps it to ~max_linear and ~max_angular and
stops the robot on shutdown.

Exit status: 0 after a recorded lap (with ~stop_after_lap) or a plain
shutdown; 1 when find_wall or record_odom is missing, find_wall fails, or
record_odom aborts the lap (its odometry stopped, say).
"""
import time

import actionlib
from actionlib.action_client import CommState
import rospy
from actionlib_msgs.msg import GoalStatus

from wall_follower.action_registration import action_server_registered
from wall_follower.cfg import WallFollowingConfig
from wall_follower.control.following.follower import FollowerParams, WallFollower
from wall_follower.msg import OdomRecordAction, OdomRecordGoal
from wall_follower.nodes.shared.course_markers import CourseMarkers
from wall_follower.nodes.shared.drive_loop import drive_loop, take_retuned
from wall_follower.nodes.shared.laser_mount import laser_x
from wall_follower.nodes.shared.latest_scan import LatestScan
from wall_follower.nodes.shared.parameters import NodeParameters
from wall_follower.nodes.shared.startup import init_node
from wall_follower.nodes.shared.waiting import wait_in_wall_time
from wall_follower.params import pick
from wall_follower.params.course.wall_following import FOLLOWER, NODE, TABLE
from wall_follower.srv import FindWall


LAP_RECORDED = 'lap recorded'
RECORDING_FAILED = 'recording failed'
# Wall seconds between two looks at the clock while it catches up with the laser.
CLOCK_POLL = 0.005


class WallFollowingNode(object):
    """The follower's ROS wiring: scan in, clamped cmd_vel out, plus the two clients."""

    def __init__(self):
        # ~laser_x if set, else read from tf, once the given values have passed.
        self.params = NodeParameters(TABLE, WallFollowingConfig, found={'laser_x': laser_x})
        values = self.params.snapshot()
        self.node = pick(values, NODE)
        self.controller = WallFollower(FollowerParams(**pick(values, FOLLOWER)))
        self._state = None
        self.loop = drive_loop('wall_following', values, LatestScan('scan'))
        self.ended = None   # LAP_RECORDED or RECORDING_FAILED, set by the action's thread
        self._recorder = None
        self._recording = None
        self._distance = 0.0
        self.markers = CourseMarkers()
        self.markers.show_band(values['laser_x'])

    def find_wall(self):
        """Call find_wall and wait for its answer; True when the wall is on the right."""
        name = rospy.resolve_name('find_wall')
        rospy.loginfo('wall_following: waiting for the %s service', name)
        try:
            rospy.wait_for_service(name, timeout=self.node['service_wait'])
        except rospy.ROSInterruptException:
            return False    # shut down while waiting
        except rospy.ROSException:
            rospy.logerr('wall_following: no %s service after %.0f s; is wall_finder running?',
                         name, self.node['service_wait'])
            return False
        try:
            found = rospy.ServiceProxy(name, FindWall)().wallfound
        except rospy.ServiceException as error:
            rospy.logerr('wall_following: %s failed: %s', name, error)
            return False
        self.markers.show_find_wall(found)
        if not found:
            rospy.logerr('wall_following: %s found no wall; not following', name)
        return found

    def start_recording(self):
        """Send the record_odom goal; False when the action server never appears."""
        name = rospy.resolve_name('record_odom')
        rospy.loginfo('wall_following: waiting for the %s action server', name)
        on_sim_time = rospy.get_param('/use_sim_time', False)
        if not self._wait_for_recorder(name):
            # One message that names the missing server and its likeliest cause.
            if on_sim_time and rospy.get_time() == 0.0:
                hint = '/use_sim_time is set and no /clock has come; is the simulator running?'
            else:
                hint = 'is odom_recorder running?'
            rospy.logerr('wall_following: no %s action server after %.0f s; %s', name,
                         self.node['service_wait'], hint)
            return False
        # On wall time the laser may stamp by the robot's clock, not this machine's:
        # record_odom allows for that offset, and there is no clock to wait for.
        if on_sim_time and not wait_in_wall_time(self._clock_at_newest_scan,
                                                 self.node['service_wait']):
            rospy.logerr('wall_following: no scan on %s, or ROS time short of its stamp, after '
                         '%.0f s; not recording', self.loop.source.topic,
                         self.node['service_wait'])
            return False
        # The goal handle is kept so that the goal stays tracked; the callbacks
        # use the handle they are given, as they can run before send_goal returns.
        self._recording = self._recorder.send_goal(OdomRecordGoal(), self._on_transition,
                                                   self._on_feedback)
        rospy.loginfo('wall_following: recording odometry on %s', name)
        return True

    def _wait_for_recorder(self, name):
        """Connect to the server of action `name` within service_wait seconds of wall time,
        whatever the ROS clock does.

        actionlib's own time-out is counted in ROS time, which stands still
        on simulated time until a /clock comes: that wait never ended. The
        client is made once the server is registered (action_server_registered
        says why).
        """
        deadline = time.monotonic() + self.node['service_wait']
        if action_server_registered(name, self.node['service_wait']):
            self._recorder = actionlib.ActionClient(name, OdomRecordAction)
            if wait_in_wall_time(self._recorder.wait_for_server, deadline - time.monotonic()):
                return True
        return False

    def _clock_at_newest_scan(self):
        """Block until a scan has come and this node's ROS time has reached its stamp.

        On simulated time only. The goal is stamped with this node's ROS
        time, and the lap is counted from that stamp. This node's clock can
        lag the world's, when its /clock connection is slow to come up or the node
        is starved of CPU: a goal stamped then would date the lap's start
        back to before find_wall moved the robot. The scan's stamp is the
        world's time when it was taken, so a clock that has reached it is
        no longer behind the robot.
        """
        warned = False
        while not rospy.is_shutdown():
            taken = self.loop.source.taken()
            if taken is not None:
                now = rospy.Time.now()
                if now >= taken:
                    return True
                if not warned:
                    rospy.loginfo('wall_following: waiting for ROS time (%.3f s) to reach the '
                                  'newest scan (%.3f s) before recording', now.to_sec(),
                                  taken.to_sec())
                    warned = True
            time.sleep(CLOCK_POLL)
        return False

    def _on_feedback(self, _goal, feedback):
        self._distance = feedback.current_total
        rospy.loginfo_throttle(self.node['feedback_period'],
                               'wall_following: %.2f m travelled' % feedback.current_total)

    def _on_transition(self, goal):
        """The goal's result once it is done.

        A plain ActionClient rather than SimpleActionClient: the simple one
        compares each transition with the goal handle it stores when
        send_goal returns, and a server answering before that logs an error
        and loses the transition (ros/actionlib#206).
        """
        if goal.get_comm_state() == CommState.DONE:
            self._on_recorded(goal)

    def _on_recorded(self, goal):
        """Stop after a recorded lap (with stop_after_lap), or when the recording failed.

        record_odom aborts a goal when odometry stops or jumps back in time:
        the base that reports it may be gone, and there is no lap left to
        drive for, so the robot stops. A goal cancelled by someone else only
        ends the recording.
        """
        state = goal.get_goal_status()
        if state == GoalStatus.ABORTED:
            rospy.logerr('wall_following: record_odom aborted the lap (%s); stopping',
                         goal.get_goal_status_text())
            self.ended = RECORDING_FAILED
        elif state != GoalStatus.SUCCEEDED:
            rospy.logwarn('wall_following: record_odom ended without a lap (%s); '
                          'following on', GoalStatus.to_string(state))
        else:
            result = goal.get_result()
            points = len(result.list_of_odoms) if result is not None else 0
            rospy.loginfo('wall_following: lap recorded: %d points, %.2f m', points,
                          self._distance)
            if self.node['stop_after_lap']:
                self.ended = LAP_RECORDED

    def follow(self):
        """Answer each scan until shutdown, the recorded lap (stop_after_lap) or a failed one."""
        self.loop.run(self._answer, lambda: self.ended, on_clock_reset=self._restart_controller)

    def _answer(self, view, taken):
        values = take_retuned(self.params, self.loop)
        if values is not None:
            self.node = pick(values, NODE)
            self.controller.reconfigure(FollowerParams(**pick(values, FOLLOWER)))
        command = self.controller.update(view, taken)
        if self.controller.state != self._state:
            rospy.loginfo('wall_following: %s -> %s', self._state, self.controller.state)
            self._state = self.controller.state
        return command

    def _restart_controller(self):
        """A controller that timed its corners on the old clock starts afresh."""
        self.controller = WallFollower(self.controller.params)
        self._state = None


def main():
    init_node('wall_following')
    node = WallFollowingNode()
    try:
        if node.node['find_wall'] and not node.find_wall():
            return 1
        if node.node['record_odom'] and not node.start_recording():
            return 1
        rospy.loginfo('wall_following: following the wall on the right')
        node.follow()
    except rospy.ROSInterruptException:
        pass
    if node.ended == LAP_RECORDED:
        rospy.signal_shutdown('lap recorded')
    return 1 if node.ended == RECORDING_FAILED else 0
