"""Stage's differential-drive motion: one explicit Euler step per world update.

Stage (ModelPosition::Move) moves by the velocity times the interval along
the heading held *before* the step, then turns; it does not integrate the
arc. The reference recordings match this to 1e-15, so the same formula is
used here rather than an exact arc.
"""
import math

__all__ = ['diff_drive_step', 'clamp_velocity', 'normalize_angle']


def normalize_angle(angle):
    """Into [-pi, pi] by whole turns, as Stage's normalize() does."""
    while angle < -math.pi:
        angle += 2.0 * math.pi
    while angle > math.pi:
        angle -= 2.0 * math.pi
    return angle


def diff_drive_step(pose, v, w, dt):
    """Pose (x, y, yaw) after driving at v [m/s], w [rad/s] for dt [s], Stage's way."""
    x, y, yaw = pose
    dx = v * dt
    turn = normalize_angle(w * dt)
    return (x + dx * math.cos(yaw), y + dx * math.sin(yaw), normalize_angle(yaw + turn))


def clamp_velocity(v, w, bounds):
    """(v, w) limited to a position model's velocity_bounds (xmin xmax ... amin amax)."""
    return (min(max(v, bounds[0]), bounds[1]), min(max(w, bounds[6]), bounds[7]))
