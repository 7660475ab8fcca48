"""The arm's nodes: the trajectory controller, the move_arm action and the joint plot."""
