"""/clock driven by a rostest, which can hold simulated time still while it sends.

A node that drives /clock itself keeps time going while the test process is
held up on a loaded machine, so a message stamped a little ahead may arrive
after its time. Driven from the test, time stands still while the test sends
and waits for the node to take what it sent.
"""
import contextlib
import threading
import time

import rospy
from rosgraph_msgs.msg import Clock

from waiting import wait_until

# Wall seconds a step waits for the node's own step before it goes on regardless (the
# test's own checks then fail on what is missing).
STEP_LIMIT = 30.0


class DrivenClock(object):
    """Simulated time from 0, advanced by step [s] each step / speedup wall seconds unless
    held; latched, so a node that subscribes late starts from the time it is at.

    reached(time) tells whether the driven node has put out its step at time [s] or a later
    one; reached(0) is whether it has put out anything. From its first output on, each step
    waits for the node's output of that step, so the node steps with the clock however
    slowly it runs, and skips none.
    """

    def __init__(self, step, speedup, reached):
        self._step = rospy.Duration.from_sec(step)
        self._pause = step / speedup
        self._reached = reached
        self._publisher = rospy.Publisher('/clock', Clock, queue_size=1, latch=True)
        self._lock = threading.Lock()
        self._now = rospy.Time(0)
        thread = threading.Thread(target=self._run, name='driven_clock')
        thread.daemon = True
        thread.start()

    def _run(self):
        while not rospy.is_shutdown():
            time.sleep(self._pause)
            with self._lock:
                self._now += self._step
                try:
                    self._publisher.publish(Clock(clock=self._now))
                except rospy.ROSException:
                    if not rospy.is_shutdown():
                        raise
                    return   # rospy closes the topics while it shuts down
                if self._reached(0.0):
                    wait_until(lambda: self._reached(self._now.to_sec()), STEP_LIMIT)

    @contextlib.contextmanager
    def held(self):
        """Inside, simulated time stands still at the time yielded [s], and the node has
        done its step at that time."""
        with self._lock:
            yield self._now.to_sec()
