"""Which simulator `simulation.launch simulator:=... gui:=...` runs.

Real stageros paces its world only in its GUI: headless (`stageros -g`) it
runs as fast as the CPU allows, hundreds of times faster than real time, and
the Python controllers fall so far behind that the course cannot run. So:

- builtin: this package's simulator, whatever gui says (it has no window:
  rviz:=true shows the robot);
- auto (the default): real stageros when stage_ros is installed and
  gui:=true; the built-in simulator otherwise;
- stage: real stageros with gui:=true; refused without stage_ros, and
  refused headless, since it could not be paced (run its GUI under
  `xvfb-run -a` on a machine without a display).

No combination runs a simulator that cannot run the course.
"""
from collections import namedtuple

SIMULATORS = ('builtin', 'stage', 'auto')

BUILTIN = 'builtin'
STAGE = 'stage'

Choice = namedtuple('Choice', 'simulator error note')
Choice.__doc__ = """simulator: 'builtin', 'stage' or None (refused, error says why);
note: a line worth logging about the choice, or ''."""

HEADLESS_STAGE = ('real stageros cannot be paced headless (stageros -g runs as fast as the CPU '
                  'allows and the controllers fall behind)')


def choose_simulator(requested, gui, stage_ros_installed):
    """The simulator to run for simulator:=requested gui:=gui (see the module's rule)."""
    if requested not in SIMULATORS:
        return Choice(None, 'unknown simulator %r: one of %s' % (requested, ', '.join(SIMULATORS)),
                      '')
    if requested == BUILTIN:
        return Choice(BUILTIN, '', 'the built-in simulator has no window; use rviz:=true'
                      if gui else '')
    if requested == STAGE:
        if not stage_ros_installed:
            return Choice(None, 'simulator:=stage needs stageros (package stage_ros), which is '
                          'not installed; simulator:=builtin runs the built-in one', '')
        if not gui:
            return Choice(None, 'simulator:=stage needs gui:=true: %s; use gui:=true '
                          '(under xvfb-run -a without a display) or simulator:=builtin'
                          % HEADLESS_STAGE, '')
        return Choice(STAGE, '', '')
    if stage_ros_installed and gui:
        return Choice(STAGE, '', 'stage_ros is installed and gui:=true: running real stageros')
    if stage_ros_installed:
        return Choice(BUILTIN, '', 'stage_ros is installed, but %s: running the built-in '
                      'simulator (gui:=true runs real Stage)' % HEADLESS_STAGE)
    return Choice(BUILTIN, '', '')
