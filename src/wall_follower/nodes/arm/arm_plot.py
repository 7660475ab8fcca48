"""The arm_plot node: the lab's `rqt_plot` of the arm's joint positions (rqt_plot is not
packaged on every system): records joint_states and saves positions and velocities
against time as a PNG (~file; a directory: joint_states.png in it) when stopped or after
~duration; where a display exists and ~live is true, also shows them in a live window.

~duration is counted in ROS time, and in wall time while ROS time stands still (no
/clock, a paused simulation): the node ends after it whatever comes, joint_states or
not. A joint_states stamped 0 is placed at the time it came. A file that cannot be
written is named in an error, and the picture saved next to it (or in the temporary
directory) instead.

    rosrun wall_follower arm_plot _file:=joints.png _duration:=20
"""
import os
import threading
import time

import rospy
from sensor_msgs.msg import JointState

from wall_follower.evaluation.pictures.joint_plot import (JointRecord, RecordingSpan, draw,
                                                          output_path, save_somewhere)
from wall_follower.nodes.shared.parameters import NodeParameters
from wall_follower.nodes.shared.startup import init_node
from wall_follower.params.arm.arm_plot import TABLE

# Wall seconds between two redraws of the live window, or two looks at the clock.
REFRESH = 0.5


def main():
    init_node('arm_plot')
    values = NodeParameters(TABLE).snapshot()
    filename = output_path(values['file'])
    if not os.path.isdir(os.path.dirname(filename)):
        rospy.logfatal('%s: cannot start: no directory %s for ~file', rospy.get_name(),
                       os.path.dirname(filename))
        return 1
    record = JointRecord()
    rospy.Subscriber('joint_states', JointState, lambda msg: record.add(
        msg.header.stamp.to_sec() or rospy.get_time(), msg.name, msg.position, msg.velocity),
        queue_size=100)
    stopped = threading.Event()
    rospy.on_shutdown(stopped.set)   # a Ctrl-C saves at once, not after the rest of a wait
    figure = None
    if values['live'] and os.environ.get('DISPLAY'):
        import matplotlib.pyplot as plt   # only here: it needs a display
        plt.ion()
        figure = plt.figure('arm_plot: joint_states', figsize=(8, 6))
    rospy.loginfo('%s: recording joint_states into %s%s', rospy.get_name(), filename,
                  ' for %.1f s' % values['duration'] if values['duration'] else
                  ' until stopped')
    span = RecordingSpan(values['duration'], rospy.get_time(), time.time())
    while not rospy.is_shutdown():
        if figure is not None:
            draw(figure, record, values['window'])
            plt.pause(REFRESH)
        else:
            stopped.wait(REFRESH)
        if span.update(rospy.get_time(), time.time()):
            break
    if not record.times:
        # Nothing to draw: an empty plot would only cost a stopped node a
        # second of a busy machine's time before it exits.
        rospy.logwarn('%s: no joint_states came; nothing saved', rospy.get_name())
        return 0
    saved, failures = save_somewhere(record, filename)
    for path, error in failures:
        rospy.logerr('%s: cannot write %s: %s', rospy.get_name(), path, error)
    if saved is None:
        rospy.logerr('%s: %d joint states recorded, but nowhere to save them',
                     rospy.get_name(), len(record.times))
        return 1
    (rospy.logwarn if failures else rospy.loginfo)(
        '%s: saved %d joint states to %s%s', rospy.get_name(), len(record.times), saved,
        ' instead' if failures else '')
    return 0
