"""GoalClient hears a goal end however soon the server answers (ros/actionlib#206)."""
from actionlib.action_client import CommState
from actionlib_msgs.msg import GoalStatus

from fake_clock import FakeClock
from wall_follower.evaluation.goal_client import GoalClient


class Handle(object):
    """A ClientGoalHandle's state, as actionlib keeps it."""

    def __init__(self):
        self.comm_state, self.status, self.cancelled = CommState.WAITING_FOR_GOAL_ACK, None, False

    def get_comm_state(self):
        return self.comm_state

    def get_goal_status(self):
        return self.status

    def get_result(self):
        return 'result'

    def cancel(self):
        self.cancelled = True


class AnsweringAtOnce(object):
    """An ActionClient whose server refuses each goal before send_goal returns: the goal's
    DONE transition reaches transition_cb while the caller has no handle yet."""

    def __init__(self):
        self.sent = []

    def send_goal(self, goal, transition_cb=None, feedback_cb=None):
        handle = Handle()
        handle.comm_state, handle.status = CommState.DONE, GoalStatus.ABORTED
        if transition_cb is not None:
            transition_cb(handle)
        self.sent.append(handle)
        return handle


def test_a_goal_refused_before_send_goal_returned_has_ended():
    clock = FakeClock()
    client = GoalClient('move_arm', None, client=AnsweringAtOnce(), clock=clock,
                        sleep=clock.sleep)
    client.send_goal('goal')
    assert client.wait_for_result(5.0)
    assert clock.now == 0.0
    assert client.get_state() == GoalStatus.ABORTED
    assert client.get_result() == 'result'


class NeverAnswering(AnsweringAtOnce):
    def send_goal(self, goal, transition_cb=None, feedback_cb=None):
        self.sent.append(Handle())
        return self.sent[-1]


def test_a_goal_not_ended_is_waited_for_until_the_timeout_only():
    clock = FakeClock()
    server = NeverAnswering()
    client = GoalClient('move_arm', None, client=server, clock=clock, sleep=clock.sleep)
    client.send_goal('goal')
    assert not client.wait_for_result(2.0)
    assert 2.0 <= clock.now < 2.1
    client.cancel_goal()
    assert server.sent[-1].cancelled
