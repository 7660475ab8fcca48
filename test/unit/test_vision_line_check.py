"""A line is a line: line colour is acted on only where it looks like the course's line on the
floor (vision.line_check), whatever the camera; yellow floors, noise and patches are not."""
import math

import numpy as np
import pytest

from line_course import WHITE, YELLOW, PaintedFloor, camera, segment
from wall_follower.vision.floor import FloorProjection, Intrinsics, level_camera_axes
from wall_follower.vision.line_check import EMPTY, LINE, NOT_A_LINE, LineCheck
from wall_follower.vision.line_image import HsvBounds, line_mask

BOUNDS = HsvBounds((20, 100, 100), (40, 255, 255))
CAMERAS = {
    'waffle_pi': dict(),
    'wide_low': dict(height=0.18, tilt_deg=30.0, width=160, image_height=120),
    'high_large': dict(height=0.4, tilt_deg=55.0, width=640, image_height=480, hfov=75.0,
                       vfov=55.0),
}


def judged(image, projection):
    return LineCheck(0.045, 2.0).judge(line_mask(image, BOUNDS), projection)


def frame_of(centreline, projection, width=0.045, base=(0.0, 0.0, 0.0)):
    return PaintedFloor(centreline, width).frame(projection, base)


@pytest.mark.parametrize('name', sorted(CAMERAS))
@pytest.mark.parametrize('line', [
    segment((0.0, 0.0), (2.0, 0.0)),                            # straight ahead
    segment((0.3, -1.0), (0.5, 1.0)),                           # across the view
    segment((0.0, 0.15), (1.5, -0.4)),                          # oblique, out at a side
])
def test_a_line_is_a_line_with_any_camera(name, line):
    projection = camera(**CAMERAS[name])
    image = frame_of(line, projection)
    verdict = judged(image, projection)
    assert verdict.kind == LINE, verdict
    # All of it is acted on.
    assert np.count_nonzero(verdict.mask) >= 0.95 * np.count_nonzero(line_mask(image, BOUNDS))


@pytest.mark.parametrize('name', sorted(CAMERAS))
def test_a_line_of_another_width_passes_within_its_tolerance(name):
    projection = camera(**CAMERAS[name])
    line = segment((0.0, 0.0), (2.0, 0.2))
    assert judged(frame_of(line, projection, width=0.03), projection).kind == LINE
    assert judged(frame_of(line, projection, width=0.07), projection).kind == LINE


def test_clear_floor_is_empty():
    projection = camera()
    image = np.full((240, 320, 3), WHITE, np.uint8)
    assert judged(image, projection).kind == EMPTY


@pytest.mark.parametrize('name', sorted(CAMERAS))
def test_an_all_yellow_frame_is_no_line(name):
    projection = camera(**CAMERAS[name])
    k = projection.intrinsics
    verdict = judged(np.full((k.height, k.width, 3), YELLOW, np.uint8), projection)
    assert verdict.kind == NOT_A_LINE and not verdict.mask.any()
    assert 'covers more of the floor' in verdict.problem


@pytest.mark.parametrize('name', sorted(CAMERAS))
@pytest.mark.parametrize('seed', [1, 2])
def test_noise_is_no_line(name, seed):
    projection = camera(**CAMERAS[name])
    k = projection.intrinsics
    noise = np.random.RandomState(seed).randint(0, 256, (k.height, k.width, 3)).astype(np.uint8)
    verdict = judged(noise, projection)
    assert verdict.kind == NOT_A_LINE and 'scattered' in verdict.problem


@pytest.mark.parametrize('density', [0.05, 0.2, 0.35, 0.5, 0.7, 0.9])
def test_yellow_specks_of_any_density_are_no_line(density):
    projection = camera()
    image = np.full((240, 320, 3), WHITE, np.uint8)
    image[np.random.RandomState(3).random_sample((240, 320)) < density] = YELLOW
    assert judged(image, projection).kind == NOT_A_LINE


def test_a_patch_wider_than_the_line_is_no_line():
    projection = camera()
    verdict = judged(frame_of(segment((0.0, 0.0), (2.0, 0.0)), projection, width=0.2),
                     projection)
    assert verdict.kind == NOT_A_LINE and 'wider than the line' in verdict.problem


def test_a_thread_narrower_than_the_line_is_left_out():
    projection = camera()
    thread = frame_of(segment((0.35, -0.1), (0.6, 0.1)), projection, width=0.008)
    assert judged(thread, projection).kind == EMPTY
    line = frame_of(segment((0.0, 0.2), (2.0, 0.2)), projection)
    both = np.where((line == WHITE).all(axis=2)[:, :, None], thread, line)
    verdict = judged(both, projection)
    assert verdict.kind == LINE
    assert np.count_nonzero(verdict.mask) == np.count_nonzero(line_mask(line, BOUNDS))


def test_the_edge_of_a_line_cut_by_the_image_border_is_kept():
    """Turning in place, a search first sees the line as a sliver at the image's side: too
    thin as seen, but cut by the border, so it may be the line."""
    projection = camera()
    line = segment((-1.0, -1.0), (2.0, 0.5))
    for yaw in np.arange(0.0, 1.2, 0.05):
        image = frame_of(line, projection, base=(0.0, 0.0, yaw))
        seen = np.count_nonzero(line_mask(image, BOUNDS))
        if 0 < seen < 300:
            break
    verdict = judged(image, projection)
    assert 0 < seen < 300 and verdict.kind == LINE


def test_a_camera_that_sees_no_floor_sees_no_line():
    k = Intrinsics.from_camera_info([100, 0, 80, 0, 100, 60, 0, 0, 1], 160, 120)
    looking_up = FloorProjection(k, level_camera_axes(math.radians(-60.0)), (0.0, 0.0, 0.3),
                                 1.5)
    verdict = judged(np.full((120, 160, 3), WHITE, np.uint8), looking_up)
    assert verdict.kind == NOT_A_LINE and 'sees no floor' in verdict.problem
