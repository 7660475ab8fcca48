#!/usr/bin/env python3
"""Scores one lap of a line world from base_pose_ground_truth, on whatever master ROS_MASTER_URI
names, and writes the figures as JSON: for checks that run a simulation on a master of its own.

    line_lap_score.py WORLD WALL_LIMIT OUTPUT
"""
import json
import sys
import threading
import time

import numpy as np
import rospy
from nav_msgs.msg import Odometry

from wall_follower.evaluation.scoring.line import cross_track, progress
from wall_follower.evaluation.scoring.line_track import load_centreline
from wall_follower.sim.stage_interface import world_path


def main(world, limit, output):
    line = load_centreline(world_path(world))
    lock = threading.Lock()
    poses = []

    def on_truth(msg):
        p = msg.pose.pose.position
        with lock:
            poses.append((msg.header.stamp.to_sec(), p.x, p.y))
    rospy.init_node('line_lap_score', anonymous=True, disable_signals=True)
    rospy.Subscriber('base_pose_ground_truth', Odometry, on_truth, queue_size=10000)
    deadline = time.monotonic() + limit
    figures = {'lapped': False}
    while time.monotonic() < deadline:
        time.sleep(0.5)
        with lock:
            truth = np.array(poses)
        if len(truth) < 2:
            continue
        driven = progress(line, truth[:, 1:3])
        figures['driven'] = float(driven[-1])
        if driven[-1] >= line.length:
            lap = truth[:int(np.argmax(driven >= line.length)) + 1]
            rms, worst = cross_track(line, lap[:, 1:3])
            figures.update(lapped=True, rms=rms, max=worst, time=lap[-1, 0] - lap[0, 0],
                           mean_speed=line.length / (lap[-1, 0] - lap[0, 0]))
            break
    with open(output, 'w') as stream:
        json.dump(figures, stream)
    rospy.signal_shutdown('scored')


if __name__ == '__main__':
    main(sys.argv[1], float(sys.argv[2]), sys.argv[3])
