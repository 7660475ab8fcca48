"""The robot arm: planning time and success on random reachable points, and executed motion
time against the fastest the joint limits allow.

Planning runs here, with no ROS (wall_follower.arm.planning on the package's URDF, SRDF
and joint limits): each point is where the hand origin is at random joint positions
within the limits and clear of the floor and of the arm itself, planned from other such
random positions. Execution runs arm.launch on a private master in simulated time (the
built-in controller driving /clock), sends move_arm a number of those points, and
measures from joint_states how long each move took, from the last state at rest before
it to the first at rest after it (up to two steps of joint_states, 20 ms each, more than
the motion), against the least time any joint needs for its own part of the move within
its velocity and acceleration limits (a bound no move that starts and stops all joints
together can beat; planned moves follow the straight joint-space line at the pace of the
joint for which the limits bite hardest).
"""
import argparse
import os
import tempfile
import time

import numpy as np
import rospkg
import rospy
import yaml
from geometry_msgs.msg import PointStamped
from sensor_msgs.msg import JointState

from wall_follower.action_registration import action_server_registered
from wall_follower.arm.collision import CollisionChecker
from wall_follower.arm.kinematics import tool_position
from wall_follower.arm.model import (read_acceleration_limits, read_srdf, read_urdf,
                                     read_velocity_limits)
from wall_follower.arm.planning import Planner, PlanningError
from wall_follower.arm.timing import fastest_duration
from wall_follower.evaluation.goal_client import GoalClient
from wall_follower.evaluation.launching import (LAUNCH_STOP_GRACE, ProcessGroup, free_port,
                                                launch_command, master_environment)
from wall_follower.evaluation.tables import fmt, print_table
from wall_follower.msg import MoveArmAction, MoveArmGoal

RESULT_LIMIT = 120.0   # wall s for move_arm to answer one goal


def package_files():
    """(model, semantics, velocity, acceleration) from the package's own files."""
    root = rospkg.RosPack().get_path('wall_follower')
    with open(os.path.join(root, 'urdf', 'cougarbot.urdf')) as stream:
        model = read_urdf(stream.read())
    with open(os.path.join(root, 'config', 'cougarbot.srdf')) as stream:
        semantics = read_srdf(stream.read(), model)
    with open(os.path.join(root, 'config', 'joint_limits.yaml')) as stream:
        limits = yaml.safe_load(stream)
    return (model, semantics, read_velocity_limits(limits, model),
            read_acceleration_limits(limits, model))


def clear_positions(model, checker, rng):
    """Random joint positions within the limits, touching nothing."""
    while True:
        positions = rng.uniform(model.lower, model.upper)
        if not checker.contacts(positions):
            return positions


def planning_trials(count, seed):
    """[(success, planning time [s], reason or None)] of count random reachable points."""
    model, semantics, velocity, acceleration = package_files()
    planner = Planner(model, semantics, acceleration, velocity)
    checker = CollisionChecker(model, semantics.disabled)
    rng = np.random.RandomState(seed)
    trials = []
    for _ in range(count):
        point = tool_position(model, clear_positions(model, checker, rng))
        current = clear_positions(model, checker, rng)
        started = time.perf_counter()
        try:
            planner.to_point(point, current)
            trials.append((True, time.perf_counter() - started, None))
        except PlanningError as error:
            trials.append((False, time.perf_counter() - started, str(error)))
    return trials


def execution_trials(count, seed, speedup, timeout):
    """[(moved s, fastest s, hand error m)] of count move_arm goals to random reachable points,
    run on arm.launch in simulated time; [] if the launch did not come up."""
    model, semantics, velocity, acceleration = package_files()
    checker = CollisionChecker(model, semantics.disabled)
    rng = np.random.RandomState(seed)
    port = free_port()
    os.environ.update(master_environment(port))
    log = tempfile.NamedTemporaryFile('w', prefix='benchmark-arm-', suffix='.log', delete=False)
    with ProcessGroup(grace=LAUNCH_STOP_GRACE) as group:
        group.start(launch_command('arm.launch', {'sim_time': 'true', 'speedup': speedup}, port),
                    log=log)
        try:
            return _execute(model, checker, velocity, acceleration, rng, count, timeout)
        finally:
            log.close()
            os.unlink(log.name)


def move_arm_client(timeout, system_state=None, clock=time.monotonic, sleep=time.sleep,
                    make_client=GoalClient):
    """A GoalClient of move_arm once its server is there, within timeout wall seconds; None
    if it is not.

    The client is made only once the server is registered with the master, as the nodes
    make theirs: made before, it can miss the server for good (action_registration says
    why). system_state, clock and sleep as action_server_registered takes them;
    make_client(name, action): the client.
    """
    deadline = clock() + timeout
    if not action_server_registered('move_arm', timeout, system_state, clock, sleep):
        return None
    client = make_client('move_arm', MoveArmAction)
    while not client.wait_for_server(rospy.Duration(1.0)):
        if clock() > deadline:
            return None
    return client


def _execute(model, checker, velocity, acceleration, rng, count, timeout):
    rospy.init_node('benchmark_arm', anonymous=True, disable_signals=True)
    states = []
    rospy.Subscriber('joint_states', JointState, lambda msg: states.append(
        (msg.header.stamp.to_sec(), np.array(msg.position), np.array(msg.velocity))),
        queue_size=1000)
    client = move_arm_client(timeout)
    if client is None:
        return []
    trials = []
    for _ in range(count):
        point = tool_position(model, clear_positions(model, checker, rng))
        goal = MoveArmGoal(target=PointStamped())
        goal.target.header.frame_id = model.root
        goal.target.point.x, goal.target.point.y, goal.target.point.z = point
        before = len(states)
        client.send_goal(goal)
        result = client.get_result() if client.wait_for_result(RESULT_LIMIT) else None
        if result is None or not result.success:
            trials.append((float('nan'), float('nan'), float('nan')))
            continue
        run = states[before - 1:]
        moving = [i for i, s in enumerate(run) if np.any(np.abs(s[2]) > 1e-9)]
        # from the last state at rest before the motion to the first at rest after it
        moved = run[min(moving[-1] + 1, len(run) - 1)][0] - run[max(moving[0] - 1, 0)][0] \
            if moving else 0.0
        trials.append((moved, fastest_duration(run[0][1], run[-1][1], velocity, acceleration),
                       result.position_error))
    rospy.signal_shutdown('benchmark done')
    return trials


def main(argv=None):
    parser = argparse.ArgumentParser(prog='benchmark arm', description=__doc__)
    parser.add_argument('--points', type=int, default=1000, help='points planned')
    parser.add_argument('--moves', type=int, default=10, help='points moved to through ROS')
    parser.add_argument('--speedup', type=float, default=4.0,
                        help='simulated seconds per wall second of the executed moves')
    parser.add_argument('--seed', type=int, default=0)
    args = parser.parse_args(argv)

    trials = planning_trials(args.points, args.seed)
    times = np.array([t for _, t, _ in trials]) * 1000.0
    reasons = {}
    for ok, _, reason in trials:
        if not ok:
            kind = reason.split(': ', 1)[-1].split(' (')[0].split(' ')[:4]
            reasons[' '.join(kind)] = reasons.get(' '.join(kind), 0) + 1
    print_table(['points', 'success %', 'planning median ms', 'planning max ms'], [[
        len(trials), fmt(100.0 * np.mean([ok for ok, _, _ in trials]), '.1f'),
        fmt(np.median(times), '.2f'), fmt(np.max(times), '.2f')]])
    for reason, number in sorted(reasons.items(), key=lambda item: -item[1]):
        print('  failed %d: %s ...' % (number, reason))

    if args.moves:
        print()
        moves = execution_trials(args.moves, args.seed + 1, args.speedup, 120.0)
        done = [m for m in moves if m[0] == m[0]]
        if not done:
            print('no move executed (arm.launch did not come up?)')
            return 1
        ratios = np.array([m[0] / m[1] for m in done if m[1] > 0])
        print_table(['moves', 'succeeded', 'moved s (total)', 'fastest s (total)',
                     'time / fastest median', 'max', 'hand error max mm'], [[
                         len(moves), len(done), fmt(sum(m[0] for m in done), '.2f'),
                         fmt(sum(m[1] for m in done), '.2f'), fmt(np.median(ratios), '.3f'),
                         fmt(np.max(ratios), '.3f'),
                         fmt(1000.0 * max(m[2] for m in done), '.3f')]])
        print('\nfastest: the least time the slowest joint needs for its own part of the move '
              'within its velocity and acceleration limits')
    return 0
