"""The mapping nodes' parameter tables: slam, map_saver, world_map."""
