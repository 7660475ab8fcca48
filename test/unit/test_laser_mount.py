"""laser_mount: laser_x from tf, and the Burger's value with a warning when tf has none."""
import math

import pytest
from geometry_msgs.msg import TransformStamped

from wall_follower.nodes.shared.laser_mount import BURGER_LASER_X, Mount, choose_laser_x, mount_of


def transform(x, y=0.0, yaw=0.0):
    t = TransformStamped()
    t.transform.translation.x, t.transform.translation.y = x, y
    t.transform.rotation.z, t.transform.rotation.w = math.sin(yaw / 2), math.cos(yaw / 2)
    return t


def test_a_waffle_mount_gives_its_laser_x_and_no_warning():
    assert choose_laser_x(Mount(-0.064, 0.0, 0.0), 'base_scan') == (-0.064, None)


def test_no_transform_falls_back_to_the_burger_and_says_why():
    value, warning = choose_laser_x(None, 'base_scan', 'base_link', 5.0)
    assert value == BURGER_LASER_X == -0.032
    assert 'no transform base_link -> base_scan within 5 s' in warning
    assert 'Burger' in warning and '~laser_x' in warning


@pytest.mark.parametrize('frame, why', [(None, 'no scan came'),
                                        ('', 'the scan has no frame_id')])
def test_no_scan_or_no_frame_falls_back_to_the_burger(frame, why):
    value, warning = choose_laser_x(None, frame)
    assert value == BURGER_LASER_X
    assert warning.startswith(why)


def test_a_turned_laser_is_used_but_warned_about():
    value, warning = choose_laser_x(Mount(-0.05, 0.0, math.pi), 'base_scan')
    assert value == -0.05
    assert 'turned 180 deg' in warning


def test_mount_of_reads_translation_and_yaw():
    assert mount_of(transform(-0.064, 0.01, 0.5)) == pytest.approx((-0.064, 0.01, 0.5))
    assert mount_of(None) is None
