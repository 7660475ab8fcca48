"""Parameters of the arm_plot node (the lab's rqt_plot of joint_states), read once at start."""
from wall_follower.params import Parameter as P, Section

TABLE = (
    Section('plot', (
        P('file', 'arm_joints.png', 'the PNG written: positions and velocities against time'),
        P('duration', 0.0, 'record this long, save and exit [s of ROS time]; 0: until the node '
          'is stopped, then save', 0.0, 86400.0),
        P('window', 30.0, 'the live window shows the last this many seconds [s]', 1.0, 3600.0),
        P('live', True, 'show a live window where a display exists'),
    )),
)
"""Every parameter of arm_plot (wall_follower.nodes.arm.arm_plot)."""
