"""An action server awaited on the master's graph, counted as one node on all five of its
topics; and grading's view of the action server, which counts it the same way."""
from fake_clock import FakeClock
from master_graphs import Graph, server_graph
from wall_follower.action_registration import (GRAPH_POLL, action_server_registered,
                                               action_servers)
from wall_follower.nodes.shared import case_graph

SERVER = server_graph('/record_odom', '/recorder')


def registered(graph, timeout=10.0):
    clock = FakeClock()
    return action_server_registered('record_odom', timeout, graph, clock, clock.sleep)


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


def test_grading_sees_an_action_server_only_in_a_node_on_all_five_topics():
    graph = case_graph.Graph('record_odom')
    assert graph.action_server(SERVER)
    # A status topic alone (a node that publishes it, say, without serving) is no server.
    assert not graph.action_server((SERVER[0][:1], [], []))
    assert not graph.action_server(([], [], []))
