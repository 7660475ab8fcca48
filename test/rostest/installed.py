"""Whether an optional ROS package (real Stage, gmapping) is installed, for the checks
that run only where it is, and the stand-in that says such a check was NOT RUN."""
import unittest

from wall_follower.evaluation.launching import display_wrapper, package_installed


def real_stage_suite(name, suite):
    """suite (a TestCase class) where real Stage can run here; else one whose single test
    passes and says, on stdout and in its name, that check `name` was NOT RUN, and why."""
    if not package_installed('stage_ros'):
        why = 'stage_ros_not_installed'
        text = 'stage_ros is not installed (tools/build-real-stage builds it)'
    elif display_wrapper() is None:
        why = 'no_display_and_no_xvfb_run'
        text = 'Stage needs a display: no DISPLAY and no xvfb-run'
    else:
        return suite

    def not_run(_self):
        print('%s: NOT RUN: %s' % (name, text))
    return type('NotRun', (unittest.TestCase,),
                {'test_%s_not_run__%s' % (name, why): not_run})
