"""Waits bounded in wall seconds: wait_in_wall_time, and action_server_registered's look at
the master's graph."""
import threading
import time

from wall_follower.nodes.shared.waiting import (
    GRAPH_POLL, action_server_registered, action_servers, wait_in_wall_time)


def test_a_wait_that_never_ends_gives_up_after_the_timeout():
    never = threading.Event()
    started = time.monotonic()
    assert wait_in_wall_time(never.wait, 0.2) is False
    assert 0.2 <= time.monotonic() - started < 2.0


def test_the_answer_of_a_wait_that_ends_in_time():
    assert wait_in_wall_time(lambda: True, 5.0) is True
    assert wait_in_wall_time(lambda: False, 5.0) is False


SERVER = [('/record_odom/status', ['/recorder']), ('/record_odom/result', ['/recorder']),
          ('/record_odom/feedback', ['/recorder'])], \
         [('/record_odom/goal', ['/recorder']), ('/record_odom/cancel', ['/recorder'])], []


class Graph(object):
    """A master whose graph is each of `states` in turn, then the last for good."""

    def __init__(self, *states):
        self.states = list(states)
        self.asked = 0

    def __call__(self):
        self.asked += 1
        state = self.states[min(self.asked, len(self.states)) - 1]
        if isinstance(state, Exception):
            raise state
        return state


class FakeTime(object):
    def __init__(self):
        self.now = 0.0

    def sleep(self, seconds):
        self.now += seconds


def registered(graph, timeout=10.0):
    fake = FakeTime()
    return action_server_registered('record_odom', timeout, graph, lambda: fake.now,
                                    fake.sleep)


def test_a_server_is_registered_once_one_node_has_all_five_topics():
    publishing_only = SERVER[0], [], []
    graph = Graph(([], [], []), OSError('no master yet'), publishing_only, SERVER)
    assert registered(graph)
    assert graph.asked == 4


def test_five_topics_shared_by_two_nodes_are_no_server():
    publishers, subscribers, services = SERVER
    split = publishers, [(topic, ['/client']) for topic, _ in subscribers], services
    assert action_servers('/record_odom', split) == set()
    assert action_servers('/record_odom', SERVER) == {'/recorder'}


def test_no_server_within_the_timeout_is_false():
    graph = Graph(([], [], []))
    assert not registered(graph, timeout=1.0)
    assert abs(graph.asked - (1 + 1.0 / GRAPH_POLL)) <= 1
