"""Waits that rospy's shutdown ends, told apart from waits that fail; and a node's quiet end.

A node stopped by a signal (Ctrl-C, or roslaunch or grade ending it with
SIGINT or SIGTERM) has rospy shut down (startup.init_node's answer, or
rospy's own handler), which ends every wait it is in. Nothing the node
waited for failed: a wait that answered False for it, as for its
time-limit, would have the node log an error that names the wrong cause (a
simulator that never came, a follower that ended), exit with status 1, or
write a record that blames the simulator or the solution for a run it
never saw end. So the waits here end on shutdown
as rospy's own do (rospy.sleep, wait_for_service, a service call), with
rospy.ROSInterruptException, which no "gave up" answer can be mistaken
for; and a node's main run by quiet_on_shutdown then ends as a node
stopped while it starts does (startup.init_node): with status 0, having
failed at nothing.
"""
import functools
import time

import rospy


def raise_if_shut_down():
    """rospy.ROSInterruptException once rospy has shut down, as rospy's own waits raise it."""
    if rospy.is_shutdown():
        raise rospy.ROSInterruptException('rospy shut down')


def poll_until(condition, limit, period=0.05):
    """True once condition() holds; False after limit wall seconds without; raises
    rospy.ROSInterruptException if rospy shuts down first."""
    deadline = time.monotonic() + limit
    while not condition():
        raise_if_shut_down()
        if time.monotonic() > deadline:
            return False
        time.sleep(period)
    return True


def quiet_on_shutdown(main):
    """main, ending with status 0 and one info line when a wait of it ended because rospy
    shut down (rospy.ROSInterruptException), not with a traceback and status 1.

    Only when rospy has shut down: rospy.sleep also raises a subclass of
    that exception when simulated time jumps back, which is no signal.
    """
    @functools.wraps(main)
    def run():
        try:
            return main()
        except rospy.ROSInterruptException:
            if not rospy.is_shutdown():
                raise
            rospy.loginfo('%s: shut down before its work was done; ending', rospy.get_name())
            return 0
    return run
