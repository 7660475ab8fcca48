"""The course's nodes' parameter tables: wall_finder, wall_following, odom_recorder."""
