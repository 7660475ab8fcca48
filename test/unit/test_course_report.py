"""course_report ends when no lap can come, instead of waiting for ever.

no_lap_reason is driven here with a stand-in follower and clock (no master):
each poll advances the clock by one second.
"""
import itertools
import threading

import pytest
import rospy

from wall_follower.nodes.evaluation.course_report import RESULT_GRACE, no_lap_reason


class Monitor(object):
    def __init__(self, goal_time=None):
        self.done = threading.Event()
        self.goal_time = goal_time


def follower_alive_for(polls):
    """A follower that answers for the first `polls` polls, then is gone."""
    count = itertools.count()
    return lambda _name: next(count) < polls


def reason(monitor, alive):
    clock = itertools.count()
    return no_lap_reason(monitor, '/wall_following', alive=alive,
                         clock=lambda: float(next(clock)), poll=0.0)


def test_follower_gone_before_the_goal_means_find_wall_failed():
    text = reason(Monitor(), follower_alive_for(2))
    assert 'ended before it started the lap' in text and 'find_wall failed' in text
    assert 'no lap can come' in text


def test_follower_gone_mid_lap():
    assert 'ended during the lap' in reason(Monitor(goal_time=3.0), follower_alive_for(5))


def test_follower_never_seen():
    assert 'is not running' in reason(Monitor(), follower_alive_for(0))


def test_a_result_ends_the_wait_without_a_reason():
    monitor = Monitor(goal_time=1.0)
    polls = itertools.count()

    def alive(_name):
        if next(polls) == 3:
            monitor.done.set()
        return True
    assert reason(monitor, alive) is None


def test_the_result_gets_a_grace_after_the_follower_ends():
    """A follower that stops after the lap may end before its result reaches the report."""
    monitor = Monitor(goal_time=1.0)
    polls = itertools.count()

    def alive(_name):
        poll = next(polls)
        if poll == 1 + int(RESULT_GRACE):
            monitor.done.set()
        return poll == 0
    assert reason(monitor, alive) is None


def test_a_shutdown_is_no_reason_why_no_lap_can_come(monkeypatch):
    """A signal ends the wait, not the lap: it raises as rospy's waits do, and no error
    names a cause (before: 'shut down before the lap was recorded', status 1)."""
    monkeypatch.setattr(rospy, 'is_shutdown', lambda: True)
    with pytest.raises(rospy.ROSInterruptException):
        reason(Monitor(goal_time=1.0), lambda _name: True)
