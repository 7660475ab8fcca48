"""The built-in Stage-compatible simulator's node."""
