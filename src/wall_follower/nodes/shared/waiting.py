"""Waits that give up after wall seconds, also while simulated time stands still."""
import threading
import time

import rosgraph
import rospy

# Wall seconds between two looks at the master's graph.
GRAPH_POLL = 0.05
# The topics an action server publishes, and those it subscribes to, under its namespace.
SERVER_PUBLISHES = ('status', 'result', 'feedback')
SERVER_SUBSCRIBES = ('goal', 'cancel')


def wait_in_wall_time(wait, timeout):
    """wait()'s answer if it comes within timeout wall seconds, else False.

    wait is a call that blocks until what it waits for is there, or until
    rospy shuts down (actionlib's wait_for_server() with no time-out, say).
    The time-outs of actionlib's waits are counted in ROS time, which
    stands still on simulated time while nobody publishes /clock: a wait
    meant to give up after some seconds would then wait for ever. This one
    counts wall seconds. A wait still blocked when they are up goes on in a
    daemon thread, which ends with rospy and never keeps the process alive.
    """
    answer = []
    thread = threading.Thread(target=lambda: answer.append(wait()))
    thread.daemon = True
    thread.start()
    thread.join(timeout)
    return bool(answer and answer[0])


def action_server_registered(action_ns, timeout, system_state=None, clock=time.monotonic,
                             sleep=time.sleep):
    """Whether one node is registered with the master as the server of action_ns, on all
    five of its topics, within timeout wall seconds.

    Create an action client only once this holds. rospy can miss a
    publisher that registers while one of its subscribers is registering:
    the master tells the subscriber of the new publisher, but the empty list
    of publishers its own registration returned can be queued after that
    news, and rospy keeps only the later of two updates of a topic. The
    subscriber then never connects, and an action client started together
    with its server (a launch file, a rostest) waits for it for ever, on a
    loaded machine now and then. Subscribed once the server is registered,
    the client finds the server in its registration's answer.

    system_state: a call giving the master's getSystemState(); by default
    the master's own, asked as this node.
    """
    namespace = rospy.resolve_name(action_ns)
    if system_state is None:
        system_state = rosgraph.Master(rospy.get_name()).getSystemState
    deadline = clock() + timeout
    while not rospy.is_shutdown():
        if action_servers(namespace, _graph(system_state)):
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


def _graph(system_state):
    """The master's graph, or an empty one while the master does not answer."""
    try:
        return system_state()
    except (rosgraph.MasterException, OSError):
        return [], [], []
