"""The line mask, the lab's slice centroid and the line's pixels on synthetic images."""
import math

import cv2
import numpy as np
import pytest

from wall_follower.vision.line_image import (
    HsvBounds, hsv_bounds, line_mask, line_pixels, mark_centroid, slice_centroid, slice_rows)

YELLOW = HsvBounds((20, 100, 100), (40, 255, 255))
BGR_YELLOW = (0, 255, 255)


def floor_with_line(width, height, column, line_width, colour=BGR_YELLOW):
    image = np.full((height, width, 3), 255, np.uint8)      # Stage's white floor
    left = int(column - line_width / 2)
    image[:, left:left + line_width] = colour
    return image


@pytest.mark.parametrize('width,height', [(320, 240), (640, 480), (64, 48)])
def test_mask_holds_the_yellow_line_and_nothing_of_the_floor(width, height):
    image = floor_with_line(width, height, width // 3, width // 10)
    image[:height // 4, -20:] = (40, 40, 200)                # a red box: not the line
    mask = line_mask(image, YELLOW)
    assert mask.dtype == np.uint8 and mask.shape == (height, width)
    expected = np.zeros((height, width), bool)
    left = int(width // 3 - (width // 10) / 2)
    expected[:, left:left + width // 10] = True
    assert np.array_equal(mask > 0, expected)


def test_hue_bounds_that_wrap_take_red_from_both_ends():
    image = np.zeros((2, 3, 3), np.uint8)
    image[0, 0] = (0, 0, 255)          # hue 0
    image[0, 1] = (40, 0, 255)         # hue about 175
    image[0, 2] = (0, 255, 0)          # green
    mask = line_mask(image, HsvBounds((170, 100, 100), (10, 255, 255)))
    assert list(mask[0] > 0) == [True, True, False]


def test_bounds_from_parameters():
    values = dict(hue_low=1, saturation_low=2, value_low=3, hue_high=4, saturation_high=5,
                  value_high=6)
    assert hsv_bounds(values) == HsvBounds((1, 2, 3), (4, 5, 6))


def test_slice_centroid_finds_the_line_in_the_slice_only():
    image = np.full((240, 320, 3), 255, np.uint8)
    image[180:200, 200:220] = BGR_YELLOW          # in the lab's slice (3/4 of the height down)
    image[0:100, 20:60] = BGR_YELLOW              # far ahead: not in the slice
    centroid = slice_centroid(line_mask(image, YELLOW), 0.75, 20 / 240.0)
    assert centroid == pytest.approx((209.5, 189.5))


def test_slice_centroid_is_none_without_line_in_the_slice():
    image = np.full((240, 320, 3), 255, np.uint8)
    image[:100, 100:120] = BGR_YELLOW
    assert slice_centroid(line_mask(image, YELLOW), 0.75, 0.1) is None


def test_slice_rows_hold_at_least_one_row_inside_the_image():
    assert slice_rows(240, 0.75, 20 / 240.0) == (180, 200)
    assert slice_rows(10, 0.99, 0.001) == (9, 10)
    assert slice_rows(10, 1.5, 0.5) == (9, 10)


def test_line_pixels_are_columns_and_rows_of_the_mask():
    mask = np.zeros((6, 8), np.uint8)
    mask[2, 5] = mask[4, 1] = 255
    assert sorted(map(tuple, line_pixels(mask, 1))) == [(1.0, 4.0), (5.0, 2.0)]
    mask[:, :] = 255
    assert len(line_pixels(mask, 2)) == 12


def test_centroid_marked_by_a_red_dot_on_a_copy():
    image = np.full((48, 64, 3), 255, np.uint8)
    marked = mark_centroid(image, (10.2, 20.7), 3)
    assert tuple(marked[21, 10]) == (0, 0, 255)
    assert tuple(image[21, 10]) == (255, 255, 255)
    assert np.array_equal(mark_centroid(image, None, 3), image)
    hsv = cv2.cvtColor(marked, cv2.COLOR_BGR2HSV)
    assert hsv[21, 10, 1] == 255


def test_pixel_p_turns_toward_the_line_and_stops_without_one():
    from line_course import camera
    from wall_follower.control.motion import STOP, Answer
    from wall_follower.vision.pixel_p import PixelP
    follower = PixelP(0.2, 0.01, 0.75, 20 / 240.0)
    right = line_mask(floor_with_line(320, 240, 200, 20), YELLOW)
    command, ahead_known = follower.update(right, camera(), math.radians(30.0))
    assert command.linear == 0.2 and ahead_known
    assert command.angular == pytest.approx(-0.01 * (199.5 - 160.0))
    # The slice lies near the robot: 100 px off the middle is over 30 deg off its heading.
    far_right = line_mask(floor_with_line(320, 240, 260, 20), YELLOW)
    command, ahead_known = follower.update(far_right, camera(), math.radians(30.0))
    assert command.angular == pytest.approx(-0.01 * (259.5 - 160.0)) and not ahead_known
    assert follower.update(np.zeros((240, 320), np.uint8), camera(), math.radians(30.0)) == (
        Answer(STOP, False))
