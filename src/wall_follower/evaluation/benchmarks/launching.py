"""Runs one launch file on a private master and collects the figures it writes.

Each run gets its own master on a free port, so runs never share state and
a roscore already running on the machine is left alone.
"""
import argparse
import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile

from wall_follower.sim.laser_profiles import PROFILES
from wall_follower.sim.stage_interface import world_path

WORLDS = ('room', 'arena', 'obstacles')


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


def free_port():
    sock = socket.socket()
    sock.bind(('', 0))
    port = sock.getsockname()[1]
    sock.close()
    return port


def display_wrapper():
    """The command prefix that gives real Stage's window a display: none when
    there is one, `xvfb-run -a` when there is not; None when neither can be had."""
    if os.environ.get('DISPLAY'):
        return []
    if shutil.which('xvfb-run'):
        return ['xvfb-run', '-a']
    return None


def launch_command(launch_file, args, port):
    """roslaunch wall_follower launch_file args, on its own master at port."""
    return (['roslaunch', '-p', str(port), 'wall_follower', launch_file]
            + ['%s:=%s' % item for item in sorted(args.items())])


def launch_and_wait(command, port, log, timeout):
    """Runs a roslaunch command to its end, its output into the file log.

    True when it ended by itself within timeout wall seconds; otherwise it
    is interrupted (SIGINT, as Ctrl-C) and False is returned.
    """
    env = dict(os.environ, ROS_MASTER_URI='http://localhost:%d' % port)
    process = subprocess.Popen(command, env=env, stdout=log, stderr=subprocess.STDOUT,
                               start_new_session=True)
    try:
        process.wait(timeout=timeout)
        return True
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGINT)
        process.wait()
        return False


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
    try:
        subprocess.run(command, stdout=subprocess.DEVNULL, stderr=subprocess.STDOUT,
                       timeout=timeout)
    except subprocess.TimeoutExpired:
        pass
    if not os.path.exists(output):
        sys.stderr.write('run failed: %s\n' % ' '.join(command))
        return None
    with open(output) as stream:
        figures = json.load(stream)
    os.unlink(output)
    return figures


def fmt(value, spec):
    """A table cell; '-' where a figure is missing."""
    if value is None or value != value:
        return '-'
    return format(value, spec)


def print_table(header, rows):
    widths = [max(len(str(cell)) for cell in column) for column in zip(header, *rows)]

    def line(cells):
        return '| ' + ' | '.join(str(c).ljust(w) for c, w in zip(cells, widths)) + ' |'
    print(line(header))
    print('|' + '|'.join('-' * (w + 2) for w in widths) + '|')
    for row in rows:
        print(line(row))
