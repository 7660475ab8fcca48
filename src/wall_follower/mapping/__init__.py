"""Mapping a room: a log-odds occupancy grid built at poses found by scan matching."""
