"""Parameters of the find_trials node, read once at start.

No dynamic_reconfigure server: find_trials is a one-shot tool that runs
its trials and ends. Its start poses are a structure (world -> list of
poses), which only a node without live tuning can take: dynamic_reconfigure
has no type for it.
"""
from wall_follower.params import Parameter as P, Section

TABLE = (
    Section('trials', (
        P('world', 'arena', 'the world the trials run in: a world of worlds/ by name, or a '
          '.world path; its start poses are those under its name in poses'),
        P('poses', {}, 'start poses of find_wall: world name -> list of [x, y, yaw] [m, m, '
          'degrees]'),
        P('json', '', "file for the trials' figures (the benchmark reads it); empty: none"),
    )),
)
"""Every parameter of find_trials."""
