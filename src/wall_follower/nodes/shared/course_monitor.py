"""Watches a simulated run from outside the robot, for reports, tests and benchmarks.

It listens to what the simulator knows and the robot does not (ground
truth, and stalls where the built-in simulator reports them) and to what the
nodes say (cmd_vel, the record_odom action's goal, feedback and result), and
scores the run with wall_follower.evaluation.scoring.course. Contact is judged from
ground truth and the map too, so the score works on real stageros, which
publishes no `stalled`.
"""
import threading
import xmlrpc.client

import genpy.dynamic
import numpy as np
import rosgraph
import rospy
from geometry_msgs.msg import Twist
from nav_msgs.msg import Odometry
from std_msgs.msg import Bool
from std_srvs.srv import Empty

from actionlib_msgs.msg import GoalStatus, GoalStatusArray

from wall_follower.evaluation.scoring.course import RunScore, stretches_on_trail
from wall_follower.nodes.shared.connections import keep_connected
from wall_follower.nodes.shared.messages import pose_of
from wall_follower.nodes.shared.shutdown import poll_until, raise_if_shut_down

# Every simulated step matters to a score, and in lockstep the simulator runs
# as fast as the controllers answer: queues long enough never to drop one.
QUEUE = 10000
# The topics a score cannot do without: ground truth, and the recorder's.
# `stalled` is not one: only the built-in simulator publishes it.
NEEDED_TOPICS = ('base_pose_ground_truth', 'feedback', 'result', 'status')
BUILTIN = 'builtin stage_sim'
STAGEROS = 'stageros'
# Wall seconds a node has to answer the master's ping.
PING_TIMEOUT = 3.0


def simulator_of(publications, truth_topic, stalled_topic):
    """Which simulator publishes truth_topic, from the master's [(topic, [node, ...])].

    Only the built-in simulator publishes `stalled` beside ground truth; any
    other publisher is real stageros (or one that speaks its interface).
    None when nobody publishes ground truth.
    """
    publishers = dict(publications)
    truth = set(publishers.get(truth_topic, ()))
    if not truth:
        return None
    return BUILTIN if truth & set(publishers.get(stalled_topic, ())) else STAGEROS


class _TimeoutTransport(xmlrpc.client.Transport):
    """An XML-RPC transport whose connections give up after a time-out."""

    def __init__(self, timeout):
        xmlrpc.client.Transport.__init__(self)
        self._timeout = timeout

    def make_connection(self, host):
        connection = xmlrpc.client.Transport.make_connection(self, host)
        connection.timeout = self._timeout
        return connection


def node_alive(name):
    """Whether the node `name` is registered and answers a ping.

    A node that ends cleanly unregisters from the master; one that was killed
    stays registered but no longer answers.
    """
    caller = rospy.get_name()
    try:
        uri = rosgraph.Master(caller).lookupNode(name)
    except (rosgraph.MasterError, OSError):
        return False
    proxy = xmlrpc.client.ServerProxy(uri, transport=_TimeoutTransport(PING_TIMEOUT))
    try:
        proxy.getPid(caller)
    except (OSError, xmlrpc.client.Error):
        return False
    return True


class AnyTypeSubscriber(object):
    """A subscription that takes the message type its publisher declares.

    A course solution declares the record_odom action in a package of its
    own, with Point or Point32 in its result: the messages are rebuilt from
    the definition each connection carries, so the monitor reads any of
    them by their field names.
    """

    def __init__(self, topic, callback, queue_size):
        self._callback = callback
        self._classes = {}
        self._sub = rospy.Subscriber(topic, rospy.AnyMsg, self._on_message, queue_size=queue_size)
        self.name = self._sub.name

    def _on_message(self, raw):
        header = raw._connection_header
        key = (header['type'], header['md5sum'])
        if key not in self._classes:
            self._classes[key] = genpy.dynamic.generate_dynamic(
                header['type'], header['message_definition'])[header['type']]
        message = self._classes[key]()
        message.deserialize(raw._buff)
        self._callback(message)

    def get_num_connections(self):
        return self._sub.get_num_connections()

    def unregister(self):
        self._sub.unregister()


class CourseMonitor(object):
    """Scores a run from ground truth while the nodes under test drive.

    With start_on_goal, scoring starts when a record_odom goal is sent (the
    course: the lap begins after find_wall); otherwise at the first pose.
    The goal's send time comes from whichever of the goal, status, feedback
    or result messages is seen first (each carries the goal's stamp), and
    ground truth is kept until then, so a monitor that missed the goal
    message itself still scores the lap from its true start. action_ns:
    the record_odom action's namespace; its messages may be of any
    package's OdomRecord action (see AnyTypeSubscriber).
    """

    def __init__(self, course_map, start_on_goal=True, action_ns='record_odom', **lap_params):
        self.score = RunScore(course_map, **lap_params)
        self.start_on_goal = start_on_goal
        self.lock = threading.Lock()
        self.done = threading.Event()
        self.pose = None
        self.pose_stamp = None
        self.goal_pose = None
        self.goal_time = None
        self.feedback = []
        self.result = None
        self.result_time = None
        self.result_status = None
        self.result_text = ''
        self.result_point_type = None
        self.trail = []
        self._trail_stamps = []
        self._before_goal = []
        # (stamp, pose) of every ground truth heard; with start_on_goal, all of it
        # until the goal comes is what scoring replays from the goal on.
        self._heard = []
        self._subs = [
            rospy.Subscriber('base_pose_ground_truth', Odometry, self._on_truth,
                             queue_size=QUEUE),
            rospy.Subscriber('cmd_vel', Twist, self._on_command, queue_size=QUEUE),
            rospy.Subscriber('stalled', Bool, self._on_stalled, queue_size=QUEUE),
            AnyTypeSubscriber(action_ns + '/goal', self._on_goal, queue_size=5),
            AnyTypeSubscriber(action_ns + '/feedback', self._on_feedback, queue_size=QUEUE),
            AnyTypeSubscriber(action_ns + '/result', self._on_result, queue_size=5),
            rospy.Subscriber(action_ns + '/status', GoalStatusArray, self._on_status, queue_size=5),
        ]
        self._keeper = keep_connected(self._subs)

    @property
    def truth_at_result(self):
        """True distance from the first recorded point to the last (None before the result)."""
        with self.lock:
            if not self.result:
                return None
            stretches = self._recorded_stretches()
            if len(stretches) < 2:
                return 0.0
            steps = np.diff(np.array(self.trail[stretches[0][0]:stretches[-1][0] + 1]), axis=0)
            return float(np.hypot(steps[:, 0], steps[:, 1]).sum())

    @property
    def recorded_stamps(self):
        """The ground-truth stamps at which the recorded points were taken (None before the result).

        The goal's and the result's stamps alone would not tell: in lockstep
        the simulator runs many times faster than real time, and the
        recorder starts and answers seconds of driving late.
        """
        spans = self.recorded_spans
        return None if spans is None else [earliest for earliest, _ in spans]

    @property
    def recorded_spans(self):
        """(earliest, latest) ground-truth stamp at which each recorded point may have been taken.

        The two differ only for a point taken while the robot stood still
        (see scoring.stretches_on_trail). None before the result.
        """
        with self.lock:
            if not self.result:
                return None
            stamps = self._trail_stamps
            return [(stamps[first], stamps[last]) for first, last in self._recorded_stretches()]

    def _recorded_stretches(self):
        """Where on the ground-truth trail, up to the result, each recorded point was taken."""
        recorded = int(np.searchsorted(self._trail_stamps, self.result_time, side='right'))
        return stretches_on_trail(self.trail[:recorded], self.result)

    def full_trail(self):
        """The whole true path heard, from the first pose: the lap's trail and, with
        start_on_goal, the way to where the lap began (all of it when no lap began)."""
        with self.lock:
            if self.start_on_goal and self.goal_time is None:
                return [pose[:2] for _, pose in self._heard]
            return self._before_goal + list(self.trail)

    @property
    def scoring(self):
        return not self.start_on_goal or self.goal_time is not None

    def _on_truth(self, msg):
        pose = pose_of(msg)
        stamp = msg.header.stamp.to_sec()
        with self.lock:
            self.pose, self.pose_stamp = pose, stamp
            self._heard.append((stamp, pose))
            if self.scoring:
                self._take(stamp, pose)

    def _take(self, stamp, pose):
        """Score a pose of the lap; one stamped before the goal is kept only as where the
        robot stood just before it.

        Ground truth and the goal come on connections of their own, and on a
        busy machine the truth of the last steps before the goal can come
        after it: those steps are find_wall's, not the lap's.
        """
        if self.start_on_goal and stamp < self.goal_time:
            # Odometry is the pose before each step, so the recorder's first
            # point can be where the robot was just before the goal: the
            # trail that places the points keeps that pose too.
            self._before_goal.extend(self.trail)
            self.trail[:] = [pose[:2]]
            self._trail_stamps[:] = [stamp]
        else:
            self._score(stamp, pose)

    def _score(self, stamp, pose):
        if self.goal_pose is None and self.start_on_goal:
            self.goal_pose = pose
        self.trail.append(pose[:2])
        self._trail_stamps.append(stamp)
        self.score.add_pose(stamp, pose)
        if not self.start_on_goal and self.score.lap.closed:
            self.done.set()

    def _goal_sent(self, goal_id):
        """Start scoring from the goal's send time, replaying the truth kept since."""
        with self.lock:
            if self.goal_time is not None:
                return
            self.goal_time = goal_id.stamp.to_sec()
            # The lap's time runs from the goal, not from whichever pose was
            # heard first: the simulator's very first one may come before
            # the monitor's connection does.
            self.score.begin(self.goal_time)
            for stamp, pose in self._heard if self.start_on_goal else []:
                self._take(stamp, pose)

    def _on_command(self, msg):
        with self.lock:
            self.score.add_command(msg.linear.x, msg.angular.z)

    def _on_stalled(self, msg):
        with self.lock:
            self.score.add_stall(msg.data)

    def _on_goal(self, msg):
        self._goal_sent(msg.goal_id)

    def _on_status(self, msg):
        if msg.status_list:
            self._goal_sent(msg.status_list[0].goal_id)

    def _on_feedback(self, msg):
        self._goal_sent(msg.status.goal_id)
        with self.lock:
            self.feedback.append(msg.feedback.current_total)

    def _on_result(self, msg):
        self._goal_sent(msg.status.goal_id)
        with self.lock:
            self.result = [(p.x, p.y, p.z) for p in msg.result.list_of_odoms]
            self.result_time = msg.header.stamp.to_sec()
            self.result_status = msg.status.status
            self.result_text = msg.status.text
            # Point or Point32: the course has seen both.
            self.result_point_type = dict(zip(msg.result.__slots__,
                                              msg.result._slot_types)).get('list_of_odoms')
            self.score.finish(self.result_time)
        if self.start_on_goal:
            self.done.set()

    def summary(self):
        """The score's figures so far (RunScore.summary).

        Under the lock: ground truth keeps arriving on the subscriber's
        thread, poses stamped up to the recorder's result still count after
        the run has ended, and a summary taken while one is being added
        would pair one pose's weight with another's distance.
        """
        with self.lock:
            return self.score.summary()

    def wait(self, catch_up=10.0):
        """Block until the run ends (result, or lap on ground truth); on shutdown,
        rospy.ROSInterruptException (shutdown.py: no run ended).

        Then, up to catch_up wall seconds, until ground truth has been heard
        up to the result's stamp too (see caught_up). There is no time-out
        for the run itself: rostest's time-limit and the launch's own end
        bound every run.
        """
        while not self.done.wait(0.1):
            raise_if_shut_down()
        if not poll_until(self.caught_up, catch_up, period=0.01):
            rospy.logwarn('course monitor: no ground truth up to the result after %.0f s; '
                          'scoring what came', catch_up)

    def poses_between(self, start, end):
        """The ground truth heard stamped from start to end [s], as (stamp, pose) pairs."""
        with self.lock:
            return [(stamp, pose) for stamp, pose in self._heard if start <= stamp <= end]

    def latest(self):
        """(stamp, pose) of the newest ground truth heard, (None, None) before any."""
        with self.lock:
            return self.pose_stamp, self.pose

    def caught_up(self):
        """Whether ground truth has been heard up to the end of the run.

        The result comes on a connection of its own and can overtake the
        ground truth stamped before it, by a second of simulated time when
        lockstep runs fast: figures taken at once would miss the lap's last
        steps, and show a shorter path in a longer lap.
        """
        with self.lock:
            if self.score.lap.closed:
                return True
            heard = self._trail_stamps[-1] if self._trail_stamps else None
            return None not in (heard, self.result_time) and heard >= self.result_time

    @property
    def lap_recorded(self):
        """Whether record_odom's goal ended with a lap (False before its result)."""
        return self.result_status == GoalStatus.SUCCEEDED

    def connected(self, topics=NEEDED_TOPICS):
        """Whether every one of topics (by last name) is connected; by default all a score needs."""
        return all(sub.get_num_connections() > 0 for sub in self._subs
                   if sub.name.rsplit('/', 1)[-1] in topics)

    def simulator(self):
        """Which simulator the run is on (simulator_of), asked of the master."""
        publications, _, _ = rosgraph.Master(rospy.get_name()).getSystemState()
        return simulator_of(publications, rospy.resolve_name('base_pose_ground_truth'),
                            rospy.resolve_name('stalled'))

    def start_world(self, limit=30.0):
        """Once every subscription is connected, unpause a simulator started paused.

        A monitor that starts listening late misses the start of the run;
        so the launch starts the simulator paused and the monitor lets it go
        only when it hears everything it needs. A simulator without pause_physics
        (real stageros) is left as it is. False if the monitor could not
        connect within limit wall seconds; rospy.ROSInterruptException if rospy
        shut down meanwhile (shutdown.py: that is no simulator missing).
        """
        if not poll_until(self.connected, limit):
            return False
        try:
            rospy.wait_for_service('unpause_physics', timeout=min(5.0, limit))
        except rospy.ROSException:
            raise_if_shut_down()
            rospy.loginfo('no unpause_physics service: the simulator was not paused')
            return True
        rospy.ServiceProxy('unpause_physics', Empty)()
        return True

    def close(self):
        self._keeper.stop()
        for sub in self._subs:
            sub.unregister()
