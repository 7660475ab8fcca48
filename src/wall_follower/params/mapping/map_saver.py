"""Parameters of the map_saver node, read once at start.

No dynamic_reconfigure server: map_saver is a one-shot tool that saves one
map and exits, so nothing of it runs long enough to be tuned. Each
parameter also has map_server's map_saver spelling on the command line
(-f, --occ, --free) or ours (--after-lap); what the command line gives wins.
"""
from wall_follower.params import Parameter as P, Section

TABLE = (
    Section('saving', (
        P('file', 'map', 'where to save: FILE.pgm and FILE.yaml (-f)'),
        P('occupied_threshold', 65, 'a cell this likely occupied or more is saved occupied '
          '[%] (--occ)', 1, 100),
        P('free_threshold', 25, 'a cell this likely occupied or less is saved free, below '
          'occupied_threshold [%] (--free)', 0, 100),
        P('after_lap', False, "wait for record_odom's result, then save the first map stamped "
          'at or after it (--after-lap)'),
    )),
)
"""Every parameter of map_saver; their defaults are map_server's map_saver's."""
