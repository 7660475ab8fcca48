"""When a service was called and when it replied, seen from its TCP connections.

A ROS service call is a TCP connection of its own from the client to the
port of the node that serves it (its rosrpc:// URI), held open by the
server while its handler runs and closed once the reply has been read.
The same port also takes the node's topic connections (every subscriber
of what it publishes, rosout's included), which stay open as long as the
subscriber does. So, polled from the kernel's table of the namespace's
TCP sockets (/proc/net/tcp, tcp6), each established connection to the
port is followed by its peer's address: one that came and went while
the run went on was a call (or the probe of rospy.wait_for_service,
which lasts no simulated time); one still open at the end is a topic's,
or a call that never replied, which cannot be told apart.
"""

ESTABLISHED = '01'
TABLES = ('/proc/net/tcp', '/proc/net/tcp6')
# Simulated seconds a call lasts at least to be taken for the real one (a probe does not).
LASTING = 0.1


def peers_by_port(text):
    """{local port: the peers (remote address:port, as the table writes them)} of the
    established connections in a /proc/net/tcp text."""
    found = {}
    for line in text.splitlines()[1:]:
        fields = line.split()
        if len(fields) < 4 or ':' not in fields[1] or fields[3] != ESTABLISHED:
            continue
        found.setdefault(int(fields[1].rsplit(':', 1)[1], 16), set()).add(fields[2])
    return found


def connected_peers(tables=TABLES):
    """peers_by_port in this network namespace, now."""
    found = {}
    for table in tables:
        try:
            with open(table) as stream:
                for port, peers in peers_by_port(stream.read()).items():
                    found.setdefault(port, set()).update(peers)
        except (IOError, OSError):
            pass
    return found


class PortWatch(object):
    """A CallWatch for every port connections were seen to, from before anyone knows
    which port is the service's: a call may begin, and end, before the service has been
    seen in the graph."""

    def __init__(self):
        self.ports = {}

    def look(self, peers, before, after=None):
        """A poll: peers as connected_peers gives them, read between the moments before and
        after (CallWatch.look)."""
        for port in set(self.ports) | set(peers):
            self.ports.setdefault(port, CallWatch()).look(peers.get(port, ()), before, after)

    def of(self, port):
        return self.ports.get(port) or CallWatch()


class CallWatch(object):
    """The calls of one service seen so far: each a dict of its start and end (simulated
    s) and the robot's pose at each.

    A poll sees a reply only after it came: the call ended between the last
    poll that saw it open ('last_open', 'last_open_pose') and the first that
    did not ('end', 'end_pose'). Polls come every few wall milliseconds, but
    on a busy machine one may come late, while simulated time runs on and
    the solution drives away from where its reply left the robot; the pair
    says how far apart the two bounds are.
    """

    def __init__(self):
        self.calls = []
        self._open = {}

    def look(self, peers, before, after=None):
        """What a poll saw: the peers connected to the service's port, read from the table
        between the moments before and after ((simulated time, the robot's pose) each;
        after defaults to before).

        A connection seen open was still open at the read, so it is stamped
        with the moment before it; one found gone had closed by the read, so
        it is stamped with the moment after. On a busy machine the read can
        take a second of simulated time: stamped after it, a call seen open
        would seem to have been open past its reply, and be judged where the
        solution had already driven on.
        """
        after = before if after is None else after
        for peer in set(self._open) - set(peers):
            call = self._open.pop(peer)
            call.update(end=after[0], end_pose=after[1])
            self.calls.append(call)
        for peer in peers:
            call = self._open.setdefault(peer, {'start': before[0], 'start_pose': before[1]})
            call.update(last_open=before[0], last_open_pose=before[1])

    def judged(self):
        """The call to judge find_wall by: the first seen open for LASTING, else the longest;
        None when no call ended.

        Whether a call lasted is told by the polls that saw it open
        ('start' to 'last_open'), not by the one that found it closed: a
        probe seen by one poll would last as long as the gap to the next,
        which under load may pass LASTING.
        """
        lasting = [c for c in self.calls if c['last_open'] - c['start'] >= LASTING]
        if lasting:
            return lasting[0]
        return max(self.calls, key=lambda c: c['end'] - c['start']) if self.calls else None


def reply_moment(call, alignment, between=(), fits=lambda aligned: False):
    """(time, pose, alignment) at which to judge a call's reply.

    The grader cannot tell where between its two polls (CallWatch) the reply
    came, and its own late poll must not fail the solution: on a busy
    machine the closing poll may come seconds of simulated time after the
    reply, once the solution has driven on. So every moment the reply may
    have come at is a candidate: the two bounds, and `between`, the
    (time, pose) pairs of the robot's true poses heard between them.
    alignment(pose) finds the wall beside the robot ((distance, heading
    error) or None); fits(alignment) says whether that is where the call
    had to leave it. Of the candidates with a wall, one that fits is taken
    if any does, the one where the robot stood most nearly parallel among
    those; with no wall at any, the first bound.
    """
    bounds = [(call['last_open'], call['last_open_pose']), (call['end'], call['end_pose'])]
    candidates = bounds[:1] + sorted(between, key=lambda moment: moment[0]) + bounds[1:]
    moments = [(time, pose, alignment(pose)) for time, pose in candidates if pose is not None]
    if not moments:
        return None
    aligned = [moment for moment in moments if moment[2] is not None]
    if not aligned:
        return moments[0]
    return min(aligned, key=lambda moment: (not fits(moment[2]), abs(moment[2][1])))
