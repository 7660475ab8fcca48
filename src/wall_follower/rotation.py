"""Angles and rotations, one way for the whole package.

Every part that wraps an angle, turns a yaw into a quaternion or back, or
builds a rotation matrix takes it from here, so that two parts never
disagree on a convention: angles in radians (REP 103), quaternions as
(x, y, z, w), a heading's wrap into [-pi, pi). The one exception is the
simulator's own step (sim.kinematics.normalize_angle), which copies
Stage's loop bit for bit, as its recordings are matched to 1e-15.
"""
import math

import numpy as np

__all__ = ['wrap_angle', 'yaw_of_quaternion', 'quaternion_of_yaw', 'matrix_of_quaternion',
           'axis_angle_matrix', 'rpy_matrix']


def wrap_angle(angle):
    """An angle, or a numpy array of them, wrapped into [-pi, pi)."""
    wrapped = (np.asarray(angle, dtype=float) + math.pi) % (2.0 * math.pi) - math.pi
    return float(wrapped) if wrapped.ndim == 0 else wrapped


def yaw_of_quaternion(x, y, z, w):
    """The yaw (rad, about z) of the unit quaternion (x, y, z, w)."""
    return math.atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z))


def quaternion_of_yaw(yaw):
    """(z, w) of the unit quaternion of a rotation by yaw (rad) about the z axis."""
    return math.sin(yaw / 2.0), math.cos(yaw / 2.0)


def matrix_of_quaternion(quaternion):
    """The 3x3 rotation matrix of a quaternion (x, y, z, w), normalised first."""
    x, y, z, w = np.asarray(quaternion, float) / np.linalg.norm(quaternion)
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def axis_angle_matrix(axis, angle):
    """The 3x3 rotation matrix of a turn by angle (rad) about a unit axis (Rodrigues)."""
    x, y, z = axis
    c, s = math.cos(angle), math.sin(angle)
    t = 1.0 - c
    return np.array([[t * x * x + c, t * x * y - s * z, t * x * z + s * y],
                     [t * x * y + s * z, t * y * y + c, t * y * z - s * x],
                     [t * x * z - s * y, t * y * z + s * x, t * z * z + c]])


def rpy_matrix(roll, pitch, yaw):
    """The 3x3 rotation matrix of fixed-axis roll, pitch and yaw (rad), as URDF's rpy."""
    cr, sr = math.cos(roll), math.sin(roll)
    cp, sp = math.cos(pitch), math.sin(pitch)
    cy, sy = math.cos(yaw), math.sin(yaw)
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])
