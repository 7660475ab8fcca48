"""The wall follower and its manoeuvres: following, corners, left turns, the search, the body's swing."""
