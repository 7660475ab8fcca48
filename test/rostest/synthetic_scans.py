"""Synthetic LaserScan messages for the rostests that feed a node scans themselves."""
import math

import numpy as np
from sensor_msgs.msg import LaserScan


def wall_on_the_right(distance=0.25, beams=360):
    """A Stage-convention scan (angle_min -pi) of a straight wall on the right."""
    scan = LaserScan()
    scan.header.frame_id = 'base_laser_link'
    scan.angle_min, scan.angle_max = -math.pi, math.pi
    scan.angle_increment = 2.0 * math.pi / (beams - 1)
    scan.range_min, scan.range_max = 0.12, 3.5
    angles = scan.angle_min + scan.angle_increment * np.arange(beams)
    with np.errstate(divide='ignore'):
        ranges = np.where(np.sin(angles) < -1e-3, -distance / np.sin(angles), np.inf)
    scan.ranges = np.minimum(ranges, scan.range_max).tolist()
    return scan


def square_room(distance=1.2):
    """An LDS-01-convention scan (360 beams, beam 0 ahead) of a square room whose walls
    stand `distance` m from the robot on every side."""
    scan = LaserScan()
    scan.header.frame_id = 'base_scan'
    scan.angle_min, scan.angle_increment = 0.0, 2.0 * math.pi / 360
    scan.angle_max = scan.angle_increment * 359
    scan.range_min, scan.range_max = 0.12, 3.5
    scan.ranges = [distance / max(abs(math.cos(a)), abs(math.sin(a)))
                   for a in (scan.angle_increment * i for i in range(360))]
    return scan


def spoiled(scan, **fields):
    """A copy of scan with some fields replaced."""
    copy = LaserScan()
    for name in LaserScan.__slots__:
        setattr(copy, name, getattr(scan, name))
    copy.ranges = list(scan.ranges)
    for name, value in fields.items():
        setattr(copy, name, value)
    return copy


def one_valid_beam(ranges=None):
    """An LDS-01-convention scan (360 beams, beam 0 ahead) whose only valid reading is
    3.0 m at 29 deg left, the others NaN or, given, ranges (a list of 360)."""
    scan = LaserScan()
    scan.header.frame_id = 'base_scan'
    scan.angle_min, scan.angle_increment = 0.0, 2.0 * math.pi / 360
    scan.angle_max = scan.angle_increment * 359
    scan.range_min, scan.range_max = 0.12, 3.5
    scan.ranges = list(ranges) if ranges is not None else [math.nan] * 360
    scan.ranges[29] = 3.0
    return scan


def unusable_scans():
    """name -> a scan that no node may drive on, one for each way a laser fails."""
    good = wall_on_the_right()
    count = len(good.ranges)
    blind_ahead = list(good.ranges)
    for index in range(count):
        angle = good.angle_min + good.angle_increment * index
        if abs(angle) <= math.radians(35.0):
            blind_ahead[index] = 0.0
    one_ahead = list(blind_ahead)
    one_ahead[min(range(count), key=lambda index: abs(
        good.angle_min + good.angle_increment * index - math.radians(29.0)))] = 3.0
    return {
        'all NaN': spoiled(good, ranges=[math.nan] * count),
        'all 0.0': spoiled(good, ranges=[0.0] * count),
        'empty': spoiled(good, ranges=[]),
        'one beam': spoiled(good, ranges=[1.0]),
        'zero increment': spoiled(good, angle_increment=0.0),
        'negative ranges': spoiled(good, ranges=[-1.0] * count),
        'range_max below range_min': spoiled(good, range_min=3.5, range_max=0.12),
        'ranges not matching the angles': spoiled(good, ranges=good.ranges[::2]),
        'nothing valid ahead': spoiled(good, ranges=blind_ahead),
        'one valid beam': one_valid_beam(),
        'one valid beam ahead': spoiled(good, ranges=one_ahead),
    }
