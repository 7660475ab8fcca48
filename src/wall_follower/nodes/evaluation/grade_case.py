"""One graded run: watches a solution's course from ground truth and writes its record.

Started by `grade` (launch/grade_case.launch) beside the simulator, on a
master of the case's own, before the solution's launch file. The simulator
starts paused; this node lets it run once it hears ground truth, as the
course has the simulation running before the solution starts, and notes
what the solution advertises (a find_wall service, the record_odom
action) as it comes. It ends the run when the action's result
has come (and ~after_result more simulated seconds of ground truth, to see
where the robot truly went), or when the solution cannot finish any more:
~time_limit simulated seconds passed, nothing commanded (or the robot
stalled against an obstacle) for ~idle_limit,
or none of its nodes alive for ~gone_limit wall seconds (once its launch
file has had ~start_limit wall seconds to start them). Then it writes
the record (~json) that wall_follower.evaluation.grading.criteria grades, and the
plot of the true path (~plot), and ends, which ends the launch.

Everything scored comes from the simulator's ground truth and the world
map (CourseMonitor), never from the solution's own topics; from the
solution only the action's messages count, as what it declared, and what
it commanded on cmd_vel (every command: a non-finite one, and those the
simulator's watchdog cut, as the simulator's odometry shows what it applied,
see evaluation/grading/commands.py). find_wall
is judged where its call replied, seen from the service's own TCP
connection (evaluation/grading/service_calls.py), in the case's network
namespace.

When the run cannot even begin for the grader's own reasons (the world
file unreadable, no ground truth from the simulator), the record says so
in 'grader_error', and grading counts the case as not graded rather than
as the solution's failure. Stopped by a signal while it still waits (grade
ending the case at its --timeout, or interrupted), it writes no record at all
and ends quietly with status 0 (nodes/shared/shutdown.py): it has seen
nothing to blame on the solution, nor on the simulator.
"""
import math
import threading
import time

import rosgraph
import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from std_msgs.msg import Bool

from actionlib_msgs.msg import GoalStatus

from wall_follower.evaluation.grading.commands import CommandLog
from wall_follower.evaluation.grading.criteria import find_wall_fits
from wall_follower.evaluation.grading.service_calls import PortWatch, connected_peers, reply_moment
from wall_follower.evaluation.pictures.course_plot import plot_course
from wall_follower.evaluation.scoring.course import CourseMap, true_lap_length
from wall_follower.nodes.evaluation.course_report import course_figures
from wall_follower.nodes.shared.case_graph import (GONE, GRAPH_POLL, NO_SIMULATOR, SERVICE_WAIT,
                                                   Graph, SolutionGone, call_simulator,
                                                   grader_failed, solution_running,
                                                   wait_for_simulator, write_record)
from wall_follower.nodes.shared.connections import keep_connected
from wall_follower.nodes.shared.course_monitor import QUEUE, CourseMonitor
from wall_follower.nodes.shared.parameters import NodeParameters
from wall_follower.nodes.shared.shutdown import (poll_until, quiet_on_shutdown,
                                                 raise_if_shut_down)
from wall_follower.nodes.shared.startup import init_node
from wall_follower.params.evaluation.grade_case import TABLE
from wall_follower.rotation import wrap_angle
from wall_follower.sim.worldfile import WorldFileError

# Wall seconds between looks at the run and at find_wall's connections (the graph:
# case_graph.GRAPH_POLL).
POLL = 0.1
CALL_POLL = 0.01
# The find_wall calls a record keeps.
CALLS_KEPT = 10
# The robot "moved before the lap" when the lap began this far from the start [m, rad].
MOVED = (0.05, math.radians(10.0))
# The longest stretches out of band a record keeps.
OUT_OF_BAND_KEPT = 3
STATUS_NAMES = {GoalStatus.SUCCEEDED: 'succeeded', GoalStatus.ABORTED: 'aborted',
                GoalStatus.PREEMPTED: 'preempted', GoalStatus.REJECTED: 'rejected',
                GoalStatus.RECALLED: 'recalled', GoalStatus.LOST: 'lost'}


class RunClock(object):
    """Simulated times of the first and the latest cmd_vel, since when the robot is stalled,
    and every command with the velocity the simulator applied at each step, odometry's
    twist (a CommandLog, against the simulator's watchdog)."""

    def __init__(self):
        self.first = None
        self.latest = None
        self.stalled_since = None
        self.commands = CommandLog(rospy.get_param('simulator/base_watchdog_timeout', 0.2))
        self._odometry = rospy.Subscriber('odom', Odometry, self._on_odometry, queue_size=QUEUE)
        self._subs = [rospy.Subscriber('cmd_vel', Twist, self._on_command, queue_size=1000),
                      rospy.Subscriber('stalled', Bool, self._on_stalled, queue_size=100),
                      self._odometry]
        keep_connected(self._subs)

    def connected(self):
        """Whether odometry is heard: without it, the watchdog's cuts go unseen."""
        return self._odometry.get_num_connections() > 0

    def _on_command(self, msg):
        now = rospy.get_time()
        if self.first is None:
            self.first = now
        self.latest = now
        self.commands.add(now, msg.linear.x, msg.angular.z)

    def _on_odometry(self, msg):
        twist = msg.twist.twist
        self.commands.applied(msg.header.stamp.to_sec(), twist.linear.x, twist.angular.z)

    def _on_stalled(self, msg):
        if not msg.data:
            self.stalled_since = None
        elif self.stalled_since is None:
            self.stalled_since = rospy.get_time()


class FindWallWatch(object):
    """The calls of the solution's find_wall service, from the namespace's TCP connections
    (see evaluation/grading/service_calls.py; every port's, watched from the start, so
    that a call that ended before the service was seen in the graph counts), with the
    robot's true pose at each start and end."""

    def __init__(self, monitor):
        self.watch = PortWatch()
        self._monitor = monitor
        self._port = None
        self._lock = threading.Lock()
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run)
        self._thread.daemon = True
        self._thread.start()

    def found(self, service):
        """The service is advertised: watch its port."""
        if self._port is not None or service is None:
            return
        try:
            uri = rosgraph.Master(rospy.get_name()).lookupService(service)
            self._port = int(uri.rsplit(':', 1)[1].strip('/'))
        except (rosgraph.MasterError, OSError, ValueError, IndexError):
            rospy.logwarn('grade_case: cannot find the port of %s: its calls are not seen',
                          service)

    def _run(self):
        while not self._stop.wait(CALL_POLL):
            before = self._moment()
            peers = connected_peers()
            after = self._moment()
            with self._lock:
                self.watch.look(peers, before, after)

    def _moment(self):
        """(simulated time, the robot's latest true pose) now."""
        return rospy.get_time(), self._monitor.pose

    def stop(self):
        self._stop.set()
        self._thread.join(1.0)

    def record(self, course_map, start):
        """The judged call (CallWatch.judged) as the record keeps it, None without one: its
        times (s since the start), how far the robot went in it, and the wall beside the
        robot when it replied (service_calls.reply_moment)."""
        with self._lock:
            watch = self.watch.of(self._port)
            call = watch.judged()
            count = len(watch.calls)
            calls = [(c['start'] - start, c['end'] - start) for c in watch.calls[:CALLS_KEPT]]
        moment = None if call is None or call['start_pose'] is None else reply_moment(
            call, course_map.right_wall_alignment,
            self._monitor.poses_between(call['last_open'], call['end']), find_wall_fits)
        if moment is None:
            return None
        replied, pose, aligned = moment
        first = call['start_pose']
        return {'called': call['start'] - start, 'replied': replied - start,
                'seconds': replied - call['start'],
                'reply_within': call['end'] - call['last_open'],
                'moved': math.hypot(pose[0] - first[0], pose[1] - first[1]),
                'turned_deg': abs(math.degrees(wrap_angle(pose[2] - first[2]))),
                'distance': aligned[0] if aligned else float('nan'),
                'heading_error_deg': math.degrees(aligned[1]) if aligned else float('nan'),
                'calls': count, 'all': calls}


class SolutionSeen(object):
    """What the graph has shown of the solution so far: its find_wall service and action."""

    def __init__(self):
        self.find_wall_service = None
        self.action_server = False

    def look(self, graph, state):
        self.find_wall_service = self.find_wall_service or graph.find_wall_service(state)
        self.action_server = self.action_server or graph.action_server(state)


def watch(monitor, graph, seen, clock, params, start, calls):
    """Why the run ended: 'result', or the reason no lap can come any more;
    rospy.ROSInterruptException if rospy shuts down first (the run has not ended).

    Meanwhile notes in seen what the solution advertises. The solution's
    nodes count as gone only after ~start_limit wall seconds, the time
    its launch file has to start them; but a run that ends idle with none
    of them running ended because they are gone, not because they hang
    (in lockstep, simulated time may pass the idle limit first).
    """
    gone = SolutionGone(graph, params['start_limit'], params['gone_limit'])
    next_graph = time.monotonic()
    while True:
        raise_if_shut_down()
        if monitor.done.is_set():
            return 'result'
        now = rospy.get_time()
        if now - start > params['time_limit']:
            return 'no lap within %.0f simulated s' % params['time_limit']
        if now - (clock.latest if clock.latest is not None else start) > params['idle_limit']:
            if not solution_running(graph):
                return GONE
            return 'no command for %.0f simulated s: the solution hangs' % params['idle_limit']
        if clock.stalled_since is not None and now - clock.stalled_since > params['idle_limit']:
            return 'stuck against an obstacle for %.0f simulated s' % params['idle_limit']
        if time.monotonic() >= next_graph:
            next_graph = time.monotonic() + GRAPH_POLL
            state = graph.state()
            seen.look(graph, state)
            calls.found(seen.find_wall_service)
            if gone.look(state):
                return GONE
        time.sleep(POLL)


def keep_watching(monitor, seconds, wall_limit=30.0):
    """Ground truth for `seconds` more simulated seconds (at most wall_limit wall seconds);
    rospy.ROSInterruptException if rospy shuts down first: a record cut short would
    misjudge where the robot went."""
    monitor.wait(catch_up=10.0)
    end = rospy.get_time() + seconds
    poll_until(lambda: rospy.get_time() >= end, wall_limit, period=POLL)


def freeze(monitor):
    """Stop the world and stop listening, so that the record is of one moment.

    Scoring a long run takes seconds, in which a world in lockstep would
    go on for minutes of simulated time, and a result could still come.
    """
    call_simulator('pause_physics')
    monitor.close()


def case_record(monitor, params, seen, end_reason, start, start_pose, clock, calls=None,
                end_time=None):
    """The case's ground-truth record, as grading.grade_case reads it.

    find_wall is judged where its call replied (find_wall_call, from
    calls: a FindWallWatch), else, never called, where the lap began, else
    where the robot ended (at end_time, simulated s).
    """
    figures = course_figures(monitor)
    goal_pose = monitor.goal_pose
    call = calls.record(monitor.score.map, start) if calls else None
    if call is not None:
        figures['found_distance'] = call['distance']
        figures['found_heading_error_deg'] = call['heading_error_deg']
    elif goal_pose is None and monitor.pose is not None:
        # No lap began: judge find_wall where the robot ended.
        aligned = monitor.score.map.right_wall_alignment(monitor.pose)
        figures['found_distance'] = aligned[0] if aligned else float('nan')
        figures['found_heading_error_deg'] = math.degrees(aligned[1]) if aligned else float('nan')
    judged_pose = goal_pose if goal_pose is not None else monitor.pose
    moved = judged_pose is not None and start_pose is not None and (
        math.hypot(judged_pose[0] - start_pose[0], judged_pose[1] - start_pose[1]) > MOVED[0]
        or abs(wrap_angle(judged_pose[2] - start_pose[2])) > MOVED[1])
    true_lap = None
    with monitor.lock:
        if goal_pose is not None:
            true_lap = true_lap_length(list(monitor.trail), goal_pose[:2])
        feedback = list(monitor.feedback)
        stretches = monitor.score.stretches_out_of_band()[:OUT_OF_BAND_KEPT]
    out_of_band = [{'after': after, 'seconds': seconds, 'x': pose[0], 'y': pose[1],
                    'distance': distance,
                    'grid_distance': monitor.score.map.grid_right_wall_distance(worst)}
                   for after, seconds, pose, distance, worst in stretches]
    return {
        'world': params['world'],
        'solution': {'find_wall_service': seen.find_wall_service,
                     'action_server': seen.action_server,
                     'result_point_type': monitor.result_point_type},
        'end_reason': end_reason,
        'start_time': start,
        'goal_time': monitor.goal_time,
        'end_time': end_time,
        'find_wall_call': call,
        'find_wall_time': (call['seconds'] if call is not None
                           else (monitor.goal_time - start) if monitor.goal_time is not None
                           else None),
        'commands': clock.commands.record(),
        'first_command_time': clock.first,
        'result_time': monitor.result_time,
        'result_status': (STATUS_NAMES.get(monitor.result_status, str(monitor.result_status))
                          if monitor.result_status is not None else None),
        'moved_before_lap': bool(moved),
        'declared_distance': monitor.truth_at_result,
        'true_lap': true_lap,
        'recorded_spans': monitor.recorded_spans,
        'feedback_rising': all(b >= a for a, b in zip(feedback, feedback[1:])),
        'figures': figures,
        'out_of_band': out_of_band,
        'plot': params['plot'] or None,
    }


@quiet_on_shutdown
def main():
    init_node('grade_case')
    params = NodeParameters(TABLE).snapshot()
    try:
        course_map = CourseMap(params['world'])
    except (WorldFileError, EnvironmentError) as err:
        return grader_failed(params, 'cannot read world %s: %s' % (params['world'], err))
    monitor = CourseMonitor(course_map, start_on_goal=True, action_ns=params['action_ns'])
    clock = RunClock()
    graph = Graph(params['action_ns'])
    if not wait_for_simulator(lambda: monitor.connected(('base_pose_ground_truth',))
                              and clock.connected()):
        return grader_failed(params, NO_SIMULATOR)
    call_simulator('unpause_physics', wait=SERVICE_WAIT)
    start = rospy.get_time()
    poll_until(lambda: monitor.pose is not None, math.inf, period=0.01)
    start_pose = monitor.pose
    seen = SolutionSeen()
    calls = FindWallWatch(monitor)
    end_reason = watch(monitor, graph, seen, clock, params, start, calls)
    calls.stop()
    rospy.loginfo('grade_case: run ended: %s; find_wall service: %s; %s action: %s', end_reason,
                  seen.find_wall_service or 'none', params['action_ns'],
                  'up' if seen.action_server else 'none')
    if end_reason == 'result':
        keep_watching(monitor, params['after_result'])
    freeze(monitor)
    record = case_record(monitor, params, seen, end_reason, start, start_pose, clock, calls,
                         rospy.get_time())
    if not write_record(params['json'], record):
        return 1
    if params['plot']:
        spans = record['recorded_spans']
        plot_course(course_map, monitor.full_trail(), monitor.result, params['plot'],
                    title=params['world'].rsplit('/', 1)[-1], start=start_pose,
                    points_span=spans[-1][0] - spans[0][0] if spans else None)
    return 0
