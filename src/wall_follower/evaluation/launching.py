"""Launching for every evaluation tool: a master of a run's own, a display, and one ProcessGroup.

Each run gets its own master on a free port, so runs never share state and
a roscore already running on the machine is left alone. Every process a
benchmark, the grader or a picture starts is started by a ProcessGroup,
which ends all of them together, whatever they did (a node that hangs,
ignores SIGINT, or leaves its parent's session: roslaunch itself puts
every node in a session of its own). So every process of a group carries a
token in its environment, which every descendant inherits, and ending the
group ends, by their ids, every process of this user whose environment
holds the token: first SIGINT to each started process group (roslaunch
then stops its nodes cleanly), then, after a grace, SIGKILL to whatever
still carries the token.
"""
import argparse
import json
import os
import random
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
import uuid

import rospkg

from wall_follower.sim.laser_profiles import PROFILES
from wall_follower.sim.stage_interface import world_path

WORLDS = ('room', 'arena', 'obstacles')
TOKEN_VARIABLE = 'WALL_FOLLOWER_GRADE_CASE'
# Wall seconds a group's processes have to end on SIGINT before they are killed.
STOP_GRACE = 8.0
# A master's port is drawn from here up, outside the ephemeral range (free_port).
MASTER_PORTS_FROM = 20000
# Linux's default ephemeral range, where /proc does not say.
EPHEMERAL_DEFAULT = (32768, 60999)
EPHEMERAL_FILE = '/proc/sys/net/ipv4/ip_local_port_range'
# The same for a whole launch run to its end: longer than roslaunch's own wait
# (15 s) before it escalates on a node that ignores SIGINT.
LAUNCH_STOP_GRACE = 20.0


def shipped_world(suffix=''):
    """An argparse type for a world argument: the name of a world in the package's worlds/
    (NAME + suffix + .world, as NAME_odom) or a .world path; a name with no such file is a
    one-line usage error at once, instead of a row of failed runs or a traceback."""
    def check(name):
        path = world_path(name + suffix)
        if not os.path.isfile(path):
            raise argparse.ArgumentTypeError('no world %s' % path)
        return name
    return check


def laser_profile(name):
    """An argparse type for a laser profile: one of the simulator's."""
    if name not in PROFILES:
        raise argparse.ArgumentTypeError('no laser profile %r (known: %s)' % (
            name, ', '.join(PROFILES)))
    return name


def free_port(ephemeral=None, tries=100):
    """A port nothing is bound to, for a run's master, outside the ephemeral range.

    roslaunch binds port 0 for its own server before it starts the master,
    and every node does for its servers: a port of the ephemeral range
    (the ports a bind to port 0 is given), free when drawn, can be given to
    one of them before the master binds it. One grader case's roslaunch, in
    its sandbox, got the master's port this way. A port outside that range
    is taken only by a bind that names it. ephemeral: the range (low, high),
    read from the system when None; with no port outside it, any free port.
    """
    low, high = ephemeral or ephemeral_ports()
    outside = [port for port in range(MASTER_PORTS_FROM, 65536) if not low <= port <= high]
    for port in random.sample(outside, min(tries, len(outside))):
        try:
            return _bound(port)
        except OSError:
            continue
    return _bound(0)


def ephemeral_ports():
    """(low, high) of this system's ephemeral port range."""
    try:
        with open(EPHEMERAL_FILE) as stream:
            low, high = (int(word) for word in stream.read().split())
        return low, high
    except (IOError, OSError, ValueError):
        return EPHEMERAL_DEFAULT


def _bound(port):
    """The port, once bound and let go (port 0: the one the system gave); OSError if it
    cannot be bound."""
    sock = socket.socket()
    try:
        sock.bind(('', port))
        return sock.getsockname()[1]
    finally:
        sock.close()


def wait_for_port(port, limit, process):
    """Until something listens on port; False after limit wall seconds or once process ended."""
    deadline = time.monotonic() + limit
    while time.monotonic() < deadline and process.poll() is None:
        try:
            socket.create_connection(('localhost', port), timeout=1.0).close()
            return True
        except OSError:
            time.sleep(0.2)
    return False


def master_environment(port, base=None):
    """base (the environment by default) with ROS_MASTER_URI on localhost:port."""
    return dict(os.environ if base is None else base,
                ROS_MASTER_URI='http://localhost:%d' % port)


def package_installed(name):
    """True when the ROS package name is on the package path (stage_ros, gmapping, ...)."""
    try:
        rospkg.RosPack().get_path(name)
    except rospkg.ResourceNotFound:
        return False
    return True


def display_wrapper():
    """The command prefix that gives real Stage's window a display: none when
    there is one, `xvfb-run -a` when there is not; None when neither can be had."""
    if os.environ.get('DISPLAY'):
        return []
    if shutil.which('xvfb-run'):
        return ['xvfb-run', '-a']
    return None


def marked_processes(token, variable=TOKEN_VARIABLE):
    """Ids of this user's running processes whose environment holds token (as variable)."""
    needle = ('%s=%s\0' % (variable, token)).encode()
    found = []
    for entry in os.listdir('/proc'):
        if not entry.isdigit() or int(entry) == os.getpid():
            continue
        try:
            with open('/proc/%s/environ' % entry, 'rb') as stream:
                environment = stream.read()
        except (IOError, OSError):
            continue
        if needle in environment + b'\0':
            found.append(int(entry))
    return found


def processes_with(word):
    """Ids of the running processes whose command line holds word, whatever their
    environment: what a test looks for when a process may have shed the token."""
    needle = word.encode()
    found = []
    for entry in os.listdir('/proc'):
        if entry.isdigit():
            try:
                with open('/proc/%s/cmdline' % entry, 'rb') as stream:
                    if needle in stream.read():
                        found.append(int(entry))
            except (IOError, OSError):
                pass
    return found


class ProcessGroup(object):
    """Processes started together (each in a session of its own), ended together.

    token: unique to the group; by default '<this pid>-<random>', so that
    a test can look for what one grade left behind. grace: wall seconds
    stop() gives the processes to end on SIGINT. Used as a `with` block,
    the group is stopped when the block ends, however it ends.
    """

    def __init__(self, token=None, grace=STOP_GRACE):
        self.token = token or '%d-%s' % (os.getpid(), uuid.uuid4().hex)
        self.grace = grace
        self.processes = []

    def __enter__(self):
        return self

    def __exit__(self, *_exc):
        self.stop()

    def environment(self, base=None):
        return dict(os.environ if base is None else base, **{TOKEN_VARIABLE: self.token})

    def start(self, command, env=None, log=subprocess.DEVNULL, errors=subprocess.STDOUT):
        """Start command with env (the environment by default) plus the token, its output
        into log (an open file, or subprocess.PIPE) and its errors into errors."""
        process = subprocess.Popen(command, env=self.environment(env), stdout=log,
                                   stderr=errors, stdin=subprocess.DEVNULL,
                                   start_new_session=True)
        self.processes.append(process)
        return process

    def end(self, process, grace=None):
        """End one of the group's processes and its process group, as Ctrl-C would: SIGINT,
        SIGKILL after grace wall s (the group's own by default)."""
        if process.poll() is None:
            _signal_group(process.pid, signal.SIGINT)
        try:
            process.wait(timeout=self.grace if grace is None else grace)
        except subprocess.TimeoutExpired:
            _signal_group(process.pid, signal.SIGKILL)
            process.wait()
        self.forget(process)

    def forget(self, process):
        """Stop looking after a process that has ended by itself."""
        if process in self.processes:
            self.processes.remove(process)

    def stop(self):
        """End every process of the group: SIGINT to each started process group, then
        SIGKILL to whatever still carries the token after the grace."""
        for process in self.processes:
            if process.poll() is None:
                _signal_group(process.pid, signal.SIGINT)
        deadline = time.monotonic() + self.grace
        while time.monotonic() < deadline and marked_processes(self.token):
            time.sleep(0.1)
        for _ in range(3):
            left = marked_processes(self.token)
            if not left:
                break
            for pid in left:
                try:
                    os.kill(pid, signal.SIGKILL)
                except OSError:
                    pass
            time.sleep(0.1)
        for process in self.processes:
            try:
                process.wait(timeout=1.0)
            except subprocess.TimeoutExpired:
                pass


def _signal_group(pid, number):
    try:
        os.killpg(pid, number)
    except OSError:
        pass


def launch_command(launch_file, args, port):
    """roslaunch wall_follower launch_file args, on its own master at port."""
    return (['roslaunch', '-p', str(port), 'wall_follower', launch_file]
            + ['%s:=%s' % item for item in sorted(args.items())])


def launch_and_wait(command, port, log, timeout):
    """Runs a roslaunch command to its end, its output into the file log.

    True when it ended by itself within timeout wall seconds; otherwise it
    is interrupted (SIGINT, as Ctrl-C) and False is returned. Nothing it
    started outlives the call.
    """
    with ProcessGroup(grace=LAUNCH_STOP_GRACE) as group:
        process = group.start(command, master_environment(port), log)
        try:
            process.wait(timeout=timeout)
            return True
        except subprocess.TimeoutExpired:
            return False


def launch_and_read(command, port, timeout):
    """(ended, output): launch_and_wait, its output kept in a temporary file and read back
    once everything it started has ended (what a check of a launch's words needs)."""
    with tempfile.TemporaryFile('w+') as log:
        ended = launch_and_wait(command, port, log, timeout)
        log.seek(0)
        return ended, log.read()


def run_launch(launch_file, args, timeout=600.0, wrapper=()):
    """roslaunch wall_follower launch_file args json:=FILE; returns FILE's JSON or None.

    wrapper: a command prefix (display_wrapper() for real Stage's window).
    None means the run wrote nothing: it failed or ran out of time; its
    roslaunch output is then kept, and its path printed on stderr.
    """
    port = free_port()
    fd, output = tempfile.mkstemp(suffix='.json')
    os.close(fd)
    os.unlink(output)
    command = list(wrapper) + launch_command(launch_file, dict(args, json=output), port)
    with tempfile.NamedTemporaryFile('w', prefix='benchmark-', suffix='.log',
                                     delete=False) as log:
        launch_and_wait(command, port, log, timeout)
    if not os.path.exists(output):
        sys.stderr.write('run failed: %s (roslaunch output: %s)\n' % (' '.join(command), log.name))
        return None
    os.unlink(log.name)
    with open(output) as stream:
        figures = json.load(stream)
    os.unlink(output)
    return figures


def run_rostest(test_file, args, timeout):
    """rostest wall_follower test_file ARG:=VALUE... json:=FILE; FILE's JSON, or None
    (said on stderr) when the run wrote none: it failed or ran out of time."""
    fd, output = tempfile.mkstemp(suffix='.json')
    os.close(fd)
    os.unlink(output)
    command = ['rostest', 'wall_follower', test_file] + [
        '%s:=%s' % item for item in sorted(dict(args, json=output).items())]
    with ProcessGroup(grace=LAUNCH_STOP_GRACE) as group:
        process = group.start(command)
        try:
            process.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            pass
    if not os.path.exists(output):
        sys.stderr.write('run failed: %s\n' % ' '.join(command))
        return None
    with open(output) as stream:
        figures = json.load(stream)
    os.unlink(output)
    return figures
