"""ROS wiring of the package's nodes; each module has a main() for scripts/."""
