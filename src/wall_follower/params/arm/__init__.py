"""The arm's nodes' parameter tables: arm_controller, move_arm, arm_plot."""
