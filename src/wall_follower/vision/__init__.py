"""Seeing the line: finding it in a camera image, putting it on the floor, following it."""
