"""What the arm's rostests watch: every joint_states heard, and whether any broke the URDF's
limits, put a link below the floor or one link into another."""
import threading

import numpy as np
import rospy
from sensor_msgs.msg import JointState

from waiting import wait_until
from wall_follower.arm.collision import CollisionChecker
from wall_follower.arm.model import read_srdf, read_urdf

# Wall seconds a rostest waits for the arm to reach a time or a state before failing.
WALL_LIMIT = 30.0
# s: how far below the time it was taken at a stamp may read (rospy.Time.from_sec truncates
# to the nanosecond)
STAMP_ROUNDING = 1e-6


class ArmWatch(object):
    """joint_states as (stamp [s], positions, velocities) in the model's joint order."""

    def __init__(self, wait=True):
        """wait: return once the first joint_states has come (False: the caller first starts
        what makes the arm publish them, then calls wait_for_first_state)."""
        self.model = read_urdf(rospy.get_param('robot_description'))
        self.semantics = read_srdf(rospy.get_param('robot_description_semantic'), self.model)
        self.checker = CollisionChecker(self.model, self.semantics.disabled)
        self._lock = threading.Lock()
        self.states = []
        rospy.Subscriber('joint_states', JointState, self._on_state, queue_size=1000)
        if wait:
            self.wait_for_first_state()

    def wait_for_first_state(self):
        if not wait_until(lambda: self.states, WALL_LIMIT):
            raise AssertionError('no joint_states from the arm')

    def _on_state(self, msg):
        order = [list(msg.name).index(name) for name in self.model.names]
        with self._lock:
            self.states.append((msg.header.stamp.to_sec(),
                                np.array([msg.position[i] for i in order]),
                                np.array([msg.velocity[i] for i in order])))

    def latest(self):
        with self._lock:
            return self.states[-1]

    def reached(self, time):
        """Whether a joint state stamped at or after time [s] has come."""
        with self._lock:
            return bool(self.states) and self.states[-1][0] >= time - STAMP_ROUNDING

    def since(self, start, end=float('inf')):
        with self._lock:
            return [s for s in self.states if start <= s[0] <= end]

    def wait_for_time(self, time):
        """Wait until a joint state stamped at or after time [s] has come; False if none did."""
        return wait_until(lambda: self.reached(time), WALL_LIMIT)

    def at(self, time):
        """The joint positions at time [s], interpolated between the states around it."""
        with self._lock:
            stamps = np.array([s[0] for s in self.states])
            positions = np.array([s[1] for s in self.states])
        return np.array([np.interp(time, stamps, positions[:, j])
                         for j in range(positions.shape[1])])

    def assert_safe(self, test):
        """Every state heard within the position and speed limits, no link below the floor,
        no two links (but the SRDF's pairs) touching; and no step faster than the limits."""
        with self._lock:
            states = list(self.states)
        model = self.model
        for (stamp, positions, velocities), following in zip(states, states[1:] + [None]):
            test.assertEqual(model.outside_limits(positions), [], 'at %.2f s' % stamp)
            test.assertTrue((np.abs(velocities) <= model.velocity + 1e-9).all(),
                            'at %.2f s: velocities %s' % (stamp, velocities))
            test.assertEqual(self.checker.contacts(positions), [], 'at %.2f s' % stamp)
            if following is not None and following[0] > stamp:
                speed = np.abs(following[1] - positions) / (following[0] - stamp)
                test.assertTrue((speed <= model.velocity * 1.001 + 1e-6).all(),
                                'from %.2f s: %s rad/s' % (stamp, speed))
        test.assertGreater(len(states), 50)
