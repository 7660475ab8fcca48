"""Simulator speed: free run, a held speed-up with a controller in the loop, raytrace time.

Starts its own master on a free port and the stage_sim node as a separate
process; this process plays the controller (a rospy node answering every
scan with a cmd_vel), as the course nodes do. Every command carries a
distinct angular speed, so a step whose odometry twist repeats the previous
one ran without a fresh command: that is a missed control step.

    /usr/bin/python3 -m wall_follower.evaluation.benchmarks.sim [--world arena] [--seconds 5]
"""
import argparse
import os
import subprocess
import sys
import time

import rosgraph
import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from sensor_msgs.msg import LaserScan

from wall_follower.evaluation.launching import WORLDS, ProcessGroup, free_port, shipped_world
from wall_follower.evaluation.tables import fmt, print_table
from wall_follower.sim import compiled_raytrace
from wall_follower.sim.engine import Simulation
from wall_follower.sim.stage_interface import world_path
from wall_follower.sim.stage_interface import rate_in_quit_report
from wall_follower.sim.worldfile import load_world
import wall_follower

HELD_SPEEDUP = 20.0
GOAL_FREE_RUN = 500.0
RAYTRACE_GOAL = '< 1 ms'
START_LIMIT = 20.0
RUN_LIMIT = 120.0
# Simulated seconds of the first unobserved free run, which sizes the second.
UNOBSERVED_FIRST_RUN = 1000.0


class PrivateMaster(object):
    """A roscore on a free port for the duration of a `with` block; this
    process becomes a node of it, on wall time."""

    def __init__(self):
        self.port = free_port()
        self.uri = 'http://localhost:%d' % self.port
        self._group = ProcessGroup(grace=START_LIMIT)

    def __enter__(self):
        os.environ['ROS_MASTER_URI'] = self.uri
        self._group.start(['roscore', '-p', str(self.port)], errors=subprocess.DEVNULL)
        deadline = time.time() + START_LIMIT
        while not rosgraph.is_master_online(self.uri):
            if time.time() > deadline:
                raise RuntimeError('roscore did not start on port %d' % self.port)
            time.sleep(0.1)
        rospy.init_node('sim_benchmark', disable_signals=True)
        rospy.set_param('/use_sim_time', True)   # for the simulator, not for us
        return self

    def simulator(self, world, output=subprocess.DEVNULL, **params):
        """Starts stage_sim on `world` with private parameters; returns its process.

        output: where its stdout goes (subprocess.PIPE to read its log).
        """
        package_parent = os.path.dirname(os.path.dirname(wall_follower.__file__))
        env = dict(os.environ, PYTHONPATH=os.pathsep.join(
            [package_parent] + os.environ.get('PYTHONPATH', '').split(os.pathsep)))
        command = [sys.executable, '-m', 'wall_follower.nodes.sim.stage_sim', world,
                   '__name:=simulator'] + ['_%s:=%s' % item for item in sorted(params.items())]
        return self._group.start(command, env, output, errors=subprocess.DEVNULL)

    def stop(self, process):
        self._group.end(process)

    def forget(self, process):
        """Stops looking after a process that has ended by itself."""
        self._group.forget(process)

    def __exit__(self, *_):
        rospy.signal_shutdown('benchmark done')
        for process in reversed(list(self._group.processes)):
            self._group.end(process)
        self._group.stop()


class ClockWatch(object):
    """The newest /clock message and the wall time it arrived, kept by a subscriber.

    One subscriber for the whole measurement, as every node on simulated
    time has one: a subscription made and dropped for each sample lingers
    for an unknown while, and the simulator's rate depends on whether
    /clock has a listener (about 900x with one, 10000x without).
    """

    def __init__(self):
        self.latest = None
        self._sub = rospy.Subscriber('/clock', Clock, self._on_clock, queue_size=1)

    def _on_clock(self, msg):
        self.latest = (msg.clock.to_sec(), time.time())

    def sample(self):
        """(simulated time, wall time) of the next /clock message."""
        seen = self.latest
        deadline = time.time() + START_LIMIT
        while self.latest is seen and time.time() < deadline:
            time.sleep(0.001)
        if self.latest is seen:
            raise RuntimeError('no /clock from the simulator within %.0f s' % START_LIMIT)
        return self.latest

    def close(self):
        self._sub.unregister()


def unobserved_rate(master, world, seconds):
    """Simulated seconds per wall second at speedup 0 with nobody subscribed at all.

    Nothing can be watched without a subscriber, so the simulator runs to a
    quit_time and reports the rate it stepped at (its log line on stdout).
    A first run sizes the second to last about `seconds`.
    """
    rate = _reported_rate(master, world, UNOBSERVED_FIRST_RUN)
    return _reported_rate(master, world, max(rate * seconds, UNOBSERVED_FIRST_RUN))


def _reported_rate(master, world, quit_time):
    """The real-time multiple a free-running simulator logs when it reaches quit_time."""
    process = master.simulator(world, output=subprocess.PIPE, speedup=0, quit_time=quit_time)
    output = process.communicate(timeout=RUN_LIMIT)[0].decode('utf-8', 'replace')
    master.forget(process)
    rate = rate_in_quit_report(output)
    if rate is None:
        raise RuntimeError('the simulator did not report its rate at quit_time:\n' + output)
    return rate


def free_run_rate(master, world, seconds):
    """Simulated seconds per wall second at speedup 0, with nobody on the scan
    and one subscriber on /clock."""
    clock = ClockWatch()
    process = master.simulator(world, speedup=0)
    start = clock.sample()
    time.sleep(seconds)
    end = clock.sample()
    master.stop(process)
    clock.close()
    return (end[0] - start[0]) / (end[1] - start[1])


class Controller(object):
    """Answers every scan with a cmd_vel whose angular speed is new each time."""

    def __init__(self):
        self.answered = 0
        self.twists = []   # (stamp, commanded wz) from odometry, one per step
        self.recording = False
        self._cmd = rospy.Publisher('cmd_vel', Twist, queue_size=1, tcp_nodelay=True)
        self._subs = [
            rospy.Subscriber('base_scan', LaserScan, self._on_scan, queue_size=1,
                             tcp_nodelay=True),
            rospy.Subscriber('odom', Odometry, self._on_odom, queue_size=1000)]

    def _on_scan(self, _scan):
        self.answered += 1
        twist = Twist()
        twist.angular.z = 0.2 + 0.001 * (self.answered % 100)
        self._cmd.publish(twist)

    def _on_odom(self, odom):
        if self.recording:
            self.twists.append((odom.header.stamp.to_sec(), odom.twist.twist.angular.z))

    def close(self):
        for sub in self._subs:
            sub.unregister()
        self._cmd.unregister()


def held_rate(master, world, speedup, seconds):
    """(simulated s per wall s, steps, steps without a fresh command) with a
    controller in the loop at a held speed-up."""
    controller = Controller()
    process = master.simulator(world, speedup=speedup)
    deadline = time.time() + START_LIMIT
    while controller.answered < 10 and time.time() < deadline:
        time.sleep(0.05)
    controller.recording = True
    started = time.time()
    time.sleep(seconds)
    controller.recording = False
    elapsed = time.time() - started
    master.stop(process)
    controller.close()
    twists = controller.twists
    if len(twists) < 2:
        return float('nan'), 0, 0
    missed = sum(1 for (_, a), (_, b) in zip(twists, twists[1:]) if a == b)
    return (twists[-1][0] - twists[0][0]) / elapsed, len(twists) - 1, missed


def raytrace_ms(world, repeats):
    """Mean wall milliseconds a step spends on its 360-beam scan.

    Measured before this process becomes a ROS node: rospy's threads,
    still running after the master is gone, compete for the interpreter
    and made the same scans time two to three times slower.
    """
    sim = Simulation(load_world(world))
    sim.set_command(0, 0.0, 0.3)   # turning in place, so every scan differs

    def mean_step(with_scans):
        start = time.perf_counter()
        for _ in range(repeats):
            sim.set_command(0, 0.0, 0.3)
            sim.step(with_scans=with_scans)
        return (time.perf_counter() - start) / repeats

    mean_step(True)   # warm the engine's caches
    return 1000.0 * (mean_step(True) - mean_step(False))


def main(argv=None):
    parser = argparse.ArgumentParser(prog='benchmark sim', description=__doc__.split('\n\n')[0])
    parser.add_argument('--world', default='arena', type=shipped_world(),
                        help='world for the node runs (default arena)')
    parser.add_argument('--seconds', type=float, default=5.0, help='wall seconds per run')
    parser.add_argument('--repeats', type=int, default=200, help='scans per raytrace timing')
    args = parser.parse_args(argv)
    if not compiled_raytrace.available():
        sys.stderr.write('benchmark sim: error: %s\n' % compiled_raytrace.MISSING)
        return 1
    world = world_path(args.world)
    raytrace = [(name, raytrace_ms(world_path(name), args.repeats)) for name in sorted(WORLDS)]
    with PrivateMaster() as master:
        # Before this process subscribes to anything: a dropped subscription
        # lingers for a while, and a scan subscriber makes every step trace one.
        unobserved = unobserved_rate(master, world, args.seconds)
        free_run = free_run_rate(master, world, args.seconds)
        held, steps, missed = held_rate(master, world, HELD_SPEEDUP, args.seconds)
    rows = [
        ['free run, no subscribers (%s)' % args.world, fmt(unobserved, '.0f') + 'x real time',
         '>= %.0fx' % GOAL_FREE_RUN],
        ['free run, one /clock subscriber (%s)' % args.world, fmt(free_run, '.0f') + 'x real time',
         ''],
        ['speedup %.0f held, controller on scan -> cmd_vel (%s)' % (HELD_SPEEDUP, args.world),
         fmt(held, '.1f') + 'x real time', '%.0fx' % HELD_SPEEDUP],
        ['  steps without a fresh command', '%d of %d' % (missed, steps), '0'],
    ]
    rows += [['raytrace per 360-beam scan (%s)' % name, fmt(ms, '.3f') + ' ms', RAYTRACE_GOAL]
             for name, ms in raytrace]
    print_table(['measure', 'result', 'goal'], rows)
    print('\nload average (1 min) at the end: %.2f on %d cores; the figures are wall-clock '
          'bound, so a busy machine lowers them' % (os.getloadavg()[0], os.cpu_count()))
    return 0


if __name__ == '__main__':
    sys.exit(main())
