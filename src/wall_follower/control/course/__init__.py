"""The course's other behaviours: finding the wall (find_wall) and recording the lap
(record_odom)."""
