"""The lab sheets' warm-up exercises as plain logic: scan or pose in, command out.

One module per exercise, free of ROS so that unit tests drive them with no
master; their nodes (wall_follower.nodes) wire them to ROS through the same
scan reader, validator, clamp and DriveLoop as the course nodes.
"""
