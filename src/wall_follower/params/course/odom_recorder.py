"""Parameters of the odom_recorder node (the record_odom action): the node's own, then the lap's."""
import math

from wall_follower.params import Parameter as P, Section, odometry

NODE = (
    Section('node', (
        P('sample_period', 1.0, 'a point is recorded every this many seconds of ROS time [s]',
          0.01, 60.0),
        P('timeout', 5.0, 'a goal is aborted when no odometry stamped since the goal has '
          'arrived for this long [s] of ROS time and of wall time (a simulation faster than '
          'real time can outrun the odometry queue), also when the client clock is far ahead',
          0.1, 600.0),
        P('rate', 10.0, 'how often the goal loop checks for new points, the end of the lap, '
          'cancellation and the odometry time-out [Hz]', 1.0, 100.0),
    )),
)
"""odom_recorder's own parameters (wall_follower.nodes.course), in force from the next goal."""

RECORDING = (
    Section('lap', (
        P('min_travel', 2.0, 'a lap can end only after the robot has travelled this far [m] ...',
          0.0, 1000.0),
        P('leave_radius', 0.5, '... and been this far from the start point [m]', 0.0, 100.0),
        P('close_tolerance', 0.3, 'the lap ends when the robot crosses the start line this '
          'near the start point, or passes this near it [m] ...', 0.0, 100.0),
        P('max_heading_error', math.radians(60.0), '... heading within this of the start '
          'heading (passing it: of the path that left it) [rad]', 0.0, math.pi),
    )),
    odometry.JUMPS,
)
"""How a recording is kept (wall_follower.control.course.lap.LapRecorder): when a lap counts as
closed (LapDetector) and what is a jump, not counted as travel (JumpDetector). From the next
goal too."""

TABLE = NODE + RECORDING
