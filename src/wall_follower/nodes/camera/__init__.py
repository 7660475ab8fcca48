"""The camera's nodes: the line follower, the lab's mask and the camera view."""
