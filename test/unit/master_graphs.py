"""Masters' graphs, for the unit tests of what looks for an action server in them."""


def server_graph(namespace, node):
    """A getSystemState() answer in which node serves the action namespace: it publishes
    status, result and feedback, and subscribes to goal and cancel."""
    return ([(namespace + '/' + topic, [node]) for topic in ('status', 'result', 'feedback')],
            [(namespace + '/' + topic, [node]) for topic in ('goal', 'cancel')], [])


class Graph(object):
    """A master's getSystemState(): each of `states` in turn, then the last for good; a
    state that is an exception is raised instead."""

    def __init__(self, *states):
        self.states = list(states)
        self.asked = 0

    def __call__(self):
        self.asked += 1
        state = self.states[min(self.asked, len(self.states)) - 1]
        if isinstance(state, Exception):
            raise state
        return state
