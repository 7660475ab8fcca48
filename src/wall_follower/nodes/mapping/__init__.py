"""Mapping's nodes: the mapper, the map saver and a world's map."""
