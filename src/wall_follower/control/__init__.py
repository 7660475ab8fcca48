"""The robot's behaviours, by job: sensing/ (what a scan says: reading and checking it,
lines and walls), following/ (the wall follower and its manoeuvres), course/ (the finder
and the lap). Beside them what every driving node takes: the command and its clamp
(motion.py) and the check of an input's stamp (stamps.py)."""
