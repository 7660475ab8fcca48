"""dynamic_reconfigure imported without rospkg's rosdep lookup: no node asks for `rosdep init`.

Every node serves its parameters through dynamic_reconfigure, whose Python
modules (encoding, which the generated wall_follower.cfg modules import
first; server; client) each begin with rosbuild's
`roslib.load_manifest('dynamic_reconfigure')`. For a catkin package roslib
adds nothing to sys.path, but it has rospkg parse the package.xml first,
and rospkg, wherever rosdep2 imports, sorts the package's dependencies into
ROS packages and system ones by rosdep's database. On a machine with
rosdep installed (Debian's catkin-lint recommends it) but that database
never filled for the user (`rosdep init`, `rosdep update`), rospkg then
writes "the rosdep view is empty: call 'sudo rosdep init' and 'rosdep
update'" to stderr, once a process: at the start of every node, in
run-main's output and in each grade case's log. No node reads that
sorting (roslib drops a catkin package's manifest as soon as it sees it is
one), and no ROS environment variable turns it off.

So importing wall_follower.nodes imports dynamic_reconfigure first, here,
with `rosdep2.rospack` (the module rospkg imports for the sorting, rospkg
1.4 to 1.6: Debian 12's and Noetic's) set to None in sys.modules for that
import only. Python's import system then raises ImportError for it (what
None in sys.modules means), and rospkg takes its own way for a machine
without rosdep: it catches that ImportError and leaves the dependencies
unsorted. roslib keeps dynamic_reconfigure as loaded, so the imports of it
the node makes later ask nothing again. rosdep itself stays importable for
the rest of the process; where its database is filled, the lookup skipped
here is only time (rosdep2 takes about 0.2 s to import).
"""
import sys

ROSDEP_SORTING = 'rosdep2.rospack'
_ABSENT = object()


def import_dynamic_reconfigure():
    """Import dynamic_reconfigure.encoding with rosdep2.rospack out of reach, then put it back.

    Where dynamic_reconfigure does not import (a Python without ROS, as the
    unit tests under Python 3.8 have), nothing is done: a node's own import
    of it fails again, with the error in full.
    """
    saved = sys.modules.get(ROSDEP_SORTING, _ABSENT)
    sys.modules[ROSDEP_SORTING] = None
    try:
        import dynamic_reconfigure.encoding  # noqa: F401
    except ImportError:
        pass
    finally:
        if saved is _ABSENT:
            sys.modules.pop(ROSDEP_SORTING, None)
        else:
            sys.modules[ROSDEP_SORTING] = saved
