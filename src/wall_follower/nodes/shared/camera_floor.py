"""The camera's floor projection and the robot's pose at a frame's time, from camera_info and tf.

Nothing about the camera is assumed: its size and focal lengths come
from camera_info, its height and tilt from the tf of the frame named in
each image's header, in the floor frame (params.camera.line_follower's
floor_frame), read in the convention frame_convention names
(vision.floor). The robot's pose at the frame's time comes from the tf of
the floor frame in the odometry frame.

tf is read through nodes.shared.tf_lookup, its waits in wall time (in
lockstep the clock stands still until the node commands again), never at
a time beyond the buffer's reach of now (tf2 aborts the process on one).
The projection is kept while
camera_info, the camera's tf and the settings stay the same, so that what
is worked out from it once (vision.line_check's floor grid) is kept too.
"""
import threading

import rospy
import tf2_ros
from sensor_msgs.msg import CameraInfo

from wall_follower.nodes.shared.messages import yaw_of
from wall_follower.nodes.shared.tf_lookup import lookup
from wall_follower.vision.floor import (
    FloorProjection, Intrinsics, camera_pose, convention_of)

CACHE = 10.0          # s of tf the buffer keeps


class CameraFloor(object):
    """camera_info and tf, read for one node.

    values: the node's parameters (floor_frame, odom_frame, tf_timeout,
    frame_convention, max_distance), replaced by retune().
    """

    def __init__(self, values):
        self.values = values
        self._buffer = tf2_ros.Buffer(cache_time=rospy.Duration(CACHE))
        self._listener = tf2_ros.TransformListener(self._buffer)
        self._lock = threading.Lock()
        self._intrinsics = None
        self._info_problem = 'no camera_info yet'
        self._kept = (None, None)     # (what a projection was made from, the projection)
        self._sub = rospy.Subscriber('camera_info', CameraInfo, self._on_info, queue_size=1)

    def retune(self, values):
        self.values = values

    def _on_info(self, msg):
        try:
            intrinsics, problem = Intrinsics.from_camera_info(msg.K, msg.width, msg.height), None
        except ValueError as error:
            intrinsics, problem = None, 'unusable camera_info on %s: %s' % (
                self._sub.resolved_name, error)
        with self._lock:
            self._intrinsics, self._info_problem = intrinsics, problem

    def projection(self, frame_id):
        """(FloorProjection, None) for a frame from the camera frame_id, at its newest tf, or
        (None, what is missing)."""
        with self._lock:
            intrinsics, problem = self._intrinsics, self._info_problem
        if intrinsics is None:
            return None, problem
        if not frame_id:
            return None, 'the image names no camera frame'
        transform, problem = self._lookup(self.values['floor_frame'], frame_id, rospy.Time(0))
        if transform is None:
            return None, problem
        convention = convention_of(frame_id, self.values['frame_convention'])
        t, q = transform.translation, transform.rotation
        made_from = (intrinsics, (t.x, t.y, t.z), (q.x, q.y, q.z, q.w), convention,
                     self.values['max_distance'])
        if made_from != self._kept[0]:
            axes, centre = camera_pose(made_from[1], made_from[2], convention)
            try:
                projection = FloorProjection(intrinsics, axes, centre,
                                             self.values['max_distance'])
            except ValueError as error:
                return None, 'camera frame %s: %s' % (frame_id, error)
            self._kept = (made_from, projection)
        return self._kept[1], None

    def base_pose(self, stamp):
        """((x, y, yaw) of the floor frame in the odometry frame at stamp, None), or (None,
        what is missing)."""
        transform, problem = self._lookup(self.values['odom_frame'], self.values['floor_frame'],
                                          stamp)
        if transform is None:
            return None, problem
        return (transform.translation.x, transform.translation.y,
                yaw_of(transform.rotation)), None

    def _lookup(self, target, source, stamp):
        found, problem = lookup(self._buffer, target, source, stamp, self.values['tf_timeout'],
                                span=CACHE)
        if found is None:
            return None, 'no tf from %s to %s at %.3f s: %s' % (
                target, source, stamp.to_sec(), problem)
        return found.transform, None
