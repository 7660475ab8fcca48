"""The end of `main.launch report:=true`: a scored summary of the lap and its plot.

The follower already logs the search and the lap's progress; this node
waits for the record_odom result, then prints what the robot recorded next
to what really happened (ground truth, scored against the map), saves the
plot and ends, which ends the launch (it is the launch's required node).

When no lap can come (the follower has ended, because find_wall failed or
for any other reason, or record_odom ended its goal without a lap) it says
so and exits with status 1 instead of waiting for ever, and writes no plot
or figures: those exist only for a recorded lap. (roslaunch itself exits 0
whatever its required node's status; tools/run-main checks for the plot.)
Stopped by a signal (Ctrl-C, the launch ending) while it waits, it ends
quietly with status 0 and no plot (nodes/shared/shutdown.py): that is no
failure of the simulator or the follower.

Parameters: the table in wall_follower.params.evaluation.course_report, read once at
start.
"""
import json
import math
import time

import rospy

from wall_follower.evaluation.outputs import output_problem
from wall_follower.evaluation.pictures.course_plot import plot_course
from wall_follower.evaluation.scoring.course import CourseMap
from wall_follower.nodes.shared.course_monitor import CourseMonitor, node_alive
from wall_follower.nodes.shared.parameters import NodeParameters
from wall_follower.nodes.shared.shutdown import quiet_on_shutdown, raise_if_shut_down
from wall_follower.nodes.shared.startup import init_node
from wall_follower.params.evaluation.course_report import TABLE
from wall_follower.sim.stage_interface import world_path
from wall_follower.sim.worldfile import WorldFileError


# Wall seconds between checks that the follower still runs: often enough to see
# one that ends a second after it starts (find_wall failing at once).
FOLLOWER_POLL = 0.2
# Wall seconds the lap's result has to arrive once the follower is gone: a
# follower that stops after the lap ends as soon as it hears the result,
# perhaps before this node has.
RESULT_GRACE = 3.0
# Wall seconds for the follower to show up at all.
FOLLOWER_START_LIMIT = 20.0


def no_lap_reason(monitor, follower, alive=node_alive, clock=time.monotonic,
                  poll=FOLLOWER_POLL):
    """Wait for record_odom's result; None once it came, else why no lap can come.

    Polls the follower (alive(name), every poll wall seconds): once it has
    been gone for RESULT_GRACE with no result (or never appeared within
    FOLLOWER_START_LIMIT), nothing will drive the lap any more. A shutdown
    is no such reason (the lap may well have come): it raises
    rospy.ROSInterruptException.
    """
    started = clock()
    seen = False
    gone_since = None
    while not monitor.done.is_set():
        raise_if_shut_down()
        now = clock()
        if alive(follower):
            seen, gone_since = True, None
        elif not seen:
            if now - started > FOLLOWER_START_LIMIT:
                return ('the follower %s is not running (it never started, or ended at once: '
                        'see its log above); no lap can come' % follower)
        elif gone_since is None:
            gone_since = now
        elif now - gone_since > RESULT_GRACE:
            if monitor.goal_time is None:
                return ('the follower %s ended before it started the lap (no record_odom goal '
                        'was sent: find_wall failed? see its log above); no lap can come'
                        % follower)
            return ('the follower %s ended during the lap (see its log above); no lap can come'
                    % follower)
        monitor.done.wait(poll)
    return None


def course_figures(monitor):
    """The run's figures: the action's result next to the ground-truth score."""
    figures = monitor.summary()
    points = monitor.result or []
    stamps = monitor.recorded_stamps
    nan = float('nan')
    figures.update({
        'points': len(points),
        'recording_time': stamps[-1] - stamps[0] if stamps else nan,
        'recorded_distance': monitor.feedback[-1] if monitor.feedback else nan,
        'true_distance': monitor.truth_at_result or nan,
        'closing_gap': (math.hypot(points[-1][0] - points[0][0], points[-1][1] - points[0][1])
                        if points else nan),
    })
    aligned = (monitor.score.map.right_wall_alignment(monitor.goal_pose)
               if monitor.goal_pose is not None else None)
    figures['found_distance'] = aligned[0] if aligned else nan
    figures['found_heading_error_deg'] = math.degrees(aligned[1]) if aligned else nan
    return figures


def format_summary(f):
    """The report's lines, from course_figures() (and 'simulator')."""
    truth = f['true_distance']
    return [
        'simulator: %s' % (f.get('simulator') or 'unknown'),
        'record_odom result: %d points over %.1f s, %.2f m travelled (feedback)'
        % (f['points'], f['recording_time'], f['recorded_distance']),
        'ground truth: %.2f m travelled (the feedback is off by %.1f %%); '
        'last point %.3f m from the first'
        % (truth, 100.0 * (f['recorded_distance'] - truth) / truth, f['closing_gap']),
        'after find_wall: wall %.3f m on the right, heading off parallel by %.1f deg'
        % (f['found_distance'], abs(f['found_heading_error_deg'])),
        'following: %.1f %% of the lap in [0.20, 0.30] m, RMS error %.2f cm, '
        'min clearance %.3f m, contact: %s'
        % (100.0 * f['time_in_band'], 100.0 * f['rms_error'], f['min_clearance'],
           'yes' if f['contact'] else 'no'),
        'lap: %.1f s for %.2f m (%.3f x the 0.19 m/s bound); highest commands %.3f m/s, %.3f rad/s'
        % (f['lap_time'], f['path_length'], f['lap_time_ratio'], f['max_linear'],
           f['max_angular']),
    ]


@quiet_on_shutdown
def main():
    init_node('course_report')
    values = NodeParameters(TABLE).snapshot()
    world, plot, output = values['world'], values['plot'], values['json']
    for name, path in (('plot', plot), ('json', output)):
        problem = output_problem(path) if path else None
        if problem:
            rospy.logerr('course_report: cannot write ~%s: %s', name, problem)
            return 1
    try:
        course_map = CourseMap(world_path(world))
    except (WorldFileError, EnvironmentError) as err:
        rospy.logerr('course_report: cannot read world %s: %s', world, err)
        return 1
    follower = rospy.resolve_name(values['follower'])
    monitor = CourseMonitor(course_map, start_on_goal=True)
    if not monitor.start_world():
        rospy.logerr('course_report: could not connect to the simulator (%s) and record_odom',
                     rospy.resolve_name('base_pose_ground_truth'))
        return 1
    simulator = monitor.simulator() or 'an unknown simulator'
    rospy.loginfo('course_report: on %s; waiting for the lap to be recorded', simulator)
    reason = no_lap_reason(monitor, follower)
    if reason is not None:
        rospy.logerr('course_report: %s', reason)
        return 1
    monitor.wait()
    figures = course_figures(monitor)
    figures['simulator'] = simulator
    for line in format_summary(figures):
        rospy.loginfo('course_report: %s', line)
    if not monitor.lap_recorded:
        # No files: the plot and the figures exist only for a recorded lap.
        rospy.logerr('course_report: record_odom ended its goal without a lap (status %d: %s)',
                     monitor.result_status, monitor.result_text or 'no text')
        return 1
    if output:
        with open(output, 'w') as stream:
            json.dump(figures, stream, indent=1)
    if plot:
        plot_course(course_map, monitor.trail, monitor.result, plot,
                    title='record_odom in %s' % world)
        rospy.loginfo('course_report: plot saved to %s', plot)
    return 0
