"""line_mask: the lab's follower_color_filter.py and follower_line_finder.py, as one node.

For each camera frame it publishes `line_mask` (mono8: 255 where the
frame has the line's colour, the HSV bounds of params/camera/line_mask.py) and
`line_debug` (the frame, bgr8, with the centroid of the mask's thin slice
marked by a red dot), both stamped as the frame. The bounds and the slice
are dynamic_reconfigure parameters: `rosrun rqt_reconfigure
rqt_reconfigure`, or `rosrun dynamic_reconfigure dynparam set /line_mask
hue_low 15`, applied at the next frame. A frame that cannot be read is a
warning, never a traceback.
"""
import rospy
from cv_bridge import CvBridge
from sensor_msgs.msg import Image

from wall_follower.cfg import LineMaskConfig
from wall_follower.nodes.shared.latest_image import image_topics
from wall_follower.nodes.shared.parameters import NodeParameters
from wall_follower.nodes.shared.startup import init_node
from wall_follower.params.camera.line_mask import RULES, TABLE
from wall_follower.vision.line_image import hsv_bounds, line_mask, mark_centroid, slice_centroid

NAME = 'line_mask'


class LineMaskNode(object):

    def __init__(self):
        self.params = NodeParameters(TABLE, LineMaskConfig, rules=RULES,
                                     read_at_start=('compressed',))
        self.values = self.params.snapshot()
        self.bridge = CvBridge()
        self.mask_pub = rospy.Publisher('line_mask', Image, queue_size=1)
        self.debug_pub = rospy.Publisher('line_debug', Image, queue_size=1)
        topic, kind, self._read = image_topics(self.values['compressed'])
        self._sub = rospy.Subscriber(topic, kind, self._on_image, queue_size=1,
                                     buff_size=2 ** 24)
        self._found = None

    def _on_image(self, msg):
        values = self.params.take_update()
        if values is not None:
            self.values = values
        image, problem = self._read(msg)
        if image is None:
            rospy.logwarn_throttle(5.0, '%s: %s', NAME, problem)
            return
        mask = line_mask(image, hsv_bounds(self.values))
        centroid = slice_centroid(mask, self.values['slice_top'], self.values['slice_depth'])
        if (centroid is not None) != self._found:
            self._found = centroid is not None
            rospy.loginfo('%s: %s', NAME, 'the line is in the slice' if self._found
                          else 'no line in the slice')
        self._publish(self.mask_pub, mask, 'mono8', msg.header)
        self._publish(self.debug_pub, mark_centroid(image, centroid, self.values['dot_radius']),
                      'bgr8', msg.header)

    def _publish(self, publisher, image, encoding, header):
        if publisher.get_num_connections() == 0:
            return
        out = self.bridge.cv2_to_imgmsg(image, encoding)
        out.header = header
        publisher.publish(out)

    def run(self):
        rospy.loginfo('%s: masking the frames of %s', NAME, self._sub.resolved_name)
        rospy.spin()
        return 0


def main():
    init_node(NAME)
    return LineMaskNode().run()
