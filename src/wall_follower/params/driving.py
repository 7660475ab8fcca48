"""The parameters of every node that drives: its DriveLoop's and its clamp's, declared once.

Each driving node's table (wall_following, wall_finder and the exercises)
takes these two Sections rather than declaring the same names again;
nodes/shared/drive_loop.py builds and retunes the loop and the clamp from them.
"""
import math
from collections import namedtuple

from wall_follower.params import Parameter as P, Section

# The course's real TurtleBot3 kills a node that commands more than these
# (m/s, rad/s): the defaults and the ceilings of the limits below, and of
# control.motion.clamp.
MAX_LINEAR = 0.19
MAX_ANGULAR = 0.49

AHEAD_MIN_KNOWN = 0.1
"""The default of ahead_min_known: one beam in ten of the sector ahead (a one-beam view of
the way ahead is not enough; a scan that is mostly dropouts or beyond reach there still is)."""

STALE_SCAN_STOPS = 'stop the robot while the newest scan is older than this [s]'
"""What scan_timeout means to a node that drives for as long as it runs."""


AHEAD_HALF_WIDTH = 0.5236
"""The default of ahead_half_width: 30 degrees either side of straight ahead."""

RATE = P('rate', 20.0, 'how often the loop looks at the clock while it waits for input [Hz]; '
         'each new scan or frame is answered at once', 1.0, 100.0)
KEEPALIVE = P('keepalive', 0.15, 'no new scan or frame for this long: send the last command '
              'again, so that a velocity watchdog does not stop the robot mid-turn [s]',
              0.01, 1.0)


LoopInput = namedtuple('LoopInput', ['timeout', 'min_known'])
"""The names of the parameters that set a DriveLoop for one kind of input: its timeout, and
the share of beams ahead that must be valid to drive forward (None: the node's controller
says what it knows ahead)."""

LASER_INPUT = LoopInput('scan_timeout', 'ahead_min_known')
CAMERA_INPUT = LoopInput('image_timeout', None)


AHEAD = Section('view_ahead', (
    P('ahead_half_width', AHEAD_HALF_WIDTH, 'never drive forward (backward) while too few beams '
      'within this angle either side of straight ahead (behind) read a hit or a proven '
      'no-return [rad]', 0.0, math.pi),
    P(LASER_INPUT.min_known, AHEAD_MIN_KNOWN, 'share of the beams within ~ahead_half_width that '
      'must read a hit or a proven no-return for the robot to drive that way (0: one beam will '
      'do); low enough for an LDS-01 that drops beams or sees nothing beyond its reach there',
      0.0, 1.0),
))
"""How much of the way a laser must show for the robot to drive into it: the drive loop's rule
(nodes/shared/drive_loop.py), which a behaviour that checks its own way (WallFinder's slide)
takes as its table's section, so that the two never disagree."""


def loop(scan_timeout, scan_timeout_meaning=STALE_SCAN_STOPS, blind_turn=None, ahead=True):
    """The Section of the DriveLoop's parameters (nodes/shared/drive_loop.py) of a node that reads
    the laser.

    scan_timeout: its default [s], which differs between nodes, and
    scan_timeout_meaning what the node does when a scan is that old. blind_turn: the default
    of ~blind_turn [rad/s, positive left], for a node that knows which way to turn to bring
    the way ahead into view (a wall follower: toward its wall); None declares no such
    parameter, and the node turns as its command says. ahead: include the AHEAD section's
    parameters; False for a node whose behaviour's table declares them.
    """
    blind = () if blind_turn is None else (
        P('blind_turn', blind_turn, 'while too few beams ahead read valid to drive forward '
          '(a room deeper than the laser reaches), turn in place at this rate to bring the way '
          'ahead into view (a command turning faster turns at its own, unless such a turn is '
          'already under way), and stop if half a turn has not [rad/s, positive left]; 0: '
          "keep the command's own turn",
          -MAX_ANGULAR, MAX_ANGULAR),)
    return Section('drive_loop', (
        RATE, KEEPALIVE,
        P(LASER_INPUT.timeout, scan_timeout, scan_timeout_meaning, 0.05, 10.0),
    ) + (AHEAD.parameters if ahead else ()) + blind)


def camera_loop(image_timeout):
    """The Section of the DriveLoop's parameters of a node that drives by what its camera sees
    (line_follower): its input's timeout is image_timeout [s] (the default), and what is known
    ahead is the node's own to say, not a share of laser beams."""
    return Section('drive_loop', (
        RATE, KEEPALIVE,
        P(CAMERA_INPUT.timeout, image_timeout, 'stop the robot while the newest image is older '
          'than this [s]', 0.05, 10.0),
        P('ahead_half_width', AHEAD_HALF_WIDTH, 'never drive forward while nothing to follow is '
          'known within this angle either side of straight ahead [rad]', 0.0, math.pi),
    ))


LIMITS = Section('limits', (
    P('max_linear', MAX_LINEAR, 'clamp on every forward speed sent, and the speed limit of the '
      'behaviour [m/s] (the real robot kills a node above the default)', 0.0, MAX_LINEAR),
    P('max_angular', MAX_ANGULAR, 'clamp on every turn rate sent, and the turn rate limit of '
      'the behaviour [rad/s] (the same)', 0.0, MAX_ANGULAR),
))
"""The clamp on every command (nodes/shared/velocity.VelocityCommander), which behaviours that plan
their own speeds (WallFinder, SquareDriver) also take as their limits."""
