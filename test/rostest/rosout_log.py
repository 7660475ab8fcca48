"""What the nodes of a rostest have logged, as heard on /rosout, for checks of their messages."""
import rosgraph
import rospy
from rosgraph_msgs.msg import Log

from waiting import wait_until

# Wall seconds for the connections to the nodes named.
CONNECT_LIMIT = 30.0


class RosoutLog(object):
    """Every /rosout line heard from its creation on, as (node name, level, text).

    Each node publishes /rosout itself (rostest runs no rosout node to
    gather them), over a connection of its own, and a line logged before
    that connection is up is lost. So the constructor returns only once it
    is connected to each of the nodes named: a check that then sets off
    what it waits to hear of misses none of it.
    """

    def __init__(self, *nodes):
        self._lines = []
        self._subscriber = rospy.Subscriber('/rosout', Log, self._on_log, queue_size=1000)
        for node in nodes:
            if not wait_until(lambda: self._connected_to(node), CONNECT_LIMIT):
                raise AssertionError('no /rosout connection to %s after %.0f s'
                                     % (node, CONNECT_LIMIT))

    def _connected_to(self, node):
        """Whether the node runs and this subscriber has a connection to its publisher."""
        try:
            uri = rosgraph.Master(rospy.get_name()).lookupNode(node)
        except rosgraph.MasterError:
            return False
        # getBusInfo's rows (as rosnode info reads them): a subscriber's give the
        # publisher's URI second.
        return any(row[1] == uri for row in self._subscriber.impl.get_stats_info())

    def _on_log(self, msg):
        self._lines.append((msg.name, msg.level, msg.msg))

    def lines(self, node=None, fragment='', level=Log.DEBUG):
        """The texts logged by node (any node: None) at level (a rosgraph_msgs/Log level)
        or above that contain fragment."""
        return [text for name, at, text in list(self._lines)
                if (node is None or name == node) and at >= level and fragment in text]

    def said(self, node, fragment, level=Log.DEBUG):
        """True once node (any node: None) has logged a text containing fragment at level
        or above."""
        return bool(self.lines(node, fragment, level))
