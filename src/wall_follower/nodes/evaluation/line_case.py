"""One graded line-following run: watches the base on the course's line and writes its record.

Started by `grade --task line` (launch/line_case.launch) beside the
simulator, on a master of the case's own, before the solution's launch
file. The simulator starts paused; this node lets it run once it hears
ground truth, keeps every true pose of the base and every command the
solution sends, and ends the run when:

- a closed line is lapped, or the base, having moved, stood still for
  ~still simulated seconds (on an open line: its stop; on a closed one:
  it gave up);
- the base never moved in ~idle_limit simulated seconds, nothing was
  commanded for as long (or the robot stalled against a wall), or none of
  the solution's nodes is alive (after ~start_limit wall seconds to start
  them, for ~gone_limit);
- ~time_limit simulated seconds passed.

Then it pauses the world, writes the record (~json;
evaluation/grading/line_record.py, graded by line_criteria.py) and the plot
(~plot), and ends, which ends the launch. A world whose course file cannot
be read, or a simulator that sends no ground truth, is the grader's error
('grader_error' in the record), never the solution's. Stopped by a signal
while it still waits, it writes no record and ends quietly with status 0
(nodes/shared/shutdown.py).
"""
import threading
import time

import numpy as np
import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from std_msgs.msg import Bool

from wall_follower.evaluation.grading.line_criteria import END_DISTANCE
from wall_follower.evaluation.grading.line_record import (Commands, first_motion, lap_index,
                                                          run_record, still_from)
from wall_follower.evaluation.pictures.line_plot import plot_line_run
from wall_follower.evaluation.scoring.line_track import (CourseError, centreline_of, course_path,
                                                         read_course)
from wall_follower.evaluation.worlds.line_courses import describe_camera, camera_from_keys
from wall_follower.nodes.shared.case_graph import (GONE, GRAPH_POLL, NO_SIMULATOR, SERVICE_WAIT,
                                                   Graph, SolutionGone, call_simulator,
                                                   grader_failed, solution_running,
                                                   wait_for_simulator, write_record)
from wall_follower.nodes.shared.connections import keep_connected
from wall_follower.nodes.shared.messages import pose_of
from wall_follower.nodes.shared.parameters import NodeParameters
from wall_follower.nodes.shared.shutdown import quiet_on_shutdown, raise_if_shut_down
from wall_follower.nodes.shared.startup import init_node
from wall_follower.params.evaluation.line_case import TABLE

# Wall seconds between looks at the run.
POLL = 0.2
QUEUE = 1000


class Run(object):
    """The base's true poses (t, x, y, yaw), the commands, and where it first stalled."""

    def __init__(self):
        self.lock = threading.Lock()
        self.poses = []
        self.commands = Commands()
        self.stalled_since = None
        self.contact = None
        self._subs = [
            rospy.Subscriber('base_pose_ground_truth', Odometry, self._on_truth,
                             queue_size=QUEUE),
            rospy.Subscriber('cmd_vel', Twist, self._on_command, queue_size=QUEUE),
            rospy.Subscriber('stalled', Bool, self._on_stalled, queue_size=QUEUE)]
        keep_connected(self._subs)

    def _on_truth(self, msg):
        with self.lock:
            self.poses.append((msg.header.stamp.to_sec(),) + tuple(pose_of(msg)))

    def _on_command(self, msg):
        values = {'linear.x': msg.linear.x, 'linear.y': msg.linear.y, 'linear.z': msg.linear.z,
                  'angular.x': msg.angular.x, 'angular.y': msg.angular.y,
                  'angular.z': msg.angular.z}
        with self.lock:
            self.commands.add(rospy.get_time(), values)

    def _on_stalled(self, msg):
        with self.lock:
            if not msg.data:
                self.stalled_since = None
                return
            now = rospy.get_time()
            self.stalled_since = now if self.stalled_since is None else self.stalled_since
            if self.contact is None and self.poses:
                _, x, y, _ = self.poses[-1]
                self.contact = {'time': now, 'x': x, 'y': y}

    def connected(self):
        """Whether ground truth and the commands are connected (the simulator is up)."""
        return all(sub.get_num_connections() > 0 for sub in self._subs)

    def trail(self):
        with self.lock:
            return np.array(self.poses, dtype=float).reshape(-1, 4)

    def close(self):
        for sub in self._subs:
            sub.unregister()


def run_over(centreline, run, params, start):
    """(why the run is over, in words, or None while it goes on; whether the reason is that
    nothing was commanded, which may be the solution's nodes all gone)."""
    poses = run.trail()
    now = rospy.get_time()
    if len(poses) and centreline.closed and lap_index(centreline, poses) is not None:
        return 'a lap', False
    if len(poses) and still_from(poses, params['still']) is not None:
        return 'the base stood still for %g simulated s' % params['still'], False
    if now - start > params['idle_limit'] and first_motion(poses) is None:
        return 'the base never moved in %g simulated s' % params['idle_limit'], False
    with run.lock:
        latest, stalled = run.commands.latest, run.stalled_since
    if now - (latest if latest is not None else start) > params['idle_limit']:
        return 'no command for %g simulated s: the solution hangs' % params['idle_limit'], True
    if stalled is not None and now - stalled > params['idle_limit']:
        return 'stuck against a wall for %g simulated s' % params['idle_limit'], False
    if now - start > params['time_limit']:
        return 'no %s within %.0f simulated s' % (
            'lap' if centreline.closed else 'stop', params['time_limit']), False
    return None, False


def watch(centreline, run, graph, params, start):
    """Why the run ended: run_over's reason, or GONE; rospy.ROSInterruptException if rospy
    shuts down first (the run has not ended)."""
    gone = SolutionGone(graph, params['start_limit'], params['gone_limit'])
    next_graph = time.monotonic()
    while True:
        raise_if_shut_down()
        reason, idle = run_over(centreline, run, params, start)
        if reason:
            return GONE if idle and not solution_running(graph) else reason
        if time.monotonic() >= next_graph:
            next_graph = time.monotonic() + GRAPH_POLL
            if gone.look():
                return GONE
        time.sleep(POLL)


@quiet_on_shutdown
def main():
    init_node('line_case')
    params = NodeParameters(TABLE).snapshot()
    course_file = course_path(params['world'])
    try:
        course = read_course(course_file)
        centreline = centreline_of(course, course_file)
    except CourseError as err:
        return grader_failed(params, 'cannot read the course: %s' % err, task='line')
    run = Run()
    # The course's view of the graph; of it only the solution's nodes are looked at here.
    graph = Graph('record_odom')
    if not wait_for_simulator(run.connected):
        return grader_failed(params, NO_SIMULATOR, task='line')
    call_simulator('unpause_physics', wait=SERVICE_WAIT)
    start = rospy.get_time()
    end_reason = watch(centreline, run, graph, params, start)
    call_simulator('pause_physics')
    run.close()
    poses = run.trail()
    rospy.loginfo('line_case: run ended: %s', end_reason)
    record = run_record(centreline, course, poses, params['still'], run.commands)
    camera = camera_from_keys(course.get('camera'))
    record.update(task='line', world=params['world'], kind=course.get('kind'),
                  camera=describe_camera(camera) if camera else None, end_reason=end_reason,
                  contact=run.contact, still=params['still'], plot=params['plot'] or None)
    if not write_record(params['json'], record):
        return 1
    if params['plot']:
        plot_line_run(centreline, poses, record, params['plot'],
                      title='%s: %s' % (params['world'].rsplit('/', 1)[-1], end_reason),
                      end_distance=END_DISTANCE)
    return 0
