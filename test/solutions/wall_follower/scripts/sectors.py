"""The laser's readings by angle, whatever its beam count and first beam."""
import math


def readings(scan, low, high):
    """(angle, range) of each usable beam between low and high (rad; 0 ahead, left +)."""
    found = []
    for index, distance in enumerate(scan.ranges):
        angle = math.remainder(scan.angle_min + index * scan.angle_increment, 2.0 * math.pi)
        if low <= angle <= high and scan.range_min <= distance <= scan.range_max:
            found.append((angle, distance))
    return found


def nearest(scan, low=-math.pi, high=math.pi):
    """(angle, range) of the nearest reading between low and high; (None, inf) if none."""
    found = readings(scan, low, high)
    return min(found, key=lambda item: item[1]) if found else (None, float('inf'))


def clamp(value, limit):
    return max(-limit, min(limit, value))
