"""Every bad frame is named in words: wrong size, unknown encoding, truncated data, a step that
does not fit the width, a compressed frame cut short, a size camera_info does not give."""
import cv2
import numpy as np
import pytest

from wall_follower.vision.image_check import (
    decode_compressed, pixel_bytes, raw_image_problem, size_problem)


@pytest.mark.parametrize('encoding,size', [
    ('rgb8', 3), ('bgra8', 4), ('mono8', 1), ('mono16', 2), ('rgba16', 8), ('8UC3', 3),
    ('32FC1', 4), ('16SC2', 4), ('bayer_rggb8', 1), ('bayer_gbrg16', 2), ('yuv422', 2)])
def test_pixel_sizes_of_known_encodings(encoding, size):
    assert pixel_bytes(encoding) == size


def test_a_good_frame_has_no_problem():
    assert raw_image_problem('rgba8', 240, 320, 1280, 1280 * 240) is None
    assert raw_image_problem('rgb8', 2, 3, 12, 24) is None          # padded rows
    assert raw_image_problem('bgr8', 2, 330, 1024, 2048) is None    # rows aligned to 64 bytes


@pytest.mark.parametrize('frame,words', [
    (('rgb8', 0, 0, 0, 0), 'empty'),
    (('rgb8', 240, 0, 0, 0), 'empty'),
    (('jpeg-ish', 240, 320, 960, 960 * 240), 'unknown encoding'),
    (('', 240, 320, 960, 960 * 240), 'unknown encoding'),
    (('rgba8', 240, 320, 960, 960 * 240), 'row step'),              # wrong width for the step
    (('bgr8', 240, 320, 1280, 1280 * 240), 'another encoding'),     # rgba8 data named bgr8
    (('mono8', 240, 320, 960, 960 * 240), 'another encoding'),      # bgr8 data named mono8
    (('rgb8', 240, 320, 960, 960 * 239), 'bytes of data'),          # truncated
    (('rgb8', 480, 640, 1920, 960 * 240), 'bytes of data'),         # wrong size
])
def test_bad_frames_are_named(frame, words):
    problem = raw_image_problem(*frame)
    assert problem is not None and words in problem


def test_compressed_frames_decode_or_are_named():
    image = np.zeros((24, 32, 3), np.uint8)
    image[:, 10:14] = (0, 255, 255)
    for extension in ('.jpg', '.png'):
        ok, data = cv2.imencode(extension, image)
        decoded, problem = decode_compressed(data.tobytes())
        assert problem is None and decoded.shape == (24, 32, 3)
    ok, data = cv2.imencode('.png', image)
    assert decode_compressed(b'')[1] == 'an empty compressed image'
    assert 'PNG cut short' in decode_compressed(data.tobytes()[:40])[1]
    assert 'cannot be decoded' in decode_compressed(b'not an image at all')[1]


def frame_with_a_line(width=320, height=240):
    image = np.full((height, width, 3), 255, np.uint8)
    image[:, width // 2 - 10:width // 2 + 10] = (0, 255, 255)
    return image


def test_a_jpeg_cut_short_is_named_though_opencv_decodes_it():
    ok, data = cv2.imencode('.jpg', frame_with_a_line())
    cut = data.tobytes()[:800]
    assert cv2.imdecode(np.frombuffer(cut, np.uint8), cv2.IMREAD_COLOR) is not None
    image, problem = decode_compressed(cut)
    assert image is None and 'JPEG cut short' in problem


def test_a_jpeg_padded_with_zeros_is_whole():
    ok, data = cv2.imencode('.jpg', frame_with_a_line())
    image, problem = decode_compressed(data.tobytes() + bytes(16))
    assert problem is None and image.shape == (240, 320, 3)


def test_a_png_cut_short_is_named():
    ok, data = cv2.imencode('.png', frame_with_a_line())
    image, problem = decode_compressed(data.tobytes()[:-20])
    assert image is None and 'PNG cut short' in problem


def test_the_image_must_be_the_size_camera_info_gives():
    assert size_problem(np.zeros((240, 320, 3)), 320, 240) is None
    assert size_problem(np.zeros((240, 320, 3)), 640, 480) == (
        'the image is 320x240 but camera_info says 640x480')
    assert size_problem(np.zeros((1080, 1920, 3)), 320, 240) == (
        'the image is 1920x1080 but camera_info says 320x240')
