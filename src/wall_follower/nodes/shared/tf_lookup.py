"""The one way every node looks a transform up in tf: polled, its wait counted in wall time.

tf2's own timeout counts ROS time, which stands still while a simulator is
paused, in lockstep until the node commands again, or before its first
/clock: a lookup meant to give up after a few seconds would wait for
ever. So the buffer is asked again every POLL wall seconds until the wait
is over. And tf2's C++ core aborts the whole process when asked for a
transform at a stamp far from the data it holds (control.stamps): a
stamp further than `span` from now is refused before it gets there.
"""
import time

import rospy
import tf2_ros

from wall_follower.control.stamps import outside_problem

POLL = 0.002    # wall s between two looks at the buffer
SPAN = 10.0     # s: how far from now a stamp may be asked for (tf2_ros.Buffer's default cache)
TF_ERRORS = (tf2_ros.LookupException, tf2_ros.ConnectivityException,
             tf2_ros.ExtrapolationException)


def lookup(buffer, target, source, stamp=None, wait=0.0, span=SPAN, poll=POLL,
           clock=time.monotonic, sleep=time.sleep):
    """(source's TransformStamped in target, None), or (None, why there is none, in words).

    stamp: a rospy.Time, or None for the latest the buffer holds. wait:
    seconds of clock (wall time) to keep asking for at most, every poll
    seconds; 0 asks once. span: how far from ROS time a stamp may lie,
    either way.
    """
    if stamp is None:
        stamp = rospy.Time(0)
    else:
        far = outside_problem(stamp.to_sec(), rospy.Time.now().to_sec(), span)
        if far is not None:
            return None, 'asked for a time %s' % far
    deadline = clock() + wait
    while True:
        try:
            return buffer.lookup_transform(target, source, stamp), None
        except TF_ERRORS as error:
            if clock() >= deadline or rospy.is_shutdown():
                return None, str(error).splitlines()[0] if str(error) else type(error).__name__
        sleep(poll)
