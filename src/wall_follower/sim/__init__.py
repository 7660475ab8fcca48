"""The Stage-compatible simulator's logic: world files, occupancy grid, raytracing,
kinematics and the world step, all free of ROS so that they can be tested alone.
"""
