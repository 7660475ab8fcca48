"""A simulator played by a test node: /clock and the odometry of a robot driving along x."""
import threading
import time

import rospy
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock

STEP = 0.1              # simulated seconds per world step: a /clock and an odometry each
SPEED = 0.2             # m/s along x
# Wall seconds the simulator is away while it restarts: it publishes nothing.
RESTART_PAUSE = 0.5


class OdometryWorld(object):
    """A clock from `clock` (simulated s) and the odometry of a robot driving along x,
    one step every wall_step wall seconds, in a thread of its own until stop().

    published holds (stamp, x, y) of every well-formed pose. With malformed set,
    each step also sends a pose with a NaN position and one whose quaternion is
    no rotation. silence() lets the clock run on without odometry.
    """

    def __init__(self, clock, wall_step):
        self.clock = rospy.Publisher('/clock', Clock, queue_size=10)
        self.odom = rospy.Publisher('odom', Odometry, queue_size=100)
        self.lock = threading.Lock()
        self.now = clock
        self.wall_step = wall_step
        self.y = 0.0
        self.x = 0.0
        self.malformed = False
        self.published = []
        self._silent_until = None
        self._stop = threading.Event()
        self._thread = threading.Thread(target=self._run)
        self._thread.start()

    def restart(self, clock, y):
        """The simulator restarts: silent a moment, then the clock is back, the robot elsewhere."""
        with self.lock:
            time.sleep(RESTART_PAUSE)
            self.now = clock
            self.x, self.y = 0.0, y

    def silence(self, seconds):
        """Publish no odometry for the next `seconds` of simulated time; the clock runs on."""
        with self.lock:
            self._silent_until = self.now + seconds

    def stop(self):
        self._stop.set()
        self._thread.join()

    def _run(self):
        while not self._stop.is_set() and not rospy.is_shutdown():
            with self.lock:
                self._step()
            time.sleep(self.wall_step)

    def _step(self):
        self.now += STEP
        self.x += SPEED * STEP
        stamp = rospy.Time.from_sec(self.now)
        self.clock.publish(Clock(clock=stamp))
        if self._silent_until is not None and self.now < self._silent_until:
            return
        self.odom.publish(odometry(stamp, self.x, self.y))
        self.published.append((self.now, self.x, self.y))
        if self.malformed:
            no_rotation = odometry(stamp, self.x, self.y)
            no_rotation.pose.pose.orientation.w = 0.0
            self.odom.publish(odometry(stamp, float('nan'), self.y))
            self.odom.publish(no_rotation)


def odometry(stamp, x, y):
    """nav_msgs/Odometry in frame odom at (x, y), heading along x."""
    msg = Odometry()
    msg.header.stamp = stamp
    msg.header.frame_id = 'odom'
    msg.pose.pose.position.x = x
    msg.pose.pose.position.y = y
    msg.pose.pose.orientation.w = 1.0
    return msg
