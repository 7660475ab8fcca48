"""What rviz shows of the course that no other topic carries: the band and find_wall's answer.

Both are visualization_msgs/Marker in base_link, which every robot and
simulator here has, published latched by wall_following:

- the band (`~band`): two lines beside the robot at the edges of the
  course's band (evaluation.scoring.course.BAND) right of the laser, frame-locked
  so that they move with the robot: the wall should run between them;
- find_wall's answer (`~find_wall_result`): an arrow where the robot stood
  when find_wall answered, green for a wall found, red for none; not
  frame-locked, so it stays on the floor where it was put.
"""
import rospy
from geometry_msgs.msg import Point
from std_msgs.msg import ColorRGBA
from visualization_msgs.msg import Marker

from wall_follower.evaluation.scoring.course import BAND

FRAME = 'base_link'
BAND_LENGTH = 0.5          # m of each line, centred on the laser
LINE_WIDTH = 0.01          # m
BAND_COLOUR = ColorRGBA(1.0, 0.8, 0.1, 0.9)
FOUND_COLOUR = ColorRGBA(0.1, 0.8, 0.2, 1.0)
NOT_FOUND_COLOUR = ColorRGBA(0.9, 0.1, 0.1, 1.0)
ARROW = (0.25, 0.04, 0.04)  # m: length, width, height


def band_marker(laser_x, band=BAND):
    """Lines along the robot at the band's distances right of a laser laser_x ahead of
    base_link."""
    marker = Marker(type=Marker.LINE_LIST, action=Marker.ADD, frame_locked=True)
    marker.header.frame_id = FRAME
    marker.ns = 'band'
    marker.pose.orientation.w = 1.0
    marker.scale.x = LINE_WIDTH
    marker.color = BAND_COLOUR
    for distance in band:
        for x in (laser_x - BAND_LENGTH / 2.0, laser_x + BAND_LENGTH / 2.0):
            marker.points.append(Point(x, -distance, 0.0))
    return marker


def find_wall_marker(found, stamp):
    """An arrow at base_link at time stamp, coloured by find_wall's answer."""
    marker = Marker(type=Marker.ARROW, action=Marker.ADD)
    marker.header.frame_id = FRAME
    marker.header.stamp = stamp
    marker.ns = 'find_wall'
    marker.pose.orientation.w = 1.0
    marker.scale.x, marker.scale.y, marker.scale.z = ARROW
    marker.color = FOUND_COLOUR if found else NOT_FOUND_COLOUR
    return marker


class CourseMarkers(object):
    """The latched publishers of both markers (private topics of the node)."""

    def __init__(self):
        self._band = rospy.Publisher('~band', Marker, queue_size=1, latch=True)
        self._find_wall = rospy.Publisher('~find_wall_result', Marker, queue_size=1, latch=True)

    def show_band(self, laser_x):
        self._band.publish(band_marker(laser_x))

    def show_find_wall(self, found):
        self._find_wall.publish(find_wall_marker(found, rospy.Time.now()))
