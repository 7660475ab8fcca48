#!/usr/bin/env python3
"""Records real Stage's localization "odom" for the built-in simulator to be held to.

Runs real stageros (its window under `xvfb-run -a`, so that the world's
`speedup 1` paces it and a command streamed on each /clock tick drives each
update) on the odometry worlds of test/data/stage_reference, drives every
robot of a world through the same plan (straight, turn in place, a command
past the default velocity bounds, an arc commanded with a sideways velocity
too, /reset_positions, a reverse arc),
and writes /odom and /base_pose_ground_truth of every update to
test/data/stage_reference/stage_odometry.json. test/unit/
test_stage_odometry_reference.py replays it through the built-in simulator.

Needs real Stage and stage_ros (tools/build-real-stage) and this package's
workspace in the shell, and xvfb-run without a display:

    source PREFIX/setup.bash && source WS/devel/setup.bash --extend
    /usr/bin/python3 tools/record_stage_odometry.py [--out FILE]

Everything runs on a private master on a free port; every process it starts
is stopped by its id.
"""
import argparse
import datetime
import json
import math
import os
import threading
import time

import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from std_srvs.srv import Empty

from wall_follower.evaluation.scoring.stage_odometry import (GROUND_TRUTH_FIELDS, ODOM_FIELDS,
                                                             step_scale_errors)
from wall_follower.sim.worldfile import load_world

from real_stage_session import stage_session

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'test', 'data',
                    'stage_reference')
# (run name, world file): the world without odom_error twice, to see whether
# Stage draws its errors again for a new run.
RUNS = (('degrees', 'odom_degrees.world'), ('radians', 'odom_radians.world'),
        ('default-1', 'odom_default.world'), ('default-2', 'odom_default.world'))
# The drive plan, the same for every robot: (label, vx, vy, wz, seconds of sim
# time); a 'reset' calls /reset_positions while every robot stands still.
PLAN = (('still', 0.0, 0.0, 0.0, 0.3),
        ('straight', 0.15, 0.0, 0.0, 2.0),
        ('still', 0.0, 0.0, 0.0, 0.5),
        ('turn in place', 0.0, 0.0, 0.4, 2.0),
        ('still', 0.0, 0.0, 0.0, 0.5),
        ('past the velocity bounds', 1.5, 0.0, 2.0, 0.5),
        ('still', 0.0, 0.0, 0.0, 0.5),
        ('arc, commanded sideways too', 0.12, 0.1, -0.3, 3.0),
        ('still', 0.0, 0.0, 0.0, 0.5),
        ('reset', 0.0, 0.0, 0.0, 0.0),
        ('still', 0.0, 0.0, 0.0, 0.5),
        ('reverse arc', -0.1, 0.0, 0.45, 2.0),
        ('still', 0.0, 0.0, 0.0, 0.5))
INTERVAL = 0.1          # the worlds' interval_sim [s]
DIGITS = 12             # poses and twists are rounded to this many decimals
START_TIMEOUT = 30.0    # wall seconds for stageros to publish its first update


def yaw_of(quaternion):
    """stageros writes a yaw-only quaternion (tf::createQuaternionMsgFromYaw)."""
    return 2.0 * math.atan2(quaternion.z, quaternion.w)


class Recorder(object):
    """Streams the plan's command on each /clock tick and keeps each update's
    odometry and ground truth, per robot, by stamp."""

    def __init__(self, robot_count):
        prefixes = ['robot_%d/' % i for i in range(robot_count)] if robot_count > 1 else ['']
        self.lock = threading.Lock()
        self.ticked = threading.Condition(self.lock)
        self.clock = None
        self.command = (0.0, 0.0, 0.0)
        self.cmd_log = []
        self.odom = [dict() for _ in prefixes]
        self.gt = [dict() for _ in prefixes]
        self.publishers = [rospy.Publisher('/%scmd_vel' % p, Twist, queue_size=10)
                           for p in prefixes]
        self.subscribers = [rospy.Subscriber('/clock', Clock, self.on_clock, queue_size=10)]
        for index, prefix in enumerate(prefixes):
            self.subscribers.append(rospy.Subscriber(
                '/%sodom' % prefix, Odometry, self.on_odom, (self.odom[index], True),
                queue_size=100))
            self.subscribers.append(rospy.Subscriber(
                '/%sbase_pose_ground_truth' % prefix, Odometry, self.on_odom,
                (self.gt[index], False), queue_size=100))

    def close(self):
        for subscriber in self.subscribers:
            subscriber.unregister()
        for publisher in self.publishers:
            publisher.unregister()

    def on_clock(self, message):
        with self.lock:
            self.clock = message.clock.to_sec()
            v, vy, w = self.command
            self.cmd_log.append([round(self.clock, 6), v, vy, w])
            twist = Twist()
            twist.linear.x, twist.linear.y, twist.angular.z = v, vy, w
            for publisher in self.publishers:
                publisher.publish(twist)
            self.ticked.notify_all()

    @staticmethod
    def on_odom(message, args):
        store, with_twist = args
        pose, twist = message.pose.pose, message.twist.twist
        row = [pose.position.x, pose.position.y, yaw_of(pose.orientation)]
        if with_twist:
            row += [twist.linear.x, twist.linear.y, twist.angular.z]
        store[round(message.header.stamp.to_sec(), 6)] = [round(v, DIGITS) for v in row]

    def wait_ticks(self, count):
        """Block until `count` more /clock ticks have passed; the last clock seen."""
        with self.lock:
            for _ in range(count):
                before = self.clock
                if not self.ticked.wait_for(lambda: self.clock != before, START_TIMEOUT):
                    raise RuntimeError('stageros stopped publishing /clock')
            return self.clock

    def drive(self, v, vy, w, seconds):
        with self.lock:
            self.command = (v, vy, w)
        self.wait_ticks(int(round(seconds / INTERVAL)))


def record_run(name, world_file, wrapper, log, env, group):
    world = load_world(os.path.join(DATA, world_file))
    recorder = Recorder(len(world.robots))
    stageros = group.start(wrapper + ['rosrun', 'stage_ros', 'stageros',
                                      os.path.join(DATA, world_file)], env, log)
    try:
        recorder.wait_ticks(1)
        first = recorder.wait_ticks(1)
        reset = None
        for label, v, vy, w, seconds in PLAN:
            if label == 'reset':
                called_after = recorder.clock
                rospy.ServiceProxy('/reset_positions', Empty)()
                reset = {'called_after_stamp': called_after, 'returned_by_stamp': recorder.clock}
            else:
                recorder.drive(v, vy, w, seconds)
        last = recorder.wait_ticks(2)
    finally:
        group.end(stageros)
        recorder.close()
    stamps = [s for s in sorted(recorder.odom[0]) if first <= s <= last]
    steps = [int(round((b - a) / INTERVAL)) for a, b in zip(stamps[:-1], stamps[1:])]
    if set(steps) != {1}:
        raise RuntimeError('%s: updates missing from the recording (steps %s)' % (name, steps))
    robots = []
    for index, spec in enumerate(world.robots):
        odom = [recorder.odom[index][s] for s in stamps]
        gt = [recorder.gt[index][s] for s in stamps]
        robots.append({'name': spec.name, 'odom': odom, 'gt': gt})
    reset['first_stamp_at_start'] = next(
        s for s, before, after in zip(stamps[1:], robots[0]['gt'][:-1], robots[0]['gt'][1:])
        if s > reset['called_after_stamp'] and before != after)
    return {'name': name, 'world': world_file,
            'recorded_utc': datetime.datetime.utcnow().strftime('%Y-%m-%dT%H:%M:%SZ'),
            'cmd_log': [row for row in recorder.cmd_log if first <= row[0] <= last],
            'reset': reset, 'stamps': stamps, 'robots': robots}


def summary(run):
    for robot in run['robots']:
        ex, ea = step_scale_errors(robot['odom'], INTERVAL)
        print('  %-10s %-9s ex %+.6f (spread %.1e)  ea %+.6f (spread %.1e)' % (
            run['name'], robot['name'], ex.mean(), ex.max() - ex.min(), ea.mean(),
            ea.max() - ea.min()))


def document(runs):
    return {
        'schema': 'stage_odometry/1',
        'description': 'Real Stage localization "odom": every robot of each world driven '
                       'through the same plan; /odom and /base_pose_ground_truth per update.',
        'versions': 'Stage 4.3.0 (rtv/Stage 281ed731) and stage_ros 1.8.0, built by '
                    'tools/build-real-stage; stageros with its window under xvfb-run, speedup 1',
        'capture': 'cmd_vel published to every robot on each /clock tick (cmd_log rows: '
                   'the clock seen, vx, vy, wz); a command takes effect in the next update. '
                   'reset: /reset_positions called while all stood still; '
                   'first_stamp_at_start is the first update at the start poses.',
        'units': 'metres, radians, seconds of simulated time; m/s, rad/s',
        'interval_sim': INTERVAL,
        'plan': [list(phase) for phase in PLAN],
        'record_fields': {'odom': list(ODOM_FIELDS), 'gt': list(GROUND_TRUTH_FIELDS)},
        'rounding': 'poses and twists rounded to %d decimals; yaw from the quaternion' % DIGITS,
        'runs': runs,
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    parser.add_argument('--out', default=os.path.join(DATA, 'stage_odometry.json'))
    args = parser.parse_args()
    with stage_session('record_stage_odometry') as (wrapper, log, env, group):
        runs = []
        for name, world_file in RUNS:
            print('== %s: %s' % (name, world_file))
            runs.append(record_run(name, world_file, wrapper, log, env, group))
            summary(runs[-1])
            time.sleep(1.5)   # a new second: Stage seeds its default draw from the clock
    with open(args.out, 'w') as stream:
        json.dump(document(runs), stream, separators=(',', ':'))
        stream.write('\n')
    print('wrote %s (logs in %s)' % (args.out, env['ROS_LOG_DIR']))


if __name__ == '__main__':
    main()
