"""camera_view's snapshots: a reader polling the directory never finds one half written."""
import glob
import os

import cv2
import numpy as np

from wall_follower.nodes.camera import camera_view


def test_a_snapshot_is_never_seen_under_its_name_while_it_is_written(tmp_path, monkeypatch):
    image = np.zeros((24, 32, 3), np.uint8)
    image[:, 10:20] = (0, 255, 255)
    path = str(tmp_path / 'camera_0000.png')
    seen_while_writing = []
    real_imwrite = cv2.imwrite

    def imwrite(name, picture):
        # What a test globbing the directory for '*.png' would find mid-write.
        seen_while_writing.extend(glob.glob(str(tmp_path / '*.png')))
        with open(name, 'wb') as partial:
            partial.write(b'\x89PNG')
        seen_while_writing.extend(glob.glob(str(tmp_path / '*.png')))
        return real_imwrite(name, picture)

    monkeypatch.setattr(camera_view.cv2, 'imwrite', imwrite)
    assert camera_view.write_whole(path, image)
    assert seen_while_writing == []
    assert np.array_equal(cv2.imread(path), image)
    assert os.listdir(str(tmp_path)) == ['camera_0000.png']


def test_a_snapshot_that_cannot_be_written_leaves_nothing(tmp_path, monkeypatch):
    monkeypatch.setattr(camera_view.cv2, 'imwrite', lambda name, picture: False)
    assert not camera_view.write_whole(str(tmp_path / 'camera_0000.png'),
                                       np.zeros((4, 4, 3), np.uint8))
    assert os.listdir(str(tmp_path)) == []
    assert not camera_view.write_whole(str(tmp_path / 'missing' / 'camera_0000.png'),
                                       np.zeros((4, 4, 3), np.uint8))
