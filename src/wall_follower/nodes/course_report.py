"""The end of `main.launch report:=true`: a scored summary of the lap and its plot.

The follower already logs the search and the lap's progress; this node
waits for the record_odom result, then prints what the robot recorded next
to what really happened (ground truth, scored against the map), saves the
plot and ends, which ends the launch.
"""
import math

import rospy

from wall_follower.nodes.common import world_path
from wall_follower.nodes.course_monitor import CourseMonitor
from wall_follower.plot import plot_course
from wall_follower.scoring import CourseMap
from wall_follower.sim.worldfile import WorldFileError


def format_summary(monitor):
    """The report's lines: the action's result, then the ground-truth score."""
    score = monitor.score.summary()
    points = monitor.result or []
    recorded = monitor.feedback[-1] if monitor.feedback else float('nan')
    truth = monitor.truth_at_result or float('nan')
    lap_time = (monitor.result_time - monitor.goal_time
                if monitor.result_time is not None and monitor.goal_time is not None
                else float('nan'))
    lines = [
        'record_odom result: %d points over %.1f s, %.2f m travelled (feedback)'
        % (len(points), lap_time, recorded),
        'ground truth:       %.2f m travelled (feedback off by %.1f %%)'
        % (truth, 100.0 * (recorded - truth) / truth if truth else float('nan')),
    ]
    if points:
        gap = math.hypot(points[-1][0] - points[0][0], points[-1][1] - points[0][1])
        lines.append('last point to first point: %.3f m' % gap)
    if monitor.goal_pose is not None:
        aligned = monitor.score.map.right_wall_alignment(monitor.goal_pose)
        if aligned is not None:
            lines.append('after find_wall: wall %.3f m on the right, heading off parallel by %.1f deg'
                         % (aligned[0], math.degrees(abs(aligned[1]))))
    lines += [
        'following: %.1f %% of the lap in [0.20, 0.30] m, RMS error %.1f cm, min clearance %.3f m, '
        'contact: %s' % (100.0 * score['time_in_band'], 100.0 * score['rms_error'],
                         score['min_clearance'], 'yes' if score['contact'] else 'no'),
        'highest commands sent: %.3f m/s, %.3f rad/s'
        % (score['max_linear'], score['max_angular']),
    ]
    return lines


def main():
    rospy.init_node('course_report')
    world = rospy.get_param('~world', 'arena')
    plot = rospy.get_param('~plot', '')
    try:
        course_map = CourseMap(world_path(world))
    except (WorldFileError, EnvironmentError) as err:
        rospy.logerr('course_report: cannot read world %s: %s', world, err)
        return 1
    monitor = CourseMonitor(course_map, start_on_goal=True)
    rospy.loginfo('course_report: waiting for the lap to be recorded')
    if not monitor.wait():
        return 0
    for line in format_summary(monitor):
        rospy.loginfo('course_report: %s', line)
    if plot:
        plot_course(course_map, monitor.trail, monitor.result, plot,
                    title='record_odom in %s' % world)
        rospy.loginfo('course_report: plot saved to %s', plot)
    return 0
