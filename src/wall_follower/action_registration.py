"""An action server looked for in the master's graph, and awaited there before its client
is made.

rospy can lose a publisher. A subscriber that registers just before a
publisher of its topic gets the empty list of publishers its registration
returned and the master's news of the new publisher; when the empty list
is queued after the news (the registration was slow, on a loaded
machine), rospy keeps only that later, stale update and never connects.
The master lists the publisher; the subscriber hears nothing: an action
client made before its server waits for it, or for a result, for ever.

So an action client is made only once its server is registered
(action_server_registered): the registration of its subscriptions then
already lists the server, and no news of it can be lost. Whoever makes one
(the nodes, the benchmarks, the tools) waits here, and grading counts a
server as this module does (action_servers). What a node does for its
other inputs is in nodes/shared/connections.py.
"""
import time

import rosgraph
import rospy

# Wall seconds between two looks at the master while an action server is awaited.
GRAPH_POLL = 0.05
# The topics an action server publishes, and those it subscribes to, under its namespace.
SERVER_PUBLISHES = ('status', 'result', 'feedback')
SERVER_SUBSCRIBES = ('goal', 'cancel')


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
