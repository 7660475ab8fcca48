"""line_follower: keeps the robot's base on a line on the floor, seen by its camera.

Each new frame (nodes.shared.latest_image.LatestImage, answered through the
DriveLoop every driving node shares) goes through the line-following step
of vision.line_step, with the camera's floor projection from its
camera_info and tf and the base's pose at the frame's time
(nodes.shared.camera_floor): the line's colour is masked and must look like a
line on the floor (vision.line_check); then the pursuit steers the base
along the line's remembered path (~controller pursuit), or, as the lab's
baseline, the slice centroid's pixel offset steers (~controller pixel_p).
Safe as every driving node: clamped to ~max_linear and ~max_angular,
stopped while the newest image is older than ~image_timeout, unreadable,
stamped in the future, of another size than camera_info says, or not a
line (a throttled warning says why), never forward without the line
known ahead of the base, a zero Twist on shutdown. A lost line is
searched for by turning in place only, on frames of clear floor; at the
line's end the robot stops for good. Its parameters (params/camera/line_follower.py)
are tuned live (dynparam), the change applied at the next frame.
"""
import rospy
from geometry_msgs.msg import PoseStamped
from nav_msgs.msg import Path

from wall_follower.cfg import LineFollowerConfig
from wall_follower.control.motion import STOP, Answer
from wall_follower.nodes.shared.camera_floor import CameraFloor
from wall_follower.nodes.shared.drive_loop import drive_loop, take_retuned
from wall_follower.nodes.shared.latest_image import LatestImage
from wall_follower.nodes.shared.messages import pose_message
from wall_follower.nodes.shared.parameters import NodeParameters
from wall_follower.nodes.shared.startup import init_node
from wall_follower.params.camera.line_follower import RULES, TABLE
from wall_follower.vision.line_pursuit import FINISHED, FOLLOW, LOST, SEARCH
from wall_follower.vision.line_step import LineStep

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
        self.values = self.params.snapshot()
        self.images = LatestImage(self.values['compressed'])
        self.loop = drive_loop(NAME, self.values, self.images, ahead_missing='no line known')
        self.camera = CameraFloor(self.values)
        self.step = LineStep(self.values)
        self.path_pub = rospy.Publisher('line_path', Path, queue_size=1)
        self._state = None

    def run(self):
        rospy.loginfo('%s: following the line seen on %s with the %s controller', NAME,
                      self.images.topic, self.values['controller'])
        self.loop.run(self._answer, on_clock_reset=self.step.restart)
        return 0

    def _answer(self, frame, _taken):
        values = take_retuned(self.params, self.loop)
        if values is not None:
            self.values = values
            self.camera.retune(values)
            self.step.reconfigure(values)
        projection, problem = self.camera.projection(frame.frame_id)
        base = None
        if projection is not None and self.step.needs_base:
            base, problem = self.camera.base_pose(frame.stamp)
        if problem is None:
            step = self.step.update(frame.image, projection, base, self.loop.ahead_half_width)
            problem = step.problem
        if problem is not None:
            self.loop.warn('%s; stopped' % problem)
            return Answer(STOP, False)
        if step.state is not None:
            self._tell_state(step.state)
            self._publish_path(step.path, frame.stamp)
        return step.answer

    def _tell_state(self, state):
        if state != self._state:
            self._state = state
            log = rospy.loginfo if state in (FOLLOW, FINISHED) else rospy.logwarn
            log('%s: %s', NAME, STATE_NEWS[state])

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
