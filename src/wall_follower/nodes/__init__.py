"""ROS wiring of the package's nodes; each module has a main() for scripts/.

Importing it makes the process answer SIGINT and SIGTERM from now on, even
if they came in ignored (see signals): scripts import a node's module
before anything else.
"""
from wall_follower.nodes.shared import signals

signals.catch()
