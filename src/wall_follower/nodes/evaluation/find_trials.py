"""find_wall from a list of start poses, scored from ground truth and the map.

Shared by launch/find_trials.launch (a demo to watch in rviz, and the
benchmark's source of figures) and by the finder rostest. The robot is
teleported through the simulator's cmd_pose topic, so this needs the
builtin simulator (or a stageros built with cmd_pose).

Parameters: the table in wall_follower.params.evaluation.find_trials, read once at
start. Stopped by a signal before the last trial, it ends quietly with status 0
and writes no figures (nodes/shared/shutdown.py).
"""
import json
import math
import numbers
import time

import numpy as np
import rospy
from geometry_msgs.msg import Pose

from wall_follower.evaluation.outputs import output_problem
from wall_follower.evaluation.scoring.course import CourseMap
from wall_follower.nodes.shared.course_monitor import CourseMonitor
from wall_follower.nodes.shared.messages import pose_message
from wall_follower.nodes.shared.parameters import NodeParameters
from wall_follower.nodes.shared.shutdown import quiet_on_shutdown, raise_if_shut_down
from wall_follower.nodes.shared.startup import init_node
from wall_follower.params.evaluation.find_trials import TABLE
from wall_follower.sim.stage_interface import world_path
from wall_follower.sim.worldfile import WorldFileError
from wall_follower.srv import FindWall

# Simulated time for the scan and ground truth to show a new pose, and that the robot
# stands still for to count as at rest.
SETTLE = 0.5
# Wall seconds to wait for ground truth to show the robot at rest after find_wall replied.
REST_LIMIT = 30.0


class RestWatch(object):
    """Tells, from ground truth polled now and then, when the robot has stood still (the same
    pose) for settle simulated seconds.

    A busy machine may hand this process find_wall's reply before the ground
    truth of the steps that came before it: the newest pose heard then is one
    of the finder's last turn, not where it left the robot. Waiting for
    ground truth that shows the robot at rest judges where it stopped.
    """

    def __init__(self, settle=SETTLE):
        self.settle = settle
        self._pose = None
        self._since = None

    def look(self, stamp, pose):
        """The pose once at rest, else None: (stamp, pose) is the newest ground truth."""
        if pose is None:
            return None
        if self._pose is None or not np.allclose(pose, self._pose, rtol=0.0, atol=1e-9):
            self._pose, self._since = pose, stamp
            return None
        return pose if stamp - self._since >= self.settle else None


class FindTrials(object):
    """Teleports the robot, calls find_wall and scores where it ended."""

    def __init__(self, world, service_wait=30.0):
        self.world = world
        self.map = CourseMap(world_path(world))
        self.teleport = rospy.Publisher('cmd_pose', Pose, queue_size=1, latch=True)
        rospy.wait_for_service('find_wall', timeout=service_wait)
        self.find_wall = rospy.ServiceProxy('find_wall', FindWall)

    def run(self, start):
        """One trial from start = (x, y, yaw_deg); returns its figures as a dict."""
        x, y, yaw_deg = start
        self.teleport.publish(pose_message(x, y, math.radians(yaw_deg)))
        rospy.sleep(SETTLE)
        monitor = CourseMonitor(self.map, start_on_goal=False)
        started = rospy.get_time()
        found = self.find_wall().wallfound
        took = rospy.get_time() - started
        pose = at_rest(monitor)
        monitor.close()
        score = monitor.summary()
        aligned = self.map.right_wall_alignment(pose) if pose else None
        return {
            'start': list(start),
            'found': found,
            'time': took,
            'distance': aligned[0] if aligned else float('nan'),
            'heading_error_deg': math.degrees(aligned[1]) if aligned else float('nan'),
            'contact': score['contact'],
            'max_linear': score['max_linear'],
            'max_angular': score['max_angular'],
        }


def at_rest(monitor, limit=REST_LIMIT):
    """The robot's true pose once monitor's ground truth shows it at rest (RestWatch); the
    newest heard, with a warning, after limit wall seconds without;
    rospy.ROSInterruptException if rospy shuts down first."""
    watch = RestWatch()
    deadline = time.monotonic() + limit
    while time.monotonic() < deadline:
        raise_if_shut_down()
        pose = watch.look(*monitor.latest())
        if pose is not None:
            return pose
        time.sleep(0.01)
    rospy.logwarn('find_trials: the robot was not at rest %.0f s after find_wall replied; '
                  'judged where it was last heard', limit)
    return monitor.latest()[1]


def is_pose(start):
    """True for [x, y, yaw_deg], three numbers."""
    return isinstance(start, (list, tuple)) and len(start) == 3 and all(
        isinstance(value, numbers.Real) and not isinstance(value, bool) for value in start)


@quiet_on_shutdown
def main():
    init_node('find_trials')
    values = NodeParameters(TABLE).snapshot()
    world, output = values['world'], values['json']
    starts = values['poses'].get(world)
    if not starts:
        rospy.logerr('find_trials: no start poses for world %r in ~poses', world)
        return 1
    bad = [start for start in starts if not is_pose(start)]
    if bad:
        rospy.logerr('find_trials: a start pose in ~poses/%s is [x, y, yaw_deg], not %r',
                     world, bad[0])
        return 1
    problem = output_problem(output) if output else None
    if problem:
        rospy.logerr('find_trials: cannot write ~json: %s', problem)
        return 1
    try:
        trials = FindTrials(world)
    except WorldFileError as err:
        rospy.logerr('find_trials: cannot read world %s: %s', world, err)
        return 1
    except rospy.ROSException as err:
        raise_if_shut_down()   # not find_wall missing: shut down while waiting for it
        rospy.logerr('find_trials: %s', err)
        return 1
    results = []
    for start in starts:
        result = trials.run(start)
        results.append(result)
        rospy.loginfo('find_trials: from (%.2f, %.2f, %.0f deg): found=%s in %.1f s, '
                      'wall %.3f m on the right, heading off by %.1f deg, contact=%s',
                      start[0], start[1], start[2], result['found'], result['time'],
                      result['distance'], result['heading_error_deg'], result['contact'])
    if output:
        with open(output, 'w') as stream:
            json.dump({'world': world, 'trials': results}, stream, indent=1)
    return 0
