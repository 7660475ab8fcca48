"""The `map_saver` node: map_server's `map_saver -f NAME`, plus saving when a lap ends.

Without --after-lap it saves the first `map` it hears and exits, as
map_server's map_saver does. With --after-lap it first waits for the
record_odom action's result (the course's lap is over), then saves the
first map stamped at or after it, so the saved map holds the whole lap.

Parameters: the table in wall_follower.params.mapping.map_saver, read once at
start; the command line's flags, map_server's map_saver's, win over them.

A map that cannot be one (mapfile.map_problem: no cells, data that do not
fill width x height, a resolution that is not positive, an origin that is
not finite) is not written: the node says why and exits with status 1.
"""
import argparse
import os
import threading

import rospy
from nav_msgs.msg import OccupancyGrid

import numpy as np

from wall_follower.mapping.mapfile import map_problem, save_map
from wall_follower.msg import OdomRecordActionResult
from wall_follower.nodes.shared.messages import yaw_of
from wall_follower.nodes.shared.parameters import NodeParameters
from wall_follower.nodes.shared.startup import init_node
from wall_follower.params.mapping.map_saver import TABLE


class MapSaver(object):
    def __init__(self, name, occupied, free, after_lap):
        self.name, self.occupied, self.free = name, occupied, free
        self.lap_end = None if after_lap else rospy.Time(0)
        self.done = threading.Event()
        self.saved = False
        self._lock = threading.Lock()
        if after_lap:
            rospy.loginfo('map_saver: waiting for the lap to end (record_odom/result)')
            rospy.Subscriber('record_odom/result', OdomRecordActionResult, self.on_result)
        rospy.loginfo('map_saver: waiting for the map')
        rospy.Subscriber('map', OccupancyGrid, self.on_map, queue_size=1)

    def on_result(self, msg):
        with self._lock:
            if self.lap_end is None:
                self.lap_end = msg.header.stamp
                rospy.loginfo('map_saver: lap over at %.1f s; saving the next map',
                              msg.header.stamp.to_sec())

    def on_map(self, msg):
        with self._lock:
            if self.done.is_set() or self.lap_end is None or msg.header.stamp < self.lap_end:
                return
            info = msg.info
            rospy.loginfo('map_saver: received a %d X %d map @ %.3f m/pix', info.width,
                          info.height, info.resolution)
            origin = (info.origin.position.x, info.origin.position.y,
                      yaw_of(info.origin.orientation))
            problem = map_problem(info.width, info.height, len(msg.data), info.resolution,
                                  origin)
            if problem:
                rospy.logerr('map_saver: not saving the map on %s: %s', rospy.resolve_name('map'),
                             problem)
                self.done.set()
                return
            data = np.array(msg.data, dtype=np.int8).reshape(info.height, info.width)
            try:
                image, meta = save_map(self.name, data, info.resolution, origin,
                                       self.occupied, self.free)
            except (IOError, OSError) as err:
                rospy.logerr("map_saver: couldn't save the map to %s (%s)", self.name, err)
            else:
                rospy.loginfo('map_saver: wrote %s and %s', image, meta)
                self.saved = True
            self.done.set()


def main():
    init_node('map_saver')
    values = NodeParameters(TABLE).snapshot()
    parser = argparse.ArgumentParser(prog='map_saver', description=__doc__.splitlines()[0])
    parser.add_argument('-f', dest='name', default=values['file'],
                        help='file name, without .pgm/.yaml (default ~file, %(default)s)')
    parser.add_argument('--occ', type=int, default=values['occupied_threshold'],
                        help='occupied from this value on (1-100, default '
                        '~occupied_threshold, %(default)s)')
    parser.add_argument('--free', type=int, default=values['free_threshold'],
                        help='free up to this value (0-100, default ~free_threshold, '
                        '%(default)s)')
    parser.add_argument('--after-lap', action='store_true', default=values['after_lap'],
                        help='save the first map after the record_odom result (default '
                        '~after_lap)')
    args = parser.parse_args(rospy.myargv()[1:])
    if not 1 <= args.occ <= 100 or not 0 <= args.free <= 100 or args.occ <= args.free:
        rospy.logerr('map_saver: need 0 <= --free < --occ <= 100 (got --free %d --occ %d)',
                     args.free, args.occ)
        return 1
    name = os.path.expanduser(args.name)   # a launch file's ~file is not expanded by a shell
    directory = os.path.dirname(os.path.abspath(name))
    if not os.path.isdir(directory):
        rospy.logerr('map_saver: no directory %s for the map', directory)
        return 1
    saver = MapSaver(name, args.occ, args.free, args.after_lap)
    while not rospy.is_shutdown() and not saver.done.wait(0.1):
        pass
    return 0 if saver.saved or not saver.done.is_set() else 1
