"""An action client that sends one goal at a time and always hears it end.

actionlib's SimpleActionClient compares each transition of a goal with the
goal handle it stores once send_goal returns. A server that answers before
that (a goal refused at once, on a busy machine) has the goal's DONE
transition logged as "a goal handle that we're not tracking" and dropped:
wait_for_result then waits its whole timeout for a result that came long ago
(ros/actionlib#206). GoalClient waits on the goal's own communication state,
which actionlib sets whoever is told.

Its waits count wall seconds, as tf_lookup's do: ROS time stands still while
a simulator is paused or before its first /clock.
"""
import time

import actionlib
from actionlib.action_client import CommState

POLL = 0.01    # wall s between two looks at the goal's state


class GoalClient(object):
    """The part of SimpleActionClient's interface the package's tools use, without its race.

    client: an actionlib.ActionClient-like object (send_goal(goal) giving a
    ClientGoalHandle); by default actionlib's, on the action `name` of type `action`.
    """

    def __init__(self, name, action, client=None, clock=time.monotonic, sleep=time.sleep):
        self._client = client if client is not None else actionlib.ActionClient(name, action)
        self._clock, self._sleep = clock, sleep
        self._goal = None

    def wait_for_server(self, timeout):
        """True once the server is there, within timeout (a rospy.Duration)."""
        return self._client.wait_for_server(timeout)

    def send_goal(self, goal):
        """Send goal; the goal sent before it is no longer followed (nor cancelled)."""
        self._goal = self._client.send_goal(goal)

    def wait_for_result(self, timeout):
        """True once the goal sent last has ended, within timeout wall seconds."""
        deadline = self._clock() + timeout
        while not self.done():
            if self._clock() >= deadline:
                return False
            self._sleep(POLL)
        return True

    def done(self):
        """Whether the goal sent last has ended (its result is in)."""
        return self._goal is not None and self._goal.get_comm_state() == CommState.DONE

    def get_state(self):
        """The goal's actionlib_msgs/GoalStatus status."""
        return self._goal.get_goal_status()

    def get_result(self):
        return self._goal.get_result()

    def cancel_goal(self):
        self._goal.cancel()

    def goal_id(self):
        """The id of the goal sent last, as its status, feedback and result carry it."""
        return self._goal.comm_state_machine.action_goal.goal_id.id
