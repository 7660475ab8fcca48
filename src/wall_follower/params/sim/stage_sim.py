"""Parameters of the stage_sim node (the built-in simulator), read once at start.

The world file sets the rest (the robots, the laser, the step); these are
what stageros does not have or takes on its command line. No
dynamic_reconfigure server: a world does not change its physics mid-run.
"""
from wall_follower.params import Parameter as P, Section
from wall_follower.sim.laser_profiles import PROFILES

TABLE = (
    Section('pace', (
        P('speedup', 1.0, 'simulated seconds per wall second, held steady; 0 runs as fast as '
          'possible', 0.0, 10000.0),
        P('late_command_share', 0.5, 'at a held speedup, a step waits at most this share of its '
          'period for the next cmd_vel of a driven robot; the steady schedule takes the delay '
          'back on the next steps', 0.0, 1.0),
        P('lockstep', False, 'step only after every driven robot (commanded to move, or held '
          'still by a controller that told it to stand before each of the last two steps) has '
          'answered the last step\'s scans with a new cmd_vel, so that results do not depend on '
          'machine load'),
        P('lockstep_timeout', 1.0, 'in lockstep, step anyway after this long without one '
          '[wall s]', 0.0, 60.0),
        P('lockstep_grace', 0.05, 'in lockstep, the wait when nobody drives [wall s]',
          0.0, 10.0),
        P('paused', False, 'start without stepping until unpause_physics is called (a world '
          'file that says paused starts paused either way)'),
        P('quit_time', -1.0, 'exit after this many simulated seconds [s]; 0: never; '
          'negative: as the world file says', -1.0, 1e9),
    )),
    Section('robot', (
        P('laser_profile', 'stage', 'the scan convention to emulate: stage, lds01, lds02, gazebo '
          'or course720', choices=PROFILES),
        P('seed', 0, 'seed of the laser profile noise and of the odometry errors drawn for a robot '
          'with localization "odom" and no odom_error', 0, 2 ** 31 - 1),
        P('pose', '', 'x y yaw_deg: start pose of the first robot instead of the world file '
          'one; reset_positions returns there; empty: the world file pose'),
        P('base_watchdog_timeout', 0.2, 'simulated seconds without cmd_vel before a robot '
          'stops [s]', 0.0, 60.0),
    )),
)
"""Every parameter of stage_sim."""
