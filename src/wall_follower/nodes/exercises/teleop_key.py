"""teleop_key: drive with the keyboard, as ROBOTIS's turtlebot3_teleop_key does, but safely.

Keys come from standard input: a terminal (put in cbreak mode, so that
each key counts without Enter, and restored on exit) or a pipe, so that a
test or a script can drive it. Each key is applied as it comes; commands go
out on a steady ~tick whether or not a key is pressed (Stage stops a robot
0.2 s after its last cmd_vel, and ROBOTIS's node publishes only once per
key or 0.1 s idle), through the DriveLoop every driving node shares: so the
robot also stops while the laser is stale or unusable, and does not drive
forward into a sector ahead that it cannot see. Ctrl-C (a signal from a
terminal, or the byte 0x03 from a pipe) or the end of the input quits with
a zero Twist, and so does an input that cannot be read (standard input
closed, or not readable), with an error and exit status 1. Its
parameters (params/exercises/teleop_key.py: the steps, the limits, the tick) are
tuned live, from the next tick on.
"""
import os
import queue
import sys
import threading

import rospy

from wall_follower.cfg import TeleopKeyConfig
from wall_follower.exercises.teleop import USAGE, Teleop
from wall_follower.nodes.shared.drive_loop import drive_loop, take_retuned
from wall_follower.nodes.shared.latest_scan import LatestScan
from wall_follower.nodes.shared.parameters import NodeParameters
from wall_follower.nodes.shared.startup import init_node
from wall_follower.params import pick
from wall_follower.params.exercises.teleop_key import TABLE, TELEOP


# Bytes taken from standard input at once: more than anyone types between two ticks.
KEY_CHUNK = 1024


class KeyReader(object):
    """Reads standard input in a thread of its own; keys wait in a queue.

    stream: the input (sys.stdin, None when the process has none). An input
    that cannot be read ends the keys as its end does, with `problem` saying
    why (None for a plain end of input). Keys that came together (a burst
    written to a pipe, a paste, a held key that repeated while the node was
    busy) are read in one go and queued as one batch, so that the next tick
    applies them all: read byte by byte, a busy machine would hand them over
    a few per tick and stretch the ramp.
    """

    def __init__(self, stream):
        self.keys = queue.Queue()
        self.problem = None
        self._terminal = None
        self.fd = _descriptor(stream)
        if self.fd is None:
            self.problem = 'no standard input to read keys from (it is closed)'
            self.keys.put(None)
            return
        if os.isatty(self.fd):
            import termios
            import tty
            self._terminal = termios.tcgetattr(self.fd)
            tty.setcbreak(self.fd)
        thread = threading.Thread(target=self._read, name='keys')
        thread.daemon = True
        thread.start()

    def _read(self):
        while True:
            try:
                data = os.read(self.fd, KEY_CHUNK)
            except OSError as err:
                self.problem = 'cannot read keys from standard input (%s)' % (
                    err.strerror or err)
                data = b''
            if not data:
                self.keys.put(None)     # end of input
                return
            self.keys.put(data.decode('latin-1'))   # one batch of keys

    def pending(self):
        """The keys that have come since the last call (None for the end of input)."""
        keys = []
        while True:
            try:
                batch = self.keys.get_nowait()
            except queue.Empty:
                return keys
            keys.extend([None] if batch is None else batch)

    def restore(self):
        if self._terminal is not None:
            import termios
            termios.tcsetattr(self.fd, termios.TCSADRAIN, self._terminal)


def _descriptor(stream):
    """The file descriptor of stream, None if it has none (closed, or not a file)."""
    if stream is None:
        return None
    try:
        return stream.fileno()
    except (AttributeError, OSError, ValueError):   # io.UnsupportedOperation is both
        return None


class TeleopKeyNode(object):

    def __init__(self):
        self.params = NodeParameters(TABLE, TeleopKeyConfig)
        values = self.params.snapshot()
        self.loop = drive_loop('teleop_key', values, LatestScan('scan'), tick=values['tick'])
        self.teleop = Teleop(**pick(values, TELEOP))
        self.keys = KeyReader(sys.stdin)

    def run(self):
        say(USAGE % (self.teleop.max_linear, self.teleop.max_angular))
        try:
            self.loop.run(self._tick, self._keys)
        finally:
            self.keys.restore()
        return 1 if self.keys.problem else 0

    def _tick(self, _view, _taken):
        """The next command of the ramp, under any parameters changed since the last tick."""
        values = take_retuned(self.params, self.loop)
        if values is not None:
            self.loop.tick = values['tick']
            self.teleop.reconfigure(**pick(values, TELEOP))
        return self.teleop.tick()

    def _keys(self):
        """Apply the keys pressed since the last pass; 'quit' once one says so."""
        for key in self.keys.pending():
            if key is None:
                if self.keys.problem:
                    rospy.logerr('teleop_key: %s; stopping', self.keys.problem)
                else:
                    say('teleop_key: end of input; stopping')
                return 'quit'
            if self.teleop.press(key):
                say(self.teleop.describe())
            if self.teleop.quit:
                say('teleop_key: Ctrl-C (byte 0x03) read; stopping')
                return 'quit'
        return None


def say(text):
    """Print for the person at the keyboard (not a log line: this is the node's display)."""
    sys.stdout.write(text + '\n')
    sys.stdout.flush()


def main():
    init_node('teleop_key')
    return TeleopKeyNode().run()
