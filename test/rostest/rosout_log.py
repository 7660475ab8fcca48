"""What the nodes of a rostest have logged, as heard on /rosout, for checks of their messages."""
import rospy
from rosgraph_msgs.msg import Log


class RosoutLog(object):
    """Every /rosout line heard from its creation on, as (node name, text)."""

    def __init__(self):
        self._lines = []
        self._subscriber = rospy.Subscriber('/rosout', Log, self._on_log, queue_size=1000)

    def _on_log(self, msg):
        self._lines.append((msg.name, msg.msg))

    def lines(self, node=None, fragment=''):
        """The texts logged by node (any node: None) that contain fragment."""
        return [text for name, text in list(self._lines)
                if (node is None or name == node) and fragment in text]

    def said(self, node, fragment):
        """True once node (any node: None) has logged a text containing fragment."""
        return bool(self.lines(node, fragment))
