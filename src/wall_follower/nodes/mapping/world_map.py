"""world_map: the simulated world's walls on `map`, as map_server serves a map.

Reads the world file the simulation runs (the package's own world file
reader, for the built-in simulator and real stageros alike) and publishes
it once, latched: `map` (nav_msgs/OccupancyGrid) and `map_metadata`, in the
first robot's odometry frame (wall_follower.sim.world_map says why that
frame), so that rviz draws the walls under the robot. Parameters: the
table in wall_follower.params.mapping.world_map, read once at start.
"""
import rospy
from nav_msgs.msg import MapMetaData, OccupancyGrid

from wall_follower.nodes.shared.messages import pose_message
from wall_follower.nodes.shared.parameters import NodeParameters
from wall_follower.nodes.shared.startup import init_node
from wall_follower.params.mapping.world_map import TABLE
from wall_follower.sim.stage_interface import parse_pose, robot_prefix, world_path
from wall_follower.sim.world_map import world_map
from wall_follower.sim.worldfile import WorldFileError, load_world


def map_message(grid, frame, stamp):
    """The OccupancyGrid of a sim.world_map.WorldMap in `frame`."""
    msg = OccupancyGrid()
    msg.header.stamp = stamp
    msg.header.frame_id = frame
    msg.info.map_load_time = stamp
    msg.info.resolution = grid.resolution
    msg.info.height, msg.info.width = grid.values.shape
    msg.info.origin = pose_message(*grid.origin)
    msg.data = grid.values.reshape(-1).tolist()
    return msg


def main():
    init_node('world_map')
    values = NodeParameters(TABLE).snapshot()
    try:
        world = load_world(world_path(values['world']))
        start = parse_pose(values['pose'])
    except (WorldFileError, ValueError) as err:
        rospy.logerr('world_map: %s', err)
        return 1
    frame = robot_prefix(0, len(world.robots)) + 'odom'
    msg = map_message(world_map(world, start), frame, rospy.Time.now())
    map_pub = rospy.Publisher('map', OccupancyGrid, queue_size=1, latch=True)
    meta_pub = rospy.Publisher('map_metadata', MapMetaData, queue_size=1, latch=True)
    map_pub.publish(msg)
    meta_pub.publish(msg.info)
    rospy.loginfo('world_map: %s, %dx%d cells of %.3f m, in frame %s', world.path,
                  msg.info.width, msg.info.height, msg.info.resolution, frame)
    rospy.spin()
    return 0
