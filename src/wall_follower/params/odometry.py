"""Parameters shared by the nodes that read odometry: what counts as a jump.

See wall_follower.control.course.odom_check.
"""
from wall_follower.params import Parameter as P, Section

JUMPS = Section('jumps', (
    P('max_speed', 0.5, 'odometry that moves further than this speed allows between two '
      'poses [m/s] ...', 0.01, 10.0),
    P('jump_allowance', 0.1, '... plus this [m] has jumped (a reset, a glitch): it is not '
      'trusted as travel', 0.0, 10.0),
))
