"""What the laser says: scans read and checked, lines and walls fitted to them, and the
follower's observation of them."""
