"""init_node: a signal is answered by shutting rospy down from another thread than the main one.

rospy's own handler runs the shutdown hooks in the main thread, wherever
the signal caught it; a hook that publishes can then deadlock on a lock the
main thread holds mid-publish. Needs ROS's Python modules but no master:
rospy's init_node and signal_shutdown are replaced by the test's.
"""
import os
import select
import signal
import socket
import subprocess
import sys
import threading
import time

import pytest
import rospy

from wall_follower.nodes.shared import signals, startup
from wall_follower.nodes.shared.startup import init_node

SCRIPTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, os.pardir, 'scripts')

# Runs the script given as argv[1] until its first Python function call, and says
# then what answers SIGINT: the kernel's default action, or anything else.
FIRST_CALL = """
import _signal, os, sys
script = sys.argv[1]
def first_call(frame, event, _arg):
    if event == 'call' and frame.f_code.co_filename != script:
        default = _signal.getsignal(_signal.SIGINT) == _signal.SIG_DFL
        os.write(1, b'default' if default else b'not default')
        os._exit(0)
with open(script) as stream:
    code = compile(stream.read(), script, 'exec')
sys.setprofile(first_call)
exec(code, {'__name__': '__main__', '__file__': script})
"""


def node_scripts():
    """The scripts of scripts/ that run a node of wall_follower.nodes."""
    names = []
    for name in sorted(os.listdir(SCRIPTS)):
        with open(os.path.join(SCRIPTS, name)) as stream:
            if 'from wall_follower.nodes' in stream.read():
                names.append(name)
    return names


@pytest.fixture
def handlers(monkeypatch):
    """Restore the process's signal handlers after the test; no node's answer in force."""
    monkeypatch.setattr(signals, '_answers', [])
    saved = dict((number, signal.getsignal(number)) for number in (signal.SIGINT, signal.SIGTERM))
    yield
    for number, handler in saved.items():
        signal.signal(number, handler)


@pytest.mark.parametrize('number', [signal.SIGINT, signal.SIGTERM])
def test_a_signal_shuts_rospy_down_from_a_thread_of_its_own(monkeypatch, handlers, number):
    calls = []
    done = threading.Event()

    def signal_shutdown(reason):
        calls.append((reason, threading.current_thread() is threading.main_thread()))
        done.set()

    monkeypatch.setattr(startup, 'master_answers', lambda: True)
    monkeypatch.setattr(rospy, 'init_node', lambda name, **kwargs: calls.append(kwargs))
    monkeypatch.setattr(rospy, 'signal_shutdown', signal_shutdown)
    init_node('test')
    assert calls == [{'disable_signals': True}]
    os.kill(os.getpid(), number)
    assert done.wait(5.0)
    assert calls[1] == ('signal %d' % number, False)


def test_a_signal_before_init_node_ends_the_process_at_once():
    """SIGINT while the node still imports ends it there, even if it came in ignored
    (a shell's background job), and by the kernel: no Python handler that would wait
    for a long C call to return, no exception that an import could swallow."""
    child = subprocess.Popen(
        [sys.executable, '-c', 'import sys, time\n'
         'from wall_follower.nodes import signals\n'
         'signals.catch()\n'
         'print("ready", flush=True)\n'
         'time.sleep(60)\n'],
        stdout=subprocess.PIPE, preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_IGN))
    try:
        assert child.stdout.readline() == b'ready\n'
        child.send_signal(signal.SIGINT)
        assert child.wait(10.0) == -signal.SIGINT
    finally:
        if child.poll() is None:
            child.kill()
            child.wait()


@pytest.mark.parametrize('inherited', [signal.SIG_DFL, signal.SIG_IGN], ids=['default', 'ignored'])
@pytest.mark.parametrize('script', node_scripts())
def test_a_node_script_leaves_sigint_to_the_kernel_before_any_python_code_runs(script, inherited):
    """Not Python's KeyboardInterrupt, which an import can swallow (the node would start
    all the same), nor the ignore a shell's background job inherits: from the first
    function call the script makes (its first import's), SIGINT ends the process."""
    path = os.path.abspath(os.path.join(SCRIPTS, script))
    answer = subprocess.run([sys.executable, '-c', FIRST_CALL, path], stdout=subprocess.PIPE,
                            preexec_fn=lambda: signal.signal(signal.SIGINT, inherited),
                            timeout=60.0, check=True).stdout
    assert answer == b'default'


def closed_port():
    """A local TCP port nothing listens on (bound, then closed at once)."""
    with socket.socket() as probe:
        probe.bind(('localhost', 0))
        return probe.getsockname()[1]


def line_with(stream, text, limit):
    """The first line read from stream (a pipe) that holds text, within limit wall seconds;
    None without one."""
    deadline = time.monotonic() + limit
    pending = b''
    while time.monotonic() < deadline:
        ready, _, _ = select.select([stream], [], [], max(0.0, deadline - time.monotonic()))
        if not ready:
            break
        chunk = os.read(stream.fileno(), 4096)
        if not chunk:
            break
        pending += chunk
        for line in pending.split(b'\n'):
            if text.encode() in line:
                return line.decode(errors='replace')
    return None


@pytest.mark.parametrize('number', [signal.SIGINT, signal.SIGTERM], ids=['SIGINT', 'SIGTERM'])
@pytest.mark.parametrize('script', ['wall_finder.py', 'wall_following.py', 'line_follower',
                                    'course_report', 'map_saver'])
def test_a_node_started_before_its_master_ends_at_once_on_a_signal(script, number):
    """rospy.init_node with no master retries registering for ever, holding the lock that
    rospy's shutdown waits for: the node never ended. It now waits for the master first,
    says so, and a signal meanwhile ends it quietly."""
    environment = dict(os.environ, ROS_MASTER_URI='http://localhost:%d' % closed_port())
    child = subprocess.Popen([sys.executable, os.path.join(SCRIPTS, script)],
                             stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=environment)
    try:
        said = line_with(child.stderr, 'waiting for the ROS master', 60.0)
        assert said, '%s never said it waits for the master' % script
        child.send_signal(number)
        assert child.wait(5.0) == 0
        rest = child.stderr.read().decode(errors='replace')
        assert 'Traceback' not in rest, rest
    finally:
        if child.poll() is None:
            child.kill()
            child.wait()
