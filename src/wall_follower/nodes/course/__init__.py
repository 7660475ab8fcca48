"""The course's nodes: the wall follower, find_wall and record_odom."""
