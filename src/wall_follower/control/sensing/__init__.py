"""What the laser says: scans read and checked, lines and walls fitted to them, the follower's observation."""
