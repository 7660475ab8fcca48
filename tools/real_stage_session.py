"""What the recorders of real Stage share: a private master and stageros in its window.

tools/record_stage_odometry.py and tools/record_stage_camera.py each run
real stageros (built by tools/build-real-stage) on worlds of their own and
keep what it publishes. Both need Stage's window (under `xvfb-run -a`
without a display, so that the world's `speedup` paces it), a master of
their own on a free port so that no other roscore is disturbed, and every
process they start ended whatever happens (launching.ProcessGroup).
"""
import contextlib
import os
import shutil
import subprocess
import sys
import tempfile
import time

import rosgraph
import rospy

from wall_follower.evaluation.launching import ProcessGroup, display_wrapper, free_port

STOP_GRACE = 15.0   # wall s for stageros and roscore to end on SIGINT before they are killed


@contextlib.contextmanager
def stage_session(name):
    """Yield (wrapper, log, env, group) with a private master up and this process its node
    `name`.

    wrapper: the words to put before a command that opens a window
    (xvfb-run where there is no display); log: the file every process
    writes to; env: the environment that names the private master; group:
    the ProcessGroup to start stageros in, every process of which ends with
    the session. Exits
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
    group = ProcessGroup(grace=STOP_GRACE)
    group.start(['roscore', '-p', str(port)], env, log)
    try:
        while not rosgraph.is_master_online():
            time.sleep(0.2)
        rospy.init_node(name, disable_signals=True)
        yield wrapper, log, env, group
    finally:
        group.stop()
        log.close()
