"""ROS wiring of the package's nodes; each module has a main() for scripts/.

Importing it makes the process answer SIGINT and SIGTERM from now on, even
if they came in ignored (see signals): scripts import a node's module
before anything else. It then imports dynamic_reconfigure, which every
node serves its parameters through, without rospkg's rosdep lookup (see
rosdep_lookup): a node never starts by asking for `rosdep init`.
"""
from wall_follower.nodes.shared import rosdep_lookup, signals

signals.catch()
rosdep_lookup.import_dynamic_reconfigure()
