"""Parameters of the move_arm node (planned moves of the arm), in force from the next goal."""
from wall_follower.params import Parameter as P, Section

TABLE = (
    Section('planning', (
        P('floor_margin', 0.0, 'the least clearance between a moving link and the floor '
          '(z = 0) that counts as clear [m]', 0.0, 0.5),
        P('self_margin', 0.0, 'the least clearance between two links that counts as clear [m]',
          0.0, 0.5),
        P('collision_step', 0.02, 'the joint-space line is checked for collisions every this '
          'much motion of the joint moving most [rad]', 0.001, 0.5),
        P('waypoint_spacing', 0.1, 'time between the points of the trajectory sent [s]',
          0.01, 2.0),
    )),
    Section('execution', (
        P('goal_tolerance', 0.01, 'the move is done once every joint is within this of its '
          'goal [rad] ...', 0.0001, 0.5),
        P('stopped_velocity', 0.01, '... and slower than this [rad/s] ...', 0.0001, 1.0),
        P('settle_timeout', 2.0, '... at most this long after the trajectory\'s end [s], or '
          'the goal is aborted', 0.1, 60.0),
        P('state_timeout', 1.0, 'joint_states older than this is stale: no goal is started, '
          'and a running one is stopped [s]', 0.05, 60.0),
        P('tf_timeout', 1.0, 'how long to wait for a transform from tf [s]', 0.01, 60.0),
        P('controller_timeout', 5.0, 'how long a planned goal waits for the arm controller '
          'to subscribe to arm_controller/command before it is aborted [wall s]', 0.1, 300.0),
    )),
)
"""Every parameter of move_arm (wall_follower.nodes.arm.move_arm)."""
