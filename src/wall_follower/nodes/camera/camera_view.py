"""camera_view: the lab's follower.py and follower_opencv.py, looking at the camera's frames.

Logs the frames' size, encoding and rate (in ROS time) every
~report_period; shows them in an OpenCV window where a display exists
(~window), and otherwise, given ~snapshot_dir, writes a PNG snapshot there
every ~snapshot_period. A frame that cannot be read is a warning, never a
traceback.
"""
import os
import threading

import cv2
import rospy

from wall_follower.nodes.shared.latest_image import image_topics
from wall_follower.nodes.shared.parameters import NodeParameters
from wall_follower.nodes.shared.startup import init_node
from wall_follower.params.camera.camera_view import TABLE

NAME = 'camera_view'
WINDOW = 'camera_view'


class CameraView(object):

    def __init__(self):
        self.values = NodeParameters(TABLE).snapshot()
        self.window = self.values['window'] and bool(os.environ.get('DISPLAY'))
        self.snapshot_dir = self.values['snapshot_dir']
        if self.snapshot_dir and not os.path.isdir(self.snapshot_dir):
            try:
                os.makedirs(self.snapshot_dir)
            except OSError as error:
                rospy.logfatal('%s: cannot start: ~snapshot_dir %s: %s', NAME, self.snapshot_dir,
                               error.strerror)
                raise SystemExit(1)
        self._lock = threading.Lock()
        self._latest = None
        self._frames = 0
        self._described = None
        self._counted_since = None
        self._snapshot_at = None
        self._snapshots = 0
        topic, kind, self._read = image_topics(self.values['compressed'])
        self._sub = rospy.Subscriber(topic, kind, self._on_image, queue_size=1,
                                     buff_size=2 ** 24)

    def _on_image(self, msg):
        image, problem = self._read(msg)
        encoding = getattr(msg, 'encoding', None) or getattr(msg, 'format', '?')
        with self._lock:
            self._frames += 1
            if image is None:
                rospy.logwarn_throttle(5.0, '%s: %s', NAME, problem)
                return
            self._latest = image
            self._described = '%d x %d, %s' % (image.shape[1], image.shape[0], encoding)

    def run(self):
        rospy.loginfo('%s: looking at %s (%s)', NAME, self._sub.resolved_name,
                      'in a window' if self.window else (
                          'PNG snapshots in %s' % self.snapshot_dir if self.snapshot_dir
                          else 'reporting only'))
        rate = rospy.Rate(30.0)
        while not rospy.is_shutdown():
            now = rospy.get_time()
            self._report(now)
            with self._lock:
                image = self._latest
            if image is not None and self.window:
                cv2.imshow(WINDOW, image)
                cv2.waitKey(1)
            elif image is not None and self.snapshot_dir:
                self._snapshot(image, now)
            try:
                rate.sleep()
            except rospy.ROSInterruptException:
                break
        if self.window:
            cv2.destroyAllWindows()
        return 0

    def _report(self, now):
        if self._counted_since is None or now < self._counted_since:
            if now > 0.0:        # on simulated time, 0 until the first /clock
                with self._lock:
                    self._frames = 0
                self._counted_since = now
            return
        elapsed = now - self._counted_since
        if elapsed < self.values['report_period']:
            return
        with self._lock:
            frames, self._frames = self._frames, 0
            described = self._described
        self._counted_since = now
        if frames == 0:
            rospy.logwarn('%s: no frame on %s for %.1f s', NAME, self._sub.resolved_name,
                          elapsed)
        else:
            rospy.loginfo('%s: %s at %.1f Hz', NAME, described or 'no readable frame',
                          frames / elapsed)

    def _snapshot(self, image, now):
        if self._snapshot_at is not None and 0.0 <= now - self._snapshot_at < \
                self.values['snapshot_period']:
            return
        self._snapshot_at = now
        path = os.path.join(self.snapshot_dir, 'camera_%04d.png' % self._snapshots)
        if write_whole(path, image):
            self._snapshots += 1
            rospy.loginfo_throttle(30.0, '%s: snapshot %s', NAME, path)
        else:
            rospy.logwarn_throttle(30.0, '%s: cannot write %s', NAME, path)


def write_whole(path, image):
    """Write image to path (its format by its extension) so that path never holds part of
    it: written under a hidden name beside it first, then renamed, which is atomic. A reader
    polling the directory (a test, a viewer) never reads a snapshot half written. False when
    it cannot be written."""
    directory, name = os.path.split(path)
    writing = os.path.join(directory, '.writing-' + name)
    try:
        written = cv2.imwrite(writing, image)
        if written:
            os.replace(writing, path)
    except (cv2.error, OSError):
        written = False
    if not written and os.path.exists(writing):
        os.unlink(writing)
    return written


def main():
    init_node(NAME)
    return CameraView().run()
