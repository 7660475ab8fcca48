"""line_follower: keeps the robot's base on a line on the floor, seen by its camera.

Each new frame (nodes.image_input.LatestImage, answered through the
DriveLoop every driving node shares) is masked by the line's colour; the
mask's pixels are put on the floor with the camera's camera_info and tf
(nodes.camera_floor), into the odometry frame, where vision.line_path
remembers the line's path and vision.line_pursuit steers the base along
it (~controller pursuit); or, as the lab's baseline, the slice centroid's
pixel offset steers (~controller pixel_p). Safe as every driving node:
clamped to ~max_linear and ~max_angular, stopped while the newest image is
older than ~image_timeout or unreadable (a warning says why), never
forward without line known ahead of the base, a zero Twist on shutdown. A
lost line is searched for by turning in place only; at the line's end the
robot stops for good. Its parameters (params/line_follower.py) are tuned
live (dynparam), the change applied at the next frame.
"""
import rospy
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Path

from wall_follower.cfg import LineFollowerConfig
from wall_follower.control.motion import STOP, Answer
from wall_follower.nodes.camera_floor import CameraFloor
from wall_follower.nodes.common import init_node, pose_message
from wall_follower.nodes.drive_loop import drive_loop, take_retuned
from wall_follower.nodes.image_input import LatestImage
from wall_follower.nodes.parameters import NodeParameters
from wall_follower.params import pick
from wall_follower.params.line_follower import PATH, PURSUIT, RULES, TABLE
from wall_follower.vision.line_image import hsv_bounds, line_mask, line_pixels
from wall_follower.vision.line_path import LinePath
from wall_follower.vision.line_pursuit import (
    FINISHED, FOLLOW, LOST, SEARCH, LinePursuit, from_base_frame, in_base_frame, known_ahead)
from wall_follower.vision.pixel_p import PixelP

NAME = 'line_follower'
STATE_NEWS = {
    FOLLOW: 'following the line',
    SEARCH: 'the line is lost; searching for it by turning in place',
    LOST: 'the search found no line; stopped until one is seen',
    FINISHED: "reached the line's end; stopped",
}


class LineFollowerNode(object):

    def __init__(self):
        self.params = NodeParameters(TABLE, LineFollowerConfig, rules=RULES,
                                     read_at_start=('compressed',))
        values = self.params.snapshot()
        self.images = LatestImage(values['compressed'])
        self.loop = drive_loop(NAME, values, self.images, ahead_missing='no line known')
        self.camera = CameraFloor(values)
        self.memory = LinePath(**pick(values, PATH))
        self.pursuit = LinePursuit(**pick(values, PURSUIT))
        self.path_pub = rospy.Publisher('line_path', Path, queue_size=1)
        self._configure(values)
        self._state = None

    def _configure(self, values):
        self.values = values
        self.bounds = hsv_bounds(values)
        self.camera.retune(values)
        self.memory.reconfigure(**pick(values, PATH))
        self.pursuit.reconfigure(**pick(values, PURSUIT))
        self.pixel_p = PixelP(values['p_speed'], values['p_gain'], values['slice_top'],
                              values['slice_depth'])

    def run(self):
        rospy.loginfo('%s: following the line seen on %s with the %s controller', NAME,
                      self.images.topic, self.values['controller'])
        self.loop.run(self._answer, on_clock_reset=self._restart)
        return 0

    def _restart(self):
        """ROS time moved back (a simulator restarted): forget the path and start afresh."""
        self.memory.forget()
        self.pursuit = LinePursuit(**pick(self.values, PURSUIT))

    def _answer(self, frame, _taken):
        values = take_retuned(self.params, self.loop)
        if values is not None:
            self._configure(values)
        mask = line_mask(frame.image, self.bounds)
        if self.values['controller'] == 'pixel_p':
            command = self.pixel_p.update(mask)
            return Answer(command, command != STOP)
        projection, problem = self.camera.projection(frame.frame_id, frame.stamp)
        base = None
        if projection is not None:
            base, problem = self.camera.base_pose(frame.stamp)
        if base is None:
            self.loop.warn('%s; stopped' % problem)
            return Answer(STOP, False)
        margin = self.values['view_margin']

        def in_view(points):
            return projection.sees(in_base_frame(points, base), margin)

        seen = from_base_frame(projection.to_floor(
            line_pixels(mask, self.values['pixel_stride'])), base)
        path = self.memory.update(seen, in_view, base, lambda point: in_view(point)[0])
        command = self.pursuit.update(path, self.memory.end_seen, base)
        known = known_ahead(path, base, self.loop.ahead_half_width) if len(path) else False
        self._tell_state()
        self._publish_path(path, frame.stamp)
        return Answer(command, known)

    def _tell_state(self):
        if self.pursuit.state != self._state:
            self._state = self.pursuit.state
            log = rospy.loginfo if self._state in (FOLLOW, FINISHED) else rospy.logwarn
            log('%s: %s', NAME, STATE_NEWS[self._state])

    def _publish_path(self, path, stamp):
        if self.path_pub.get_num_connections() == 0:
            return
        msg = Path()
        msg.header.frame_id = self.values['odom_frame']
        msg.header.stamp = stamp
        for x, y in path:
            pose = PoseStamped()
            pose.header = msg.header
            pose.pose = pose_message(x, y, 0.0)
            msg.poses.append(pose)
        self.path_pub.publish(msg)


def main():
    init_node(NAME)
    return LineFollowerNode().run()
