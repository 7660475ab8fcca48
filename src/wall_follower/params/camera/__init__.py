"""The camera nodes' parameter tables: line_follower, line_mask, camera_view."""
