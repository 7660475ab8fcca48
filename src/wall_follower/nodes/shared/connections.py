"""A node's inputs kept connected to every publisher the master lists.

rospy can lose a publisher for good: a subscriber that registers just
before a publisher of its topic can keep only the stale news that there is
none (wall_follower/action_registration.py tells how). The master lists the
publisher; the subscriber hears nothing: a driving node stops for want of
a scan, a grading monitor misses a run. An action client is made only once
its server is registered (action_registration); a node's other inputs are
kept connected here (keep_connected): the master's list of a topic's
publishers is told to the node again, as the master itself does (the
slave API's publisherUpdate), and rospy connects to those it is not
connected to.
"""
import threading
import xmlrpc.client

import rosgraph
import rospy

# Wall seconds between two looks at the master. A topic short of connections at
# two looks in a row is announced again: a connection is made in milliseconds, so
# one still missing then was lost, not on its way.
PERIOD = 2.0
# The caller id of an announcement: the master's own.
MASTER_ID = '/master'


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
