"""The robot's behaviours: scan reading and checking, walls, the follower and its
manoeuvres, the finder, the lap."""
