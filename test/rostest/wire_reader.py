"""A subscription read straight off its TCPROS socket, in the caller's thread.

rospy's subscribers each read on a thread of their own, so the order in
which two topics' callbacks run says as much about the subscriber's threads
as about the publisher. A test of the order in which a publisher puts
messages on the wire reads the sockets itself: what is in a socket when
another's message is read had been sent before it.
"""
import io
import select
import socket
import struct
from xmlrpc.client import ServerProxy

import rosgraph
from rosgraph.network import read_ros_handshake_header, write_ros_handshake_header

WAIT_LIMIT = 10.0   # wall seconds, to connect or for a message; only bounds a failing test
LENGTH = struct.Struct('<I')


class WireReader(object):
    """Messages of `topic` from the one node that publishes it, in the order sent.

    caller_id: a name no other subscriber of the publisher uses (rospy keeps one
    connection per caller and topic, and drops the older).
    """

    def __init__(self, caller_id, topic, data_class):
        self._class = data_class
        master = rosgraph.Master(caller_id)
        name = rosgraph.names.resolve_name(topic, caller_id)
        publishers = [nodes for listed, nodes in master.getSystemState()[0] if listed == name]
        if not publishers or len(publishers[0]) != 1:
            raise AssertionError('%s has no single publisher: %s' % (name, publishers))
        node_uri = master.lookupNode(publishers[0][0])
        code, message, protocol = ServerProxy(node_uri).requestTopic(
            caller_id, name, [['TCPROS']])
        if code != 1:
            raise AssertionError('requestTopic %s: %s' % (name, message))
        self._socket = socket.create_connection((protocol[1], protocol[2]), WAIT_LIMIT)
        self._socket.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        write_ros_handshake_header(self._socket, {
            'callerid': caller_id, 'topic': name, 'md5sum': data_class._md5sum,
            'type': data_class._type, 'tcp_nodelay': '1'})
        received = io.BytesIO()
        read_ros_handshake_header(self._socket, received, 65536)
        self._buffer = received.getvalue()   # what came after the header

    def close(self):
        self._socket.close()

    def next(self, limit=WAIT_LIMIT):
        """The next message, waiting up to `limit` wall seconds for it; None if none came."""
        while True:
            message = self._parse()
            if message is not None:
                return message
            if not self._receive(limit):
                return None

    def pending(self):
        """Every message already in the socket, without waiting."""
        while self._receive(0.0):
            pass
        found = []
        message = self._parse()
        while message is not None:
            found.append(message)
            message = self._parse()
        return found

    def _receive(self, limit):
        readable, _, _ = select.select([self._socket], [], [], limit)
        if not readable:
            return False
        data = self._socket.recv(65536)
        if not data:
            raise AssertionError('the publisher closed the connection')
        self._buffer += data
        return True

    def _parse(self):
        if len(self._buffer) < LENGTH.size:
            return None
        (size,) = LENGTH.unpack_from(self._buffer)
        end = LENGTH.size + size
        if len(self._buffer) < end:
            return None
        message = self._class().deserialize(self._buffer[LENGTH.size:end])
        self._buffer = self._buffer[end:]
        return message
