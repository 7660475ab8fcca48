"""The arm benchmark makes its move_arm client only once the server is registered with the
master, as the nodes make theirs: a client made before can miss the server for good. No
master: the master's graph, the clock and the client are stand-ins."""
from fake_clock import FakeClock
from master_graphs import Graph, server_graph
from wall_follower.evaluation.benchmarks.arm import move_arm_client
from wall_follower.msg import MoveArmAction

NOTHING = [], [], []


class Clients(object):
    """make_client for move_arm_client: each client made is kept, with how many looks at
    the graph had been taken when it was made. Their wait_for_server takes its whole
    timeout on clock, and finds the server if `server`."""

    def __init__(self, graph, clock, server=True):
        self.graph, self.clock, self.server = graph, clock, server
        self.made = []

    def __call__(self, name, action):
        self.made.append((name, action, self.graph.asked))
        return self

    def wait_for_server(self, timeout):
        if not self.server:
            self.clock.sleep(timeout.to_sec())
        return self.server


def connect(graph, server=True, timeout=5.0):
    """(client or None, the clients made, wall seconds waited) of move_arm_client on graph."""
    clock = FakeClock()
    clients = Clients(graph, clock, server)
    client = move_arm_client(timeout, graph, clock, clock.sleep, clients)
    return client, clients.made, clock.now


def test_no_client_is_made_while_no_server_is_registered():
    client, made, waited = connect(Graph(NOTHING))
    assert client is None
    assert made == []
    assert waited >= 5.0


def test_the_client_is_made_once_the_server_is_registered():
    graph = Graph(NOTHING, OSError('no master yet'), server_graph('/move_arm', '/move_arm'))
    client, made, _ = connect(graph)
    assert client is not None
    assert made == [('move_arm', MoveArmAction, 3)]


def test_a_registered_server_that_never_answers_gives_no_client_within_the_timeout():
    client, made, waited = connect(Graph(server_graph('/move_arm', '/move_arm')), server=False)
    assert client is None
    assert len(made) == 1
    assert 5.0 < waited <= 6.0
