"""The end of `main.launch report:=true`: a scored summary of the lap and its plot.

The follower already logs the search and the lap's progress; this node
waits for the record_odom result, then prints what the robot recorded next
to what really happened (ground truth, scored against the map), saves the
plot and ends, which ends the launch.
"""
import json
import math

import rospy

from wall_follower.nodes.common import world_path
from wall_follower.nodes.course_monitor import CourseMonitor
from wall_follower.evaluation.plot import plot_course
from wall_follower.evaluation.scoring import CourseMap
from wall_follower.sim.worldfile import WorldFileError


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
    """The report's lines, from course_figures()."""
    truth = f['true_distance']
    return [
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


def main():
    rospy.init_node('course_report')
    world = rospy.get_param('~world', 'arena')
    plot = rospy.get_param('~plot', '')
    output = rospy.get_param('~json', '')
    try:
        course_map = CourseMap(world_path(world))
    except (WorldFileError, EnvironmentError) as err:
        rospy.logerr('course_report: cannot read world %s: %s', world, err)
        return 1
    monitor = CourseMonitor(course_map, start_on_goal=True)
    if not monitor.start_world():
        rospy.logerr('course_report: could not connect to the simulator and record_odom')
        return 1
    rospy.loginfo('course_report: waiting for the lap to be recorded')
    if not monitor.wait():
        return 0
    figures = course_figures(monitor)
    for line in format_summary(figures):
        rospy.loginfo('course_report: %s', line)
    if output:
        with open(output, 'w') as stream:
            json.dump(figures, stream, indent=1)
    if plot:
        plot_course(course_map, monitor.trail, monitor.result, plot,
                    title='record_odom in %s' % world)
        rospy.loginfo('course_report: plot saved to %s', plot)
    return 0
