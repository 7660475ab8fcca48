"""When a service was called and when it replied, seen from its TCP connections.

A ROS service call is a TCP connection of its own from the client to the
service's port (its rosrpc:// URI), held open by the server while its
handler runs and closed once the reply has been read. So, polled from the
kernel's table of the namespace's TCP sockets (/proc/net/tcp, tcp6), an
established connection to the service's port is a call in progress. The
probe of rospy.wait_for_service closes at once, before the server has
answered, and is not held established.
"""

ESTABLISHED = '01'
TABLES = ('/proc/net/tcp', '/proc/net/tcp6')


def established_to(port, text):
    """How many established connections in a /proc/net/tcp text have port as their local
    port (the server's side of a call)."""
    found = 0
    for line in text.splitlines()[1:]:
        fields = line.split()
        if len(fields) < 4 or ':' not in fields[1]:
            continue
        local_port = int(fields[1].rsplit(':', 1)[1], 16)
        if local_port == port and fields[3] == ESTABLISHED:
            found += 1
    return found


def open_calls(port, tables=TABLES):
    """Established connections to port in this network namespace, now."""
    found = 0
    for table in tables:
        try:
            with open(table) as stream:
                found += established_to(port, stream.read())
        except (IOError, OSError):
            pass
    return found


class CallWatch(object):
    """The calls of one service seen so far: each a dict of its start and end (simulated
    s; end None while it has not replied) and the pose at each."""

    def __init__(self):
        self.calls = []

    def look(self, time, open_count, pose):
        """What a poll saw at time: open_count calls in progress, the robot at pose."""
        current = self.calls[-1] if self.calls else None
        if open_count > 0 and (current is None or current['end'] is not None):
            self.calls.append({'start': time, 'end': None, 'start_pose': pose,
                               'end_pose': None})
        elif open_count == 0 and current is not None and current['end'] is None:
            current.update(end=time, end_pose=pose)

    def judged(self):
        """The call to judge find_wall by: the first that replied after simulated time had
        passed (a call answered at once may be a double of the real one), else the last
        that replied, else one that never replied; None when there was no call."""
        replied = [c for c in self.calls if c['end'] is not None]
        lasting = [c for c in replied if c['end'] > c['start']]
        if lasting:
            return lasting[0]
        if replied:
            return replied[-1]
        return self.calls[-1] if self.calls else None
