"""Parameters of the grade_case node (one graded run), read once at start.

No dynamic_reconfigure server: the node watches one run of a solution
under grading and ends; what it reads is needed before the run starts.
"""
from wall_follower.params import Parameter as P, Section

TABLE = (
    Section('case', (
        P('world', '', 'the .world file the run is scored against (the one the simulator runs)'),
        P('json', '', "file for the case's ground-truth record (the grader reads it)"),
        P('plot', '', 'PNG file for the true path over the map; empty: none'),
        P('action_ns', 'record_odom', "namespace of the solution's record_odom action"),
    )),
    Section('limits', (
        P('start_limit', 30.0, 'wall seconds the solution\'s launch file has to start its nodes, '
          'before the run ends when none is alive [s]', 1.0, 600.0),
        P('time_limit', 400.0, 'simulated seconds the run may last before it is ended without '
          'a lap [s]', 1.0, 1e5),
        P('idle_limit', 30.0, 'simulated seconds without a cmd_vel (since the start or the last '
          'one), or stalled against an obstacle, before the run is ended as stuck [s]',
          1.0, 1e5),
        P('gone_limit', 5.0, 'wall seconds with none of the solution\'s nodes alive before the '
          'run is ended [s]', 0.5, 600.0),
        P('after_result', 5.0, 'simulated seconds of ground truth kept after the lap is '
          'declared, to see whether the robot truly came back [s]', 0.0, 600.0),
    )),
)
"""Every parameter of grade_case."""
