"""What the recorders of real Stage share: a private master and stageros in its window.

tools/record_stage_odometry.py and tools/record_stage_camera.py each run
real stageros (built by tools/build-real-stage) on worlds of their own and
keep what it publishes. Both need Stage's window (under `xvfb-run -a`
without a display, so that the world's `speedup` paces it), a master of
their own on a free port so that no other roscore is disturbed, and every
process they start ended by its group id whatever happens.
"""
import contextlib
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time

import rosgraph
import rospy

from wall_follower.evaluation.benchmarks.launching import display_wrapper, free_port


def start(command, log, env):
    """A process in a session of its own, so that stop() reaches its children too."""
    return subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT, env=env,
                            start_new_session=True)


def stop(process):
    """End a process start() made, and its children, by its group id."""
    if process.poll() is None:
        os.killpg(process.pid, signal.SIGINT)
        try:
            process.wait(timeout=15)
        except subprocess.TimeoutExpired:
            os.killpg(process.pid, signal.SIGKILL)
            process.wait()


@contextlib.contextmanager
def stage_session(name):
    """Yield (wrapper, log, env) with a private master up and this process its node `name`.

    wrapper: the words to put before a command that opens a window
    (xvfb-run where there is no display); log: the file every process
    writes to; env: the environment that names the private master. Exits
    with a one-line message where real Stage or a display cannot be had.
    """
    wrapper = display_wrapper()
    if wrapper is None:
        sys.exit('%s: Stage\'s window needs a display or xvfb-run' % name)
    if shutil.which('rosrun') is None or subprocess.call(
            ['rospack', 'find', 'stage_ros'], stdout=subprocess.DEVNULL) != 0:
        sys.exit('%s: stage_ros not found: source real Stage\'s setup.bash' % name)
    port = free_port()
    env = dict(os.environ, ROS_MASTER_URI='http://localhost:%d' % port,
               ROS_LOG_DIR=tempfile.mkdtemp(prefix='%s-log-' % name))
    os.environ.update(env)
    log = open(os.path.join(env['ROS_LOG_DIR'], 'processes.log'), 'w')
    roscore = start(['roscore', '-p', str(port)], log, env)
    try:
        while not rosgraph.is_master_online():
            time.sleep(0.2)
        rospy.init_node(name, disable_signals=True)
        yield wrapper, log, env
    finally:
        stop(roscore)
        log.close()
