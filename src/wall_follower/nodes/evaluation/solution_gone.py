"""Whether a graded solution is gone: none of its nodes alive for a while, once it had time
to start them. For a case node's watch (line_case; grade_case's watch keeps the same rule)."""
import time

from wall_follower.nodes.evaluation.grade_case import solution_running

# Wall seconds between looks at the graph.
GRAPH_POLL = 1.0


class SolutionGone(object):
    """gone() is True once none of the solution's nodes (grade_case.Graph's view) has been
    alive for gone_limit wall seconds, counted only after start_limit wall seconds from
    now, the time its launch file has to start them; the graph is asked at most every
    GRAPH_POLL."""

    def __init__(self, graph, start_limit, gone_limit):
        self._graph = graph
        self._start_limit = start_limit
        self._gone_limit = gone_limit
        self._started = time.monotonic()
        self._gone_since = None
        self._next_look = self._started

    def gone(self):
        now = time.monotonic()
        if now < self._next_look:
            return False
        self._next_look = now + GRAPH_POLL
        if solution_running(self._graph) or now - self._started < self._start_limit:
            self._gone_since = None
        elif self._gone_since is None:
            self._gone_since = now
        return self._gone_since is not None and now - self._gone_since > self._gone_limit
