"""The newest camera frame, decoded to BGR and checked, for nodes that see the line.

Frames come as sensor_msgs/Image in any encoding cv_bridge reads, or as
sensor_msgs/CompressedImage (the real Waffle Pi's raspicam publishes
compressed, on `<image>/compressed` as image_transport names it). A frame
that cannot be read is held with the reason in words, never handed on,
as LatestScan holds a bad scan; LatestImage offers what a DriveLoop asks
of LatestScan, so that the loop runs on images as it runs on scans. A
frame stamped ahead of ROS time by more than the loop's timeout is stale
input too (a camera whose clock runs ahead, or a stamp years away, which
no time arithmetic downstream must meet).
"""
import threading
from collections import namedtuple

import rospy
from cv_bridge import CvBridge, CvBridgeError
from sensor_msgs.msg import CompressedImage, Image

from wall_follower.control.stamps import ahead_problem
from wall_follower.nodes.shared.connections import keep_connected
from wall_follower.nodes.shared.latest_scan import Reading, arrived
from wall_follower.params.driving import CAMERA_INPUT
from wall_follower.vision.image_check import decode_compressed, raw_image_problem

Frame = namedtuple('Frame', ['image', 'frame_id', 'stamp', 'problem'])
"""One checked frame: its BGR image (None if unreadable), its header's frame_id and stamp
(rospy.Time), and what is wrong with it (None if nothing)."""

_BRIDGE = CvBridge()


def read_image(msg):
    """(BGR image, None) of a sensor_msgs/Image, or (None, what is wrong)."""
    problem = raw_image_problem(msg.encoding, msg.height, msg.width, msg.step, len(msg.data))
    if problem is not None:
        return None, problem
    try:
        return _BRIDGE.imgmsg_to_cv2(msg, 'bgr8'), None
    except (CvBridgeError, ValueError, TypeError) as error:
        lines = str(error).strip().splitlines()
        return None, 'a %s image cv_bridge cannot turn into colour: %s' % (
            msg.encoding, lines[-1] if lines else type(error).__name__)


def read_compressed(msg):
    """(BGR image, None) of a sensor_msgs/CompressedImage, or (None, what is wrong)."""
    return decode_compressed(bytes(msg.data))


def image_topics(compressed):
    """(topic, message type, reader) of the camera: `image`, or `image`/compressed."""
    if compressed:
        return rospy.resolve_name('image') + '/compressed', CompressedImage, read_compressed
    return 'image', Image, read_image


class LatestImage(object):
    """Keeps the newest frame, decoded and checked, and knows when it has gone stale.

    Age is counted in ROS time from its arrival (latest_scan.arrived), as
    LatestScan counts a scan's; the time it was taken is its header stamp
    (its arrival if the stamp is zero). compressed: read CompressedImage
    (image_topics).
    """

    parameters = CAMERA_INPUT   # the node's parameters that set a DriveLoop on it

    def __init__(self, compressed=False):
        self._latest = (None, None)      # (Frame, arrival), replaced as one
        self._arrived = threading.Condition()
        topic, kind, self._read = image_topics(compressed)
        self._sub = rospy.Subscriber(topic, kind, self._on_image, queue_size=1, buff_size=2 ** 24)
        keep_connected([self._sub])

    @property
    def topic(self):
        return self._sub.resolved_name

    def _on_image(self, msg):
        arrival = arrived(msg.header.stamp)
        stamp = msg.header.stamp if not msg.header.stamp.is_zero() else arrival
        image, problem = self._read(msg)
        with self._arrived:
            self._latest = (Frame(image, msg.header.frame_id, stamp, problem), arrival)
            self._arrived.notify_all()

    def forget(self):
        self._latest = (None, None)

    def wait_for_newer(self, seen, timeout):
        """Wait until a frame other than `seen` (a Reading's check) comes, at most timeout
        wall s."""
        with self._arrived:
            if self._latest[0] is seen:
                self._arrived.wait(timeout)

    def latest(self, timeout):
        """The newest frame as a Reading: check and view the Frame, taken its stamp [s], if
        readable and fresh; else view None and the problem in words."""
        with self._arrived:
            frame, arrival = self._latest
            now = rospy.Time.now()
            if frame is not None and arrival.is_zero() and not now.is_zero():
                arrival = now
                self._latest = (frame, arrival)
        if frame is None or (now - arrival).to_sec() > timeout:
            return Reading(frame, None, None, 'no image on %s for %.1f s' % (self.topic, timeout))
        problem = frame.problem or ahead_problem(frame.stamp.to_sec(), now.to_sec())
        if problem is not None:
            return Reading(frame, None, None, 'the image on %s is unusable: %s' % (
                self.topic, problem))
        return Reading(frame, frame, frame.stamp.to_sec(), None)
