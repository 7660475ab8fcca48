"""The wall follower and its manoeuvres: following, corners, left turns, the search, and
the body's swing on a turn."""
