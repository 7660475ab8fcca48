"""Parameters of the range_ahead node."""
import math

from wall_follower.params import Parameter as P, Section

TABLE = (
    Section('range_ahead', (
        P('half_width', math.radians(5.0), 'the window either side of straight ahead whose '
          'valid readings\' median is the answer [rad]', 0.0, math.pi),
        P('period', 0.5, 'print at most once per this many seconds; 0: every scan [s]',
          0.0, 60.0),
        P('scan_timeout', 1.0, 'say so when no usable scan has come for this long [s]',
          0.05, 10.0),
    )),
)
"""Every parameter of range_ahead (wall_follower.nodes.exercises.range_ahead)."""
