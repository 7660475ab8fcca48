"""Real Stage's odometry, as recorded by tools/record_stage_odometry.py.

The recording (test/data/stage_reference/stage_odometry.json) keeps, per
world update and per robot, the /odom pose and twist and the ground-truth
pose, as rows of the fields below. Stage's localization "odom" turns each
update's odometry by w*dt*(1 + ea) and then advances it by v*dt*(1 + ex)
along the new heading, so every update's step gives the scale errors back:
that is how a run without odom_error shows the errors Stage drew for it.
"""
import math

import numpy as np

from wall_follower.rotation import wrap_angle

__all__ = ['ODOM_FIELDS', 'GROUND_TRUTH_FIELDS', 'step_scale_errors']

ODOM_FIELDS = ('x', 'y', 'yaw', 'vx', 'vy', 'wz')
GROUND_TRUTH_FIELDS = ('x', 'y', 'yaw')


def step_scale_errors(odom, dt):
    """(ex, ea): each update's scale errors, from one robot's odometry rows.

    ex holds one value per update that advanced (vx != 0): the step's length
    along the heading reached after that update's turn, over vx*dt, minus 1;
    ea one per update that turned (wz != 0): the turn over wz*dt, minus 1.
    A row's twist is the velocity of the update that led to its pose.
    """
    rows = np.asarray(odom, dtype=float)
    ex, ea = [], []
    for before, after in zip(rows[:-1], rows[1:]):
        x, y, yaw, vx, _, wz = after
        if vx != 0.0:
            along = (x - before[0]) * math.cos(yaw) + (y - before[1]) * math.sin(yaw)
            ex.append(along / (vx * dt) - 1.0)
        if wz != 0.0:
            turn = wrap_angle(yaw - before[2])
            ea.append(turn / (wz * dt) - 1.0)
    return np.array(ex), np.array(ea)
