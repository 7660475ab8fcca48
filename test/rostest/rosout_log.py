"""What the nodes of a rostest have logged, as heard on /rosout, for checks of their messages."""
import rospy
from rosgraph_msgs.msg import Log


class RosoutLog(object):
    """Every /rosout line heard from its creation on, as (node name, level, text)."""

    def __init__(self):
        self._lines = []
        self._subscriber = rospy.Subscriber('/rosout', Log, self._on_log, queue_size=1000)

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
