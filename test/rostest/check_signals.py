#!/usr/bin/env python3
"""rostest: every long-running node that scripts/ installs ends on SIGINT or SIGTERM, whenever
it comes, on a machine whose cores are all busy.

Each node is started as a child process and signalled at one of MOMENTS
of its life: a stage it has reached, seen from outside, and a delay after
it. The stages: its Python has started (it is still importing), it has
installed a signal handler (shared.startup.init_node, about to register with the
master), and the master knows it (from then on it waits for its first
scan, odometry, service or action server, and runs). Counted from stages,
not from the start, because a loaded machine stretches a start unevenly:
here imports alone took up to 8 s of wall time, and moments of a few seconds
after the start would all have fallen into them. It must end within
EXIT_LIMIT seconds of its own, and a node that drives must have sent a
zero Twist last. Its own: the wall time from the signal to its exit, less
the time its threads spent ready to run but waiting for a CPU (the
kernel's run delay, /proc/PID/task/*/schedstat). A Python process takes a
tenth of a second of CPU to end; on a machine this busy it may wait
seconds for it, which is the machine's time, not the node's. A node that
sleeps, waits for a time-out or computes on after the signal still spends
its own time, and fails.

Every core is kept busy by a process of this test's own (Load) all
through, as a robot's computer often is while it starts. Each wave tries
every node once, each at another moment, half of them with SIGINT and half
with SIGTERM; GROUP nodes run at a time, the next one starting as soon as
one has ended. Half the runs start with SIGINT ignored, as a shell starts a
job in the background (and the issue's nodes were started): a node must
answer it all the same, from its script's first line on. A SIGINT waits
for that line: before it, a background job's is discarded by the kernel
and a starting interpreter's is answered by Python's own handler, neither
of them the node's. A SIGTERM comes at its moment, whatever the stage. The
nodes are started as roslaunch starts them, by their path: rosrun would
first run a lookup of its own (catkin_find, a Python program, seconds on a
loaded machine) that a signal can land in.

In wall time (/use_sim_time false): the test itself is about wall time,
and it feeds the nodes a room's scan and a standing robot's odometry
(with tf between them) so that the ones that drive do; the arm's nodes get
its description as arm.launch loads it. Left out: the tools that end by
themselves (TOOLS), which a launch file does not keep running. Every
script CMakeLists.txt installs is one or the other: a new node is not
left out by accident.
"""
import os
import re
import pty
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
import unittest

import roslib.packages
import rosgraph
import rospkg
import rospy
import rostest
import tf2_ros
import yaml
from geometry_msgs.msg import TransformStamped, Twist
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan

from synthetic_scans import square_room
from waiting import wait_until

EXIT_LIMIT = 2.0      # s of the node's own (not waiting for a CPU) from the signal to its exit
DELIVERY_LIMIT = 2.0  # wall s for its last command to reach this node
LATE_LIMIT = 10.0     # wall s more that a node past EXIT_LIMIT is given, to tell late from hung
PERIOD = 0.1          # wall s between two scans and two odometry messages
# (stage, wall s after the node reached it) at which it is signalled.
MOMENTS = (('started', 0.0), ('started', 0.3), ('started', 1.0), ('handler', 0.0),
           ('registered', 0.0), ('registered', 0.5), ('registered', 1.5), ('registered', 3.0))
SIGNALS = (signal.SIGINT, signal.SIGTERM)
STAGES = {'started': 'its start', 'handler': 'its signal handler', 'registered': 'registering'}
WAVES = 2
GROUP = 4             # nodes running at once: as many as a small launch file starts
RUN_LIMIT = 60.0      # wall s for a node to be signalled and to end
LOOKUP_PERIOD = 0.1   # wall s between two questions to the master about one node
ROOM = 1.2            # m from the robot to each wall of the room in the scans
PACKAGE = rospkg.RosPack().get_path('wall_follower')
OUT = '{out}'         # in the arguments: the folder the test makes for the files nodes write

# script -> (arguments, whether it drives)
NODES = {
    'wall_following.py': (['_laser_x:=-0.032', '_service_wait:=30.0'], True),
    'wall_finder.py': (['_laser_x:=-0.032'], True),
    'odom_recorder.py': ([], False),
    'teleop_key': ([], True),
    'simple_move_square': ([], True),
    'forward_stop': ([], True),
    'range_ahead': ([], False),
    'wander': ([], True),
    'slam': ([], False),
    'map_saver': (['-f', os.path.join(OUT, 'map')], False),
    'stage_sim': (['--simulator', 'builtin', '-g', os.path.join(
        PACKAGE, 'worlds', 'room.world')], False),
    'world_map': ([], False),
    'line_follower': ([], True),
    'line_mask': ([], False),
    'camera_view': (['_window:=false'], False),
    'arm_controller': ([], False),
    'move_arm': ([], False),
    'arm_plot': (['_live:=false', '_file:=' + os.path.join(OUT, 'joints.png')], False),
    'grade_case': (['_world:=' + os.path.join(PACKAGE, 'worlds', 'room.world'), '_json:=' +
                    os.path.join(OUT, 'grade_case.json')], False),
    'line_case': (['_world:=' + os.path.join(PACKAGE, 'worlds', 'line_lab.world'), '_json:=' +
                   os.path.join(OUT, 'line_case.json')], False),
}
# Scripts that end by themselves once their job is done.
TOOLS = ('benchmark', 'course_report', 'map_png', 'require_package', 'find_trials', 'grade')
# Scripts that need the arm's description (arm.launch's parameters), in their namespace.
ARM_NODES = ('arm_controller', 'move_arm')


def installed_scripts():
    """The scripts CMakeLists.txt's catkin_install_python installs, by file name."""
    with open(os.path.join(PACKAGE, 'CMakeLists.txt')) as cmake:
        block = re.search(r'catkin_install_python\(PROGRAMS(.*?)DESTINATION', cmake.read(), re.S)
    return set(os.path.basename(word) for word in block.group(1).split())


def arm_description():
    """The parameters arm.launch loads for the arm's nodes: name -> value."""
    def text(*path):
        with open(os.path.join(PACKAGE, *path)) as stream:
            return stream.read()
    return {'robot_description': text('urdf', 'cougarbot.urdf'),
            'robot_description_semantic': text('config', 'cougarbot.srdf'),
            'robot_description_planning': yaml.safe_load(text('config', 'joint_limits.yaml'))}


def signal_masks(pid):
    """(ignored, caught): the masks of the signals the process ignores and those it has a
    handler for, as /proc shows them; None once gone."""
    try:
        with open('/proc/%d/status' % pid) as status:
            fields = dict(line.split(':', 1) for line in status)
        return int(fields['SigIgn'], 16), int(fields['SigCgt'], 16)
    except (OSError, ValueError, KeyError):
        return None


def run_delays(pid):
    """thread id -> the time (s) that thread has spent ready to run but waiting for a CPU,
    for the threads of the process still readable (its main thread's until it is reaped,
    a zombie's too)."""
    delays = {}
    try:
        threads = os.listdir('/proc/%d/task' % pid)
    except OSError:
        return delays
    for thread in threads:
        try:
            with open('/proc/%d/task/%s/schedstat' % (pid, thread)) as stream:
                delays[thread] = int(stream.read().split()[1]) * 1e-9
        except (OSError, ValueError, IndexError):
            pass
    return delays


def exited(pid):
    """Whether the child has ended, without reaping it (its /proc entry stays readable)."""
    return os.waitid(os.P_PID, pid, os.WEXITED | os.WNOHANG | os.WNOWAIT) is not None


def has(mask, number):
    return bool(mask & (1 << (number - 1)))


def registered(name):
    """Whether the master knows the node."""
    try:
        rosgraph.Master(rospy.get_name()).lookupNode(name)
        return True
    except rosgraph.MasterError:
        return False


# Busy until stopped, or until this test's process is gone (killed at its time limit, say).
BUSY = 'import os\nparent = os.getppid()\nwhile os.getppid() == parent:\n    pass\n'


class Load(object):
    """A process per core that keeps it busy, until stop()."""

    def __init__(self):
        self.processes = [subprocess.Popen([sys.executable, '-c', BUSY])
                          for _ in range(os.cpu_count() or 1)]

    def stop(self):
        for process in self.processes:
            process.kill()
            process.wait()


class Feed(object):
    """Scans, odometry and tf for every node under test, from a thread of its own."""

    def __init__(self):
        self.scans = rospy.Publisher('/signals/scan', LaserScan, queue_size=1)
        self.odom = rospy.Publisher('/signals/odom', Odometry, queue_size=1)
        self.tf = tf2_ros.TransformBroadcaster()
        threading.Thread(target=self._run, daemon=True).start()

    def _run(self):
        scan, odom = square_room(ROOM), Odometry()
        odom.header.frame_id, odom.child_frame_id = 'odom', 'base_footprint'
        odom.pose.pose.orientation.w = 1.0
        links = []
        for parent, child in (('odom', 'base_footprint'), ('base_footprint', 'base_link'),
                              ('base_link', 'base_scan')):
            link = TransformStamped()
            link.header.frame_id, link.child_frame_id = parent, child
            link.transform.rotation.w = 1.0
            links.append(link)
        while not rospy.is_shutdown():
            now = rospy.Time.now()
            for message in [scan, odom] + links:
                message.header.stamp = now
            self.scans.publish(scan)
            self.odom.publish(odom)
            self.tf.sendTransform(links)
            time.sleep(PERIOD)


class Run(object):
    """One node under test: its process, when to signal it, and what it commanded. out: the
    folder for the files it writes."""

    def __init__(self, out, script, wave, moment, inherited, number):
        arguments, self.drives = NODES[script]
        arguments = [argument.replace(OUT, out) for argument in arguments]
        name = '%s_%d' % (script.split('.')[0], wave)
        self.stage, self.delay = moment
        self.number = number
        self.label = '%s (%s %.1f s after %s, started with SIGINT %s)' % (
            script, signal.Signals(number).name, self.delay, STAGES[self.stage],
            'ignored' if inherited == signal.SIG_IGN else 'default')
        self.lock = threading.Lock()
        self.commands = []
        rospy.Subscriber('/signals/%s/cmd_vel' % name, Twist, self._on_cmd, queue_size=1000)
        if script in ARM_NODES:
            for key, value in arm_description().items():
                rospy.set_param('/signals/%s/%s' % (name, key), value)
        self.terminal, child_end = pty.openpty()   # teleop_key reads a keyboard
        self.errors = tempfile.TemporaryFile()
        self.path = roslib.packages.find_node('wall_follower', script)[0]
        self.process = subprocess.Popen(
            [self.path] + arguments +
            ['__name:=' + name, '__ns:=/signals/' + name, 'scan:=/signals/scan',
             'odom:=/signals/odom'],
            stdin=child_end, stdout=subprocess.DEVNULL, stderr=self.errors,
            preexec_fn=lambda: signal.signal(signal.SIGINT, inherited))
        os.close(child_end)
        self.name, self.inherited = '/signals/%s/%s' % (name, name), inherited
        self.execed = False   # seen running the script, not this process's fork
        self.reached = {}   # stage -> wall time it was first seen reached
        self.answering = False   # seen answering SIGINT by its default action
        self.looked_up = None    # wall time of the last question to the master
        self.signalled = self.ended = None
        self.delays = {}    # thread id -> (run delay at the signal or its birth, latest)
        self.registered_first = False

    def _on_cmd(self, msg):
        with self.lock:
            self.commands.append((msg.linear.x, msg.angular.z))

    def step(self, now):
        """Note the stages reached; signal the node once its moment has come; note when it
        has ended."""
        if self.signalled is None:
            self._see_stages(now)
            reached = self.reached.get(self.stage)
            if reached is not None and now - reached >= self.delay and self._ready_for_signal(now):
                self._note_delays(run_delays(self.process.pid))
                self.process.send_signal(self.number)
                self.signalled = now
        else:
            self._note_delays(run_delays(self.process.pid))
        if self.ended is None and exited(self.process.pid):
            self.ended = now
            self.process.wait()

    def _see_stages(self, now):
        """Python started: it ignores SIGPIPE (this process's children start with it
        restored); what comes before (the exec, seconds on a loaded machine) is no part of
        the package. A handler: SIGINT caught once it had been seen at its default action
        (a Python started with SIGINT default holds a handler of its own until the
        script's first line). Registered: the master knows it.

        Nothing counts before Python has started: until the exec the child is this
        process's fork (SIGPIPE ignored as here), and from the exec until Python ignores
        SIGPIPE, and installs its own SIGINT handler with it, SIGINT is at its default
        action as after the script's first line. Taken for that line, a signal sent then
        reached a starting interpreter, whose KeyboardInterrupt an import swallowed."""
        masks = signal_masks(self.process.pid)
        if masks is None or not self._running_the_script():
            return
        ignored, caught = masks
        if 'started' not in self.reached and has(ignored, signal.SIGPIPE):
            self.reached['started'] = now
        if 'started' not in self.reached:
            return
        if not has(ignored, signal.SIGINT) and not has(caught, signal.SIGINT):
            self.answering = True
        elif self.answering and has(caught, signal.SIGINT):
            self.reached.setdefault('handler', now)
        if 'registered' not in self.reached and self.stage == 'registered' and \
                self._may_look_up(now) and registered(self.name):
            self.reached['registered'] = now

    def _running_the_script(self):
        """Whether the child has been seen running the node's script (its command line names
        it), not this process's fork."""
        if not self.execed:
            try:
                with open('/proc/%d/cmdline' % self.process.pid, 'rb') as cmdline:
                    self.execed = self.path.encode() in cmdline.read().split(b'\0')
            except OSError:
                pass
        return self.execed

    def _may_look_up(self, now):
        """At most one question to the master per LOOKUP_PERIOD for this node."""
        if self.looked_up is not None and now - self.looked_up < LOOKUP_PERIOD:
            return False
        self.looked_up = now
        return True

    def _note_delays(self, delays):
        for thread, delay in delays.items():
            first = self.delays.get(thread, (0.0 if self.signalled else delay,))[0]
            self.delays[thread] = (first, delay)

    def own_time(self, now):
        """The node's own seconds since the signal: wall time less its threads' run delay
        since then."""
        return now - self.signalled - self.waited()

    def waited(self):
        """The seconds the node's threads spent ready to run, waiting for a CPU, since the
        signal (each thread's, summed)."""
        return sum(latest - first for first, latest in self.delays.values())

    def _ready_for_signal(self, now):
        """For SIGINT: False until the node answers it, from its script's first line on
        (before, a shell's background job ignores it, and a starting interpreter holds
        Python's own handler: neither is the node's); notes a node registered with the
        master before that. (The master first: a node registers only after it answers
        SIGINT, so this order cannot see the two the wrong way round.)"""
        if self.number != signal.SIGINT or self.answering:
            return True
        registered_now = registered(self.name)
        self._see_stages(now)
        if self.answering:
            return True
        self.registered_first = registered_now
        return registered_now

    def done(self, now):
        return self.ended is not None or (self.signalled is not None
                                          and self.own_time(now) > EXIT_LIMIT)

    def finish(self):
        """What went wrong with this run, in words (None if nothing did); kills a node
        still running."""
        os.close(self.terminal)
        if self.ended is None:
            if self.signalled is None:
                self.process.kill()
                self.process.wait()
                return '%s: not signalled in %.0f s; stages reached: %s' % (
                    self.label, RUN_LIMIT, ', '.join(sorted(self.reached)) or 'none')
            late = 'at the limit: %.1f s after the signal, %.1f s of them waiting for a ' \
                'CPU' % (time.monotonic() - self.signalled, self.waited())
            try:   # late, or not ending at all? Say which.
                self.process.wait(LATE_LIMIT)
                ended = 'ended only %.1f s after the signal (%s)' % (
                    time.monotonic() - self.signalled, late)
            except subprocess.TimeoutExpired:
                self.process.kill()
                self.process.wait()
                ended = 'still running %.0f s after the signal (%s)' % (
                    time.monotonic() - self.signalled, late)
            return '%s: %s (limit %.1f s of its own); it wrote:\n%s' % (
                self.label, ended, EXIT_LIMIT, self.written())
        if self.registered_first:
            return '%s: answered SIGINT only after registering with the master' % self.label
        if self.signalled is None or self.ended < self.signalled:
            return '%s: ended by itself before the signal (status %s)' % (
                self.label, self.process.returncode)
        if self.drives and not wait_until(self._stopped_last, DELIVERY_LIMIT):
            return '%s: last command %s, not a stop' % (self.label, self.commands[-1])
        rospy.loginfo('%s: ended %.2f s after the signal, %.2f s of them waiting for a CPU',
                      self.label, self.ended - self.signalled, self.waited())
        return None

    def written(self):
        """The end of what the node wrote on stderr."""
        self.errors.seek(0)
        return self.errors.read().decode(errors='replace')[-2000:]

    def _stopped_last(self):
        with self.lock:
            return not self.commands or self.commands[-1] == (0.0, 0.0)


class Signals(unittest.TestCase):

    def test_every_installed_script_is_tried_or_a_tool(self):
        self.assertEqual(installed_scripts(), set(NODES) | set(TOOLS))

    def test_every_node_ends_on_a_signal_at_any_moment_under_load(self):
        out = tempfile.mkdtemp(prefix='check_signals')
        self.addCleanup(shutil.rmtree, out)
        Feed()
        scripts = sorted(NODES)
        problems = []
        plan = [(script, wave, MOMENTS[(index + 3 * wave) % len(MOMENTS)],
                 (signal.SIG_DFL, signal.SIG_IGN)[(index + wave) % 2],
                 SIGNALS[(index // 2 + wave) % 2])
                for wave in range(WAVES) for index, script in enumerate(scripts)]
        waiting, running = list(plan), []
        load = Load()
        try:
            while waiting or running:
                while waiting and len(running) < GROUP:
                    running.append((Run(out, *waiting.pop(0)), time.monotonic() + RUN_LIMIT))
                now = time.monotonic()
                for run, _ in running:
                    run.step(now)
                over = [entry for entry in running if entry[0].done(now) or now >= entry[1]]
                for entry in over:
                    running.remove(entry)
                    problem = entry[0].finish()
                    if problem:
                        problems.append(problem)
                time.sleep(0.02)
        finally:
            load.stop()
        self.assertEqual(problems, [], '%d of %d runs failed:\n%s'
                         % (len(problems), len(plan), '\n'.join(problems)))


if __name__ == '__main__':
    rospy.init_node('check_signals')
    rostest.rosrun('wall_follower', 'check_signals', Signals, sys.argv)
