"""The lab's robot arm (cougarbot) as plain logic: its model, kinematics, collisions and
trajectories.

Free of ROS, so that unit tests and the benchmark use it with no master:

- model.py: the URDF, the SRDF and MoveIt's joint_limits.yaml, read into plain objects;
- kinematics.py: forward kinematics of every link, closed-form inverse kinematics of
  the `hand` origin;
- collision.py: the links against the floor and against each other;
- timing.py: a joint-space move timed within the velocity and acceleration limits, and a
  stop within the acceleration limits;
- planning.py: a planned move to a named state or a point (kinematics, collision check and
  timing together), and the goals it refuses;
- spline.py: the polynomial segments between trajectory points;
- trajectory.py: JointTrajectoryController's rules for a command and what it follows, and
  its stop.

The nodes arm_controller, move_arm and arm_plot (wall_follower.nodes) wire them to ROS.
"""
