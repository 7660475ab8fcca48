"""The lab exercises' parameter tables."""
