"""Let a simulator started paused go once a test node hears everything it scores.

A check that connects late misses the start of the run (and in lockstep the
robot may have driven a whole side by then), so the exercise rostests start
the simulator paused and unpause it from here.
"""
import time

import rospy
from std_srvs.srv import Empty

from waiting import wait_until


def start_world(subscribers, limit=30.0):
    """Unpause the simulator once every subscriber has a publisher; False if that never came.

    rospy shares one connection per topic among a process's subscribers, so
    a subscriber passed here stands for every other one on its topic (the
    drive guard's among them).
    """
    if not wait_until(lambda: all(sub.get_num_connections() > 0 for sub in subscribers), limit):
        return False
    started = time.monotonic()
    left = max(1.0, limit - (time.monotonic() - started))
    rospy.wait_for_service('unpause_physics', timeout=left)
    rospy.ServiceProxy('unpause_physics', Empty)()
    return True
