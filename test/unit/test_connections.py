"""ConnectionKeeper, which announces to the node again the publishers the master lists and a
subscriber stays unconnected to, once they have been missing at two looks in a row, and the
same ones only once."""
import rosgraph

from wall_follower.nodes.shared.connections import MASTER_ID, ConnectionKeeper

TOPIC = '/scan'


class Subscriber(object):
    def __init__(self, connections):
        self.name = TOPIC
        self.connections = connections

    def get_num_connections(self):
        return self.connections


class Master(object):
    """A master listing `publishers` of TOPIC; error: what its next answer raises instead."""

    def __init__(self, publishers):
        self.publishers = publishers
        self.error = None

    def getSystemState(self):
        if self.error is not None:
            raise self.error
        return [(TOPIC, list(self.publishers))], [(TOPIC, ['/follower'])], []

    def lookupNode(self, name):
        return 'http://host:1%s/' % name.strip('/')


class Node(object):
    def __init__(self):
        self.updates = []

    def publisherUpdate(self, caller_id, topic, uris):
        self.updates.append((caller_id, topic, uris))
        return 1, '', 0


def keeper(connections, publishers):
    """(subscriber, master, ConnectionKeeper, node) of a subscriber with `connections`
    whose master lists `publishers`."""
    subscriber, master, node = Subscriber(connections), Master(publishers), Node()
    return subscriber, master, ConnectionKeeper([subscriber], master=master, node=node), node


def test_a_publisher_missing_at_two_looks_is_announced_again():
    subscriber, _, watch, node = keeper(0, ['/stage'])
    watch.check()
    assert node.updates == []   # it may still be connecting
    watch.check()
    assert node.updates == [(MASTER_ID, TOPIC, ['http://host:1stage/'])]


def test_a_connection_made_between_the_looks_is_left_alone():
    subscriber, _, watch, node = keeper(0, ['/stage'])
    watch.check()
    subscriber.connections = 1
    watch.check()
    watch.check()
    assert node.updates == []


def test_a_publisher_new_at_the_second_look_waits_for_the_third():
    _, master, watch, node = keeper(1, ['/stage'])
    watch.check()
    master.publishers = ['/stage', '/laser']
    watch.check()
    assert node.updates == []
    watch.check()
    assert node.updates == [(MASTER_ID, TOPIC, ['http://host:1laser/', 'http://host:1stage/'])]


def test_a_master_that_does_not_answer_is_no_error():
    _, master, watch, node = keeper(0, ['/stage'])
    watch.check()
    master.error = rosgraph.MasterError('gone')
    watch.check()
    master.error = OSError('connection refused')
    watch.check()
    assert node.updates == []


def test_publishers_that_cannot_be_connected_are_announced_once():
    subscriber, _, watch, node = keeper(0, ['/stage'])
    for _ in range(5):
        watch.check()
    assert len(node.updates) == 1
    subscriber.connections = 1
    watch.check()
    subscriber.connections = 0   # the publisher came back under the same name, and was lost
    watch.check()
    watch.check()
    assert len(node.updates) == 2
