"""Parameters of the course_report node, read once at start.

No dynamic_reconfigure server: the report is a one-shot tool that waits
for one lap, writes its summary and ends; what it reads (the world, the
files to write) is needed before the lap starts and cannot change after.
"""
from wall_follower.params import Parameter as P, Section

TABLE = (
    Section('report', (
        P('world', 'arena', 'the world the run is scored against: a world of worlds/ by name, '
          'or a .world path'),
        P('plot', '', "PNG file for the recorded path over the map; empty: none"),
        P('json', '', "file for the run's figures (the benchmark reads it); empty: none"),
        P('follower', 'wall_following', 'the node that drives the lap: once it has ended '
          'without one, no lap can come'),
    )),
)
"""Every parameter of course_report."""
