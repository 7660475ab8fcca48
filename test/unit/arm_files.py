"""The package's own cougarbot files, read as the nodes read them (for the arm's tests)."""
import os

import yaml

from wall_follower.arm.model import (read_acceleration_limits, read_srdf, read_urdf,
                                     read_velocity_limits)

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')


def text(*path):
    with open(os.path.join(ROOT, *path)) as stream:
        return stream.read()


def model():
    return read_urdf(text('urdf', 'cougarbot.urdf'))


def semantics(arm):
    return read_srdf(text('config', 'cougarbot.srdf'), arm)


def limits(arm):
    """(velocity, acceleration) limits of config/joint_limits.yaml."""
    values = yaml.safe_load(text('config', 'joint_limits.yaml'))
    return read_velocity_limits(values, arm), read_acceleration_limits(values, arm)
