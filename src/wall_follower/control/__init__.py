"""The robot's behaviours: scan reading, walls, the follower and its manoeuvres, the finder, the lap."""
