"""What a graded case's node (grade_case, line_case) reads of the solution, and how it
writes the case's record.

Both case nodes run beside the solution on the case's own master and judge it from
ground truth; of the solution they look only at the graph (its nodes, its find_wall
service, its action) and at what it commands. One rule says when a solution is gone.
"""
import json
import math
import time

import rosgraph
import rospy
from std_srvs.srv import Empty

from wall_follower.action_registration import action_servers, master_graph
from wall_follower.evaluation.grading.commands import non_finite_text
from wall_follower.nodes.shared.course_monitor import node_alive
from wall_follower.nodes.shared.shutdown import poll_until, raise_if_shut_down

# Nodes of the grading itself (the case's launch file and the simulation.launch it
# includes: the simulator, the world's map and the robot's model for rviz), not of the
# solution.
OWN_NODES = ('/simulator', '/world_map', '/robot_state_publisher', '/rosout')
# Wall seconds for ground truth to connect (the simulator is started first).
SIMULATOR_LIMIT = 60.0
NO_SIMULATOR = ('no ground truth from the simulator (it did not start within %.0f wall s, or '
                'ended: see the case log)' % SIMULATOR_LIMIT)
# Wall seconds for the simulator's unpause_physics service.
SERVICE_WAIT = 10.0
# Wall seconds between looks at the graph.
GRAPH_POLL = 1.0
GONE = 'none of the solution\'s nodes is running (it crashed or ended)'


class Graph(object):
    """What the running graph offers: the solution's service, action and nodes."""

    def __init__(self, action_ns):
        self._master = rosgraph.Master(rospy.get_name())
        self._action_ns = rospy.resolve_name(action_ns)

    def state(self):
        return master_graph(self._master.getSystemState)

    def find_wall_service(self, state):
        """The name of the advertised find_wall service (any namespace), or None."""
        _, _, services = state
        names = sorted(name for name, _ in services
                       if name == '/find_wall' or name.endswith('/find_wall'))
        return names[0] if names else None

    def action_server(self, state):
        """Whether one node serves the action: it is on all five of its topics."""
        return bool(action_servers(self._action_ns, state))

    def solution_nodes(self, state):
        own = set(OWN_NODES) | {rospy.get_name()}
        nodes = set()
        for section in state:
            for _, members in section:
                nodes.update(members)
        return sorted(nodes - own)


def solution_running(graph, state=None):
    """Whether any of the solution's nodes is alive (state: the graph's, if at hand)."""
    state = graph.state() if state is None else state
    return any(node_alive(name) for name in graph.solution_nodes(state))


class SolutionGone(object):
    """Whether the solution is gone: none of its nodes alive for gone_limit wall seconds,
    counted only after start_limit wall seconds from now, the time its launch file has
    to start them."""

    def __init__(self, graph, start_limit, gone_limit):
        self._graph = graph
        self._start_limit = start_limit
        self._gone_limit = gone_limit
        self._started = time.monotonic()
        self._gone_since = None

    def look(self, state=None):
        """True once gone, from a fresh look at the graph (state: the graph's, if at
        hand)."""
        now = time.monotonic()
        if solution_running(self._graph, state) or now - self._started < self._start_limit:
            self._gone_since = None
        elif self._gone_since is None:
            self._gone_since = now
        return self._gone_since is not None and now - self._gone_since > self._gone_limit


def wait_for_simulator(connected, limit=SIMULATOR_LIMIT):
    """Until connected() says ground truth is heard; False after limit wall seconds (then
    NO_SIMULATOR is the grader's error); rospy.ROSInterruptException if rospy shuts down
    first, which is no simulator missing (shutdown.py)."""
    return poll_until(connected, limit)


def call_simulator(name, wait=None):
    """Call the simulator's std_srvs/Empty service name (unpause_physics, pause_physics),
    waiting up to wait wall seconds for it; False, said in the log, when there is none
    (a simulator that was never paused, or one that has ended); rospy.ROSInterruptException
    when rospy shut down meanwhile, which says nothing of the simulator."""
    try:
        if wait:
            rospy.wait_for_service(name, timeout=wait)
        rospy.ServiceProxy(name, Empty)()
    except (rospy.ServiceException, rospy.ROSException):
        raise_if_shut_down()
        rospy.loginfo('%s: no %s service', rospy.get_name(), name)
        return False
    return True


def grader_failed(params, reason, **record):
    """End a run that the grader itself could not hold: log it, and record it as such (with
    the task's own keys of record)."""
    rospy.logerr('%s: %s', rospy.get_name(), reason)
    write_record(params['json'], dict(record, world=params['world'], grader_error=reason))
    return 1


def _json_safe(value):
    """NaN and infinity as the strings 'nan', 'inf' and '-inf' (JSON has none of them, and
    grades.json is read by other tools than Python's; null would read as nothing
    commanded)."""
    if isinstance(value, float) and not math.isfinite(value):
        return non_finite_text(value)
    if isinstance(value, dict):
        return {key: _json_safe(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [_json_safe(item) for item in value]
    return value


def write_record(path, record):
    """Write the record; False (with an error logged) when it cannot be written."""
    try:
        with open(path, 'w') as stream:
            json.dump(_json_safe(record), stream, indent=1)
    except (IOError, OSError) as err:
        rospy.logerr('%s: cannot write the record %s: %s', rospy.get_name(), path, err)
        return False
    return True
