"""Floor projection against camera geometry worked out by hand, for any size, fov, height, tilt."""
import math

import numpy as np
import pytest

from wall_follower.vision.floor import (
    OPTICAL, STAGEROS, FloorProjection, Intrinsics, camera_pose, convention_of,
    level_camera_axes)


def stage_intrinsics(width, height, hfov_deg, vfov_deg):
    """camera_info as stageros computes it: f = size / (2 tan(fov / 2)), centre = size / 2."""
    fx = width / (2.0 * math.tan(math.radians(hfov_deg) / 2.0))
    fy = height / (2.0 * math.tan(math.radians(vfov_deg) / 2.0))
    k = [fx, 0.0, width / 2.0, 0.0, fy, height / 2.0, 0.0, 0.0, 1.0]
    return Intrinsics.from_camera_info(k, width, height)


def quaternion_rpy(roll, pitch, yaw):
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return (sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy)


@pytest.mark.parametrize('width,height,hfov,vfov,z,tilt', [
    (320, 240, 62.2, 48.8, 0.25, 30.0),
    (640, 480, 62.2, 48.8, 0.40, 45.0),
    (160, 90, 90.0, 60.0, 0.15, 20.0),
])
def test_image_centre_lands_where_the_optical_axis_meets_the_floor(width, height, hfov, vfov, z,
                                                                   tilt):
    projection = FloorProjection(stage_intrinsics(width, height, hfov, vfov),
                                 level_camera_axes(math.radians(tilt)), (0.0, 0.0, z), 5.0)
    point = projection.to_floor([(width / 2.0, height / 2.0)])
    assert point.shape == (1, 2)
    assert point[0] == pytest.approx((z / math.tan(math.radians(tilt)), 0.0), abs=1e-9)


def test_bottom_row_and_side_column_follow_the_field_of_view():
    z, tilt, hfov, vfov = 0.3, math.radians(35.0), 62.2, 48.8
    projection = FloorProjection(stage_intrinsics(320, 240, hfov, vfov),
                                 level_camera_axes(tilt), (0.0, 0.0, z), 5.0)
    # The bottom edge of the image looks down by tilt + vfov / 2.
    bottom = projection.to_floor([(160.0, 240.0)])[0]
    assert bottom[0] == pytest.approx(z / math.tan(tilt + math.radians(vfov) / 2.0), abs=1e-9)
    # The right edge of the middle row: at hfov / 2 right of the axis, on the axis' slant range.
    right = projection.to_floor([(320.0, 120.0)])[0]
    slant = z / math.sin(tilt)
    assert right[1] == pytest.approx(-slant * math.tan(math.radians(hfov) / 2.0), abs=1e-9)
    assert right[0] == pytest.approx(z / math.tan(tilt), abs=1e-9)


def test_pixels_above_the_horizon_or_too_far_are_left_out():
    projection = FloorProjection(stage_intrinsics(320, 240, 62.2, 48.8),
                                 level_camera_axes(math.radians(10.0)), (0.0, 0.0, 0.3), 1.0)
    assert len(projection.to_floor([(160.0, 0.0)])) == 0       # above the horizon
    assert len(projection.to_floor([(160.0, 120.0)])) == 0     # 1.7 m away
    assert len(projection.to_floor([(160.0, 239.0)])) == 1


def test_floor_to_pixels_inverts_pixels_to_floor():
    projection = FloorProjection(stage_intrinsics(640, 480, 70.0, 50.0),
                                 level_camera_axes(math.radians(40.0)), (0.05, 0.01, 0.35), 5.0)
    pixels = np.array([(10.0, 300.0), (320.0, 240.0), (600.0, 470.0)])
    back, ahead = projection.to_pixels(projection.to_floor(pixels))
    assert ahead.all()
    assert back == pytest.approx(pixels, abs=1e-6)
    assert list(projection.sees(projection.to_floor(pixels), 2.0)) == [True, True, True]
    assert not projection.sees(np.array([(-1.0, 0.0)]), 2.0)[0]


def test_stageros_tf_gives_height_and_tilt_whatever_its_yaw():
    tilt = math.radians(30.0)
    # stageros: roll = (90 deg - tilt) - 180 deg; its yaw mixes in the robot's heading.
    for yaw in (0.0, 1.0, -2.5):
        axes, centre = camera_pose((0.1, 0.0, 0.28), quaternion_rpy(-math.pi / 2 - tilt, 0.0, yaw),
                                   STAGEROS)
        assert axes == pytest.approx(level_camera_axes(tilt), abs=1e-9)
        assert centre == pytest.approx((0.0, 0.0, 0.28))


def test_optical_tf_is_taken_as_it_is():
    # An optical frame tilted down by 30 deg: z ahead and down, x right, y down and back.
    tilt = math.radians(30.0)
    axes = level_camera_axes(tilt)
    w = math.sqrt(1.0 + np.trace(axes)) / 2.0
    quaternion = ((axes[2, 1] - axes[1, 2]) / (4 * w), (axes[0, 2] - axes[2, 0]) / (4 * w),
                  (axes[1, 0] - axes[0, 1]) / (4 * w), w)
    got, centre = camera_pose((0.07, -0.02, 0.2), quaternion, OPTICAL)
    assert got == pytest.approx(axes, abs=1e-9)
    assert centre == pytest.approx((0.07, -0.02, 0.2))


def test_frame_convention_from_its_name():
    assert convention_of('camera_rgb_optical_frame', 'auto') == OPTICAL
    assert convention_of('camera', 'auto') == STAGEROS
    assert convention_of('camera', OPTICAL) == OPTICAL


@pytest.mark.parametrize('k,size', [
    ([0.0, 0, 160, 0, 200, 120, 0, 0, 1], (320, 240)),
    ([200.0, 0, 160, 0, 200, 120, 0, 0], (320, 240)),
    ([200.0, 0, 160, 0, 200, 120, 0, 0, 1], (0, 240)),
    ([float('nan'), 0, 160, 0, 200, 120, 0, 0, 1], (320, 240)),
])
def test_unusable_camera_info_is_refused(k, size):
    with pytest.raises(ValueError):
        Intrinsics.from_camera_info(k, *size)


def test_a_camera_below_the_floor_is_refused():
    with pytest.raises(ValueError):
        FloorProjection(stage_intrinsics(320, 240, 60, 45), level_camera_axes(0.5),
                        (0.0, 0.0, 0.0), 2.0)
