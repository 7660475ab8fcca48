"""Frames as line_follower reads them (nodes.shared.latest_image): every encoding cv_bridge
reads into colour, every bad frame named in words instead of raised, and a frame stamped in
the future held as stale input (no time arithmetic meets its stamp). Needs ROS's Python
modules but no master: LatestImage's subscriber is only created, its callback called here."""
import cv2
import numpy as np
import pytest
import rospy
from sensor_msgs.msg import CompressedImage, Image

from wall_follower.nodes.shared.latest_image import LatestImage, read_compressed, read_image


def image_msg(array, encoding):
    msg = Image()
    msg.height, msg.width = array.shape[:2]
    msg.encoding = encoding
    msg.step = array.strides[0]
    msg.data = array.tobytes()
    return msg


YELLOW_RGBA = (255, 255, 0, 255)


@pytest.mark.parametrize('encoding,pixel,expected', [
    ('rgba8', YELLOW_RGBA, (0, 255, 255)),          # stageros's
    ('rgb8', (255, 255, 0), (0, 255, 255)),
    ('bgr8', (0, 255, 255), (0, 255, 255)),
    ('bgra8', (0, 255, 255, 255), (0, 255, 255)),
    ('mono8', (200,), (200, 200, 200)),
])
def test_encodings_become_bgr(encoding, pixel, expected):
    array = np.zeros((6, 8, len(pixel)), np.uint8)
    array[:, :] = pixel
    if len(pixel) == 1:
        array = array[:, :, 0]
    image, problem = read_image(image_msg(array, encoding))
    assert problem is None
    assert image.shape == (6, 8, 3) and tuple(image[3, 4]) == expected


def test_a_bayer_frame_becomes_colour():
    image, problem = read_image(image_msg(np.full((8, 8), 120, np.uint8), 'bayer_rggb8'))
    assert problem is None and image.shape == (8, 8, 3)


@pytest.mark.parametrize('change,words', [
    (dict(encoding='h264'), 'unknown encoding'),
    (dict(height=0, width=0, step=0, data=b''), 'empty'),
    (dict(height=12), 'bytes of data'),                     # wrong size for its data
    (dict(data=bytes(100)), 'bytes of data'),               # truncated
    (dict(step=10), 'row step'),
    (dict(encoding='32FC1'), 'cv_bridge'),                  # read, but not as colour
])
def test_bad_frames_are_named_not_raised(change, words):
    msg = image_msg(np.zeros((6, 8, 4), np.uint8), 'rgba8')
    for key, value in change.items():
        setattr(msg, key, value)
    image, problem = read_image(msg)
    assert image is None and words in problem


def test_compressed_frames():
    ok, data = cv2.imencode('.jpg', np.full((24, 32, 3), 90, np.uint8))
    msg = CompressedImage(format='jpeg', data=data.tobytes())
    image, problem = read_compressed(msg)
    assert problem is None and image.shape == (24, 32, 3)
    msg.data = data.tobytes()[:30]
    assert read_compressed(msg)[0] is None
    msg.data = b''
    assert read_compressed(msg) == (None, 'an empty compressed image')


def frame_stamped(secs, nsecs=0):
    msg = image_msg(np.zeros((6, 8, 4), np.uint8), 'rgba8')
    msg.header.stamp = rospy.Time(secs, nsecs)
    return msg


def test_a_frame_stamped_in_the_future_is_stale_input(clock):
    images = LatestImage()
    clock.now = 10.0
    images._on_image(frame_stamped(4102444800))           # 2100-01-01
    reading = images.latest(0.3)
    assert reading.view is None and 'ahead of this node' in reading.problem
    images._on_image(frame_stamped(2 ** 32 - 1, 2 ** 32 - 1))   # the largest stamp there is
    assert 'ahead of this node' in images.latest(0.3).problem
    images._on_image(frame_stamped(10, 200000000))         # a step ahead: a clock not yet in
    assert images.latest(0.3).view is not None


def test_a_frame_of_a_camera_far_behind_is_read(clock):
    """Age counts from arrival, as a scan's: a camera host whose clock is behind still
    delivers fresh frames."""
    images = LatestImage()
    clock.now = 10.0
    images._on_image(frame_stamped(3))
    reading = images.latest(0.3)
    assert reading.view is not None and reading.taken == pytest.approx(3.0)
