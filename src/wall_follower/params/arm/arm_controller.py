"""Parameters of the arm_controller node (the built-in stand-in for Gazebo + ros_control's
joint_trajectory_controller), read once at start."""
from wall_follower.params import Parameter as P, Section

TABLE = (
    Section('controller', (
        P('rate', 50.0, 'how often the joints are stepped and joint_states published [Hz]',
          1.0, 1000.0),
        P('initial_positions', {}, 'joint name -> position to start at [rad]; a joint not '
          'named starts at 0, or at its nearest limit'),
    )),
    Section('clock', (
        P('publish_clock', False, 'drive /clock: each step advances simulated time by 1/rate '
          '(for tests and demos on /use_sim_time; simulated time then stands still while the '
          'controller is held up, instead of jumping)'),
        P('speedup', 1.0, 'with publish_clock: simulated seconds per wall second', 0.01, 100.0),
    )),
)
"""Every parameter of arm_controller (wall_follower.nodes.arm.arm_controller)."""
