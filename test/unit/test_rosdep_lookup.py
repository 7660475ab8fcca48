"""No node starts by asking for `rosdep init` (nodes/shared/rosdep_lookup.py).

Every node's module is imported, as its script does before main(), in one
process with rosdep installed but its database empty, as on a machine
where `rosdep init` and `rosdep update` never ran for the user: ROS_HOME is
a new empty folder, where rosdep reads its database from. rospkg writes
"the rosdep view is empty" once a process, the first time it consults
rosdep, so after the nodes the same process has rospkg parse a catkin
package's manifest: that must say it, showing that rosdep imports, its
view is empty, and nothing had consulted it before.
"""
import os
import subprocess
import sys

import pytest

from wall_follower.nodes.shared import rosdep_lookup

NODES = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, os.pardir, 'src',
                     'wall_follower', 'nodes')
ROSDEP_EMPTY = "the rosdep view is empty"
CONTROL = '== the nodes imported; now rospkg on its own\n'

PROBE = """
import importlib, sys
for name in sys.argv[1:]:
    importlib.import_module(name)
sys.stderr.write(%r)
sys.stderr.flush()
import rospkg
rospkg.RosPack().get_manifest('rospy')
""" % CONTROL


def node_modules():
    """wall_follower.nodes' node modules: every module of its folders but shared/."""
    names = []
    for folder in sorted(os.listdir(NODES)):
        if folder == 'shared' or not os.path.isdir(os.path.join(NODES, folder)):
            continue
        for name in sorted(os.listdir(os.path.join(NODES, folder))):
            if name.endswith('.py') and name != '__init__.py':
                names.append('wall_follower.nodes.%s.%s' % (folder, name[:-3]))
    return names


@pytest.mark.ros
def test_no_node_asks_for_rosdep_init_where_rosdep_is_installed_but_empty(tmp_path):
    import rosdep2.rospack  # noqa: F401 (the condition tested needs rosdep installed)
    modules = node_modules()
    assert len(modules) > 10, modules
    run = subprocess.run([sys.executable, '-c', PROBE] + modules,
                         env=dict(os.environ, ROS_HOME=str(tmp_path)), stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, universal_newlines=True, timeout=300)
    assert run.returncode == 0, run.stderr
    nodes, _, control = run.stderr.partition(CONTROL)
    assert ROSDEP_EMPTY not in nodes, run.stderr
    assert ROSDEP_EMPTY in control, (
        'rospkg on its own did not ask for rosdep init, so the condition is not the one '
        'tested:\n' + run.stderr)


def test_rosdep_is_put_back_as_it_was(monkeypatch):
    kept = object()
    monkeypatch.setitem(sys.modules, rosdep_lookup.ROSDEP_SORTING, kept)
    rosdep_lookup.import_dynamic_reconfigure()
    assert sys.modules[rosdep_lookup.ROSDEP_SORTING] is kept
    monkeypatch.delitem(sys.modules, rosdep_lookup.ROSDEP_SORTING)
    rosdep_lookup.import_dynamic_reconfigure()
    assert rosdep_lookup.ROSDEP_SORTING not in sys.modules
