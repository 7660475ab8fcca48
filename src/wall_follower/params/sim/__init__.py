"""The simulator's parameter table."""
