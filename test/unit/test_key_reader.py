"""teleop_key's KeyReader: an input that is closed or cannot be read ends the keys with the
problem in words, as the end of input ends them, instead of a traceback. Needs ROS's Python
modules (the node's module imports them) but no master."""
import io
import os
import time

from wall_follower.nodes.exercises.teleop_key import KeyReader

WAIT = 5.0


def keys_until_end(reader):
    """Every key the reader hands over up to and with the end of input (None)."""
    keys, deadline = [], time.monotonic() + WAIT
    while time.monotonic() < deadline:
        keys.extend(reader.pending())
        if keys and keys[-1] is None:
            return keys
        time.sleep(0.01)
    raise AssertionError('no end of input after %r' % keys)


class Descriptor(object):
    """A stream that is only a file descriptor."""

    def __init__(self, fd):
        self.fd = fd

    def fileno(self):
        return self.fd


def test_a_closed_standard_input_ends_the_keys_and_says_so():
    reader = KeyReader(None)
    assert keys_until_end(reader) == [None]
    assert reader.problem == 'no standard input to read keys from (it is closed)'
    reader.restore()


def test_a_stream_without_a_descriptor_is_taken_as_closed():
    reader = KeyReader(io.StringIO('w'))
    assert keys_until_end(reader) == [None]
    assert 'no standard input' in reader.problem


def test_an_input_that_cannot_be_read_ends_the_keys_and_says_why(tmp_path):
    descriptor = os.open(str(tmp_path), os.O_RDONLY)   # a directory: read() fails
    try:
        reader = KeyReader(Descriptor(descriptor))
        assert keys_until_end(reader) == [None]
    finally:
        os.close(descriptor)
    assert reader.problem.startswith('cannot read keys from standard input (')


def test_keys_from_a_pipe_then_its_end_are_no_problem():
    read_end, write_end = os.pipe()
    os.write(write_end, b'wa\x03\xff')
    os.close(write_end)
    with os.fdopen(read_end, 'rb') as stream:
        reader = KeyReader(stream)
        assert keys_until_end(reader) == ['w', 'a', '\x03', '\xff', None]
    assert reader.problem is None
