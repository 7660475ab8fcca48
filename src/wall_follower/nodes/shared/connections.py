"""Connections that rospy can miss for good, and how the nodes make sure of them.

rospy can lose a publisher. A subscriber that registers just before a
publisher of its topic gets the empty list of publishers its registration
returned and the master's news of the new publisher; when the empty list
is queued after the news (the registration was slow, on a loaded
machine), rospy keeps only that later, stale update and never connects.
The master lists the publisher; the subscriber hears nothing: a driving
node stops for want of a scan, a grading monitor misses a run, an action
client waits for its server for ever.

Two answers: an action client is made only once its server is registered
(action_server_registered), so that the registration of its subscriptions
already lists the server; and a node's inputs are kept connected
(keep_connected): the master's list of a topic's publishers is told to the
node again, as the master itself does (the slave API's publisherUpdate),
and rospy connects to those it is not connected to.
"""
import threading
import time
import xmlrpc.client

import rosgraph
import rospy

# Wall seconds between two looks at the master while an action server is awaited.
GRAPH_POLL = 0.05
# The topics an action server publishes, and those it subscribes to, under its namespace.
SERVER_PUBLISHES = ('status', 'result', 'feedback')
SERVER_SUBSCRIBES = ('goal', 'cancel')
# Wall seconds between two looks at the master. A topic short of connections at
# two looks in a row is announced again: a connection is made in milliseconds, so
# one still missing then was lost, not on its way.
PERIOD = 2.0
# The caller id of an announcement: the master's own.
MASTER_ID = '/master'


def action_server_registered(action_ns, timeout, system_state=None, clock=time.monotonic,
                             sleep=time.sleep):
    """Whether one node is registered with the master as the server of action_ns, on all
    five of its topics, within timeout wall seconds.

    Create an action client only once this holds: subscribed then, the
    client finds the server in its registrations' answers, and no news of
    it can be lost (see above). A client started together with its server
    (a launch file, a rostest) otherwise waits for it for ever, on a loaded
    machine now and then.

    system_state: a call giving the master's getSystemState(); by default
    the master's own, asked as this node.
    """
    namespace = rospy.resolve_name(action_ns)
    if system_state is None:
        system_state = rosgraph.Master(rospy.get_name()).getSystemState
    deadline = clock() + timeout
    while not rospy.is_shutdown():
        if action_servers(namespace, master_graph(system_state)):
            return True
        if clock() >= deadline:
            return False
        sleep(GRAPH_POLL)
    return False


def action_servers(namespace, state):
    """The nodes that a master's getSystemState() lists as servers of the action namespace."""
    publishers, subscribers = dict(state[0]), dict(state[1])
    nodes = None
    for topics, registered in ((SERVER_PUBLISHES, publishers), (SERVER_SUBSCRIBES, subscribers)):
        for topic in topics:
            on_topic = set(registered.get(namespace + '/' + topic, ()))
            nodes = on_topic if nodes is None else nodes & on_topic
    return nodes


def master_graph(system_state):
    """The master's graph from system_state() (its getSystemState()), or an empty one
    while the master does not answer (starting, or gone at shutdown)."""
    try:
        return system_state()
    except (rosgraph.MasterException, OSError):
        return [], [], []


def short_of_publishers(subscribers, state):
    """The topics of subscribers that have fewer connections than the publishers that a
    master's getSystemState() lists for them, with those publishers' node names."""
    publishers = dict(state[0])
    short = {}
    for subscriber in subscribers:
        nodes = publishers.get(subscriber.name, [])
        if len(nodes) > subscriber.get_num_connections():
            short[subscriber.name] = nodes
    return short


class ConnectionKeeper(object):
    """Every PERIOD wall seconds, announces to this node again the publishers of any topic
    of subscribers (rospy.Subscriber-like: name, get_num_connections()) that stayed short
    of them since the look before; in a daemon thread, until stop() or shutdown.

    The same publishers of a topic are announced once: a node that died
    without unregistering stays listed until the master is told, and
    cannot be connected to. master: the master's API (rosgraph.Master-like),
    node: this node's slave API (an XML-RPC proxy), by default both asked
    as this node.
    """

    def __init__(self, subscribers, master=None, node=None, period=PERIOD):
        self._subscribers = list(subscribers)
        self._master, self._node = master, node
        self._period = period
        self._short = {}       # topic: the publishers' nodes, of the topics short at the last look
        self._announced = {}   # topic: the publishers' nodes announced, while still short
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run, name='connection_keeper')
        self._thread.daemon = True

    def start(self):
        self._thread.start()
        return self

    def stop(self):
        self._stop.set()

    def check(self):
        """One look at the master; announces again what was short at the look before too."""
        try:
            master = self._this_master()
            short = short_of_publishers(self._subscribers, master.getSystemState())
            for topic, nodes in short.items():
                nodes = frozenset(nodes)
                if nodes <= set(self._short.get(topic, ())) and \
                        self._announced.get(topic) != nodes:
                    uris = [master.lookupNode(name) for name in sorted(nodes)]
                    self._this_node().publisherUpdate(MASTER_ID, topic, uris)
                    self._announced[topic] = nodes
                    rospy.logwarn('%s: not connected to every publisher of %s (%s); asking '
                                  'rospy to connect', rospy.get_name(), topic,
                                  ', '.join(sorted(nodes)))
        except (rosgraph.MasterException, OSError, xmlrpc.client.Error):
            return   # the master or this node is going: nothing to keep
        self._short = short
        self._announced = {topic: nodes for topic, nodes in self._announced.items()
                           if topic in short}

    def _this_master(self):
        if self._master is None:
            self._master = rosgraph.Master(rospy.get_name())
        return self._master

    def _this_node(self):
        if self._node is None:
            self._node = xmlrpc.client.ServerProxy(rospy.get_node_uri())
        return self._node

    def _run(self):
        while not self._stop.wait(self._period) and not rospy.is_shutdown():
            if rospy.core.is_initialized():   # a node of its own to announce to
                self.check()


def keep_connected(subscribers):
    """A started ConnectionKeeper of subscribers."""
    return ConnectionKeeper(subscribers).start()
