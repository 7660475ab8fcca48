"""wall_follower: right-hand wall following for a TurtleBot3 (ROS 1 Noetic).

Pure logic lives in the modules of this package and imports no ROS; the
ROS wiring of each node lives in wall_follower.nodes and is started by the
thin entry points in scripts/.
"""
