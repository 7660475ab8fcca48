"""The arm_plot node: the lab's `rqt_plot` of the arm's joint positions (rqt_plot is not
packaged on every system): records joint_states and saves positions and velocities
against time as a PNG (~file) when stopped or after ~duration; where a display exists
and ~live is true, also shows them in a live window.

    rosrun wall_follower arm_plot _file:=joints.png _duration:=20
"""
import os
import threading

import rospy
from sensor_msgs.msg import JointState

from wall_follower.evaluation.joint_plot import JointRecord, draw, save
from wall_follower.nodes.common import init_node
from wall_follower.nodes.parameters import NodeParameters
from wall_follower.params.arm_plot import TABLE

# Wall seconds between two redraws of the live window, or two looks at the clock.
REFRESH = 0.5


def main():
    init_node('arm_plot')
    values = NodeParameters(TABLE).snapshot()
    filename = os.path.abspath(os.path.expanduser(values['file']))
    if not os.path.isdir(os.path.dirname(filename)):
        rospy.logfatal('%s: cannot start: no directory %s for ~file', rospy.get_name(),
                       os.path.dirname(filename))
        return 1
    record = JointRecord()
    rospy.Subscriber('joint_states', JointState, lambda msg: record.add(
        msg.header.stamp.to_sec(), msg.name, msg.position, msg.velocity), queue_size=100)
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
    started = None
    while not rospy.is_shutdown():
        if figure is not None:
            draw(figure, record, values['window'])
            plt.pause(REFRESH)
        else:
            stopped.wait(REFRESH)
        if record.times and started is None:
            started = record.times[0]
        if values['duration'] and started is not None and \
                record.times[-1] - started >= values['duration']:
            break
    if not record.times:
        # Nothing to draw: an empty plot would only cost a stopped node a
        # second of a busy machine's time before it exits.
        rospy.logwarn('%s: no joint_states came; nothing saved', rospy.get_name())
        return 0
    save(record, filename)
    rospy.loginfo('%s: saved %d joint states to %s', rospy.get_name(), len(record.times),
                  filename)
    return 0
