"""Map files that cannot be maps: save_map writes nothing for them, load_map refuses them with
one line naming the file and what is wrong; and a pair saved under a relative name loads from
anywhere."""
import math
import os
import re
import threading

import numpy as np
import pytest

from wall_follower.mapping.mapfile import load_map, map_problem, save_map

SMALL = np.array([[0, 100, -1], [25, 65, 50]], dtype=np.int8)
ORIGIN = (-1.25, 0.5, 0.0)
NAN = float('nan')


@pytest.mark.parametrize('data, resolution, origin, says', [
    (np.zeros((0, 0), dtype=np.int8), 0.05, ORIGIN, 'no cells (0 x 0)'),
    (SMALL, 0.0, ORIGIN, 'resolution 0.0 is not a positive length'),
    (SMALL, -0.05, ORIGIN, 'resolution -0.05 is not a positive length'),
    (SMALL, NAN, ORIGIN, 'resolution nan is not a positive length'),
    (SMALL, 0.05, (NAN, 0.5, 0.0), 'origin [nan, 0.5, 0.0] is not three finite numbers'),
    (SMALL, 0.05, (0.0, 0.5, math.inf), 'origin [0.0, 0.5, inf] is not three finite'),
])
def test_a_map_that_cannot_be_one_is_not_written(tmp_path, data, resolution, origin, says):
    with pytest.raises(ValueError, match=re.escape(says)):
        save_map(os.path.join(str(tmp_path), 'bad'), data, resolution, origin)
    assert os.listdir(str(tmp_path)) == []


def test_data_that_do_not_fill_width_by_height_are_named():
    assert map_problem(3, 2, 5, 0.05, ORIGIN) == '5 values do not fill 3 x 2 cells'
    assert map_problem(3, 2, 6, 0.05, ORIGIN) is None


def test_a_map_saved_under_a_relative_name_loads_from_anywhere(tmp_path, monkeypatch):
    os.mkdir(os.path.join(str(tmp_path), 'maps'))
    monkeypatch.chdir(str(tmp_path))
    image, meta = save_map(os.path.join('maps', 'small'), SMALL, 0.05, ORIGIN)
    assert (image, meta) == (os.path.join('maps', 'small.pgm'), os.path.join('maps', 'small.yaml'))
    with open(meta) as stream:
        assert stream.readline() == 'image: small.pgm\n'
    for where in (str(tmp_path), os.path.join(str(tmp_path), 'maps'), os.sep):
        monkeypatch.chdir(where)
        loaded = load_map(os.path.join(str(tmp_path), 'maps', 'small.yaml'))
        assert loaded.data.tolist() == [[0, 100, -1], [0, 100, -1]]


def test_a_map_saved_under_an_absolute_name_names_its_image_as_map_saver_does(tmp_path):
    name = os.path.join(str(tmp_path), 'small')
    _, meta = save_map(name, SMALL, 0.05, ORIGIN)
    with open(meta) as stream:
        assert stream.readline() == 'image: %s.pgm\n' % name


def _pair(tmp_path, yaml_text, pgm=None):
    """A map description (and its image, when given) in tmp_path; the YAML's path."""
    if pgm is not None:
        with open(os.path.join(str(tmp_path), 'm.pgm'), 'wb') as stream:
            stream.write(pgm)
    path = os.path.join(str(tmp_path), 'm.yaml')
    with open(path, 'w') as stream:
        stream.write(yaml_text)
    return path


GOOD_PGM = b'P5\n# CREATOR: map_saver.cpp 0.050 m/pix\n3 2\n255\n' + bytes(6)
YAML = ('image: m.pgm\nresolution: %s\norigin: %s\nnegate: 0\noccupied_thresh: 0.65\n'
        'free_thresh: 0.196\n')


def _refused(path):
    """load_map's error for path, in at most 5 s (a cut-short header once looped for ever)."""
    outcome = []

    def load():
        try:
            load_map(path)
            outcome.append(None)
        except ValueError as error:
            outcome.append(str(error))
    thread = threading.Thread(target=load)
    thread.daemon = True
    thread.start()
    thread.join(5.0)
    assert outcome, 'load_map did not return'
    assert outcome[0] is not None, 'load_map accepted it'
    assert '\n' not in outcome[0]
    return outcome[0]


@pytest.mark.parametrize('pgm, says', [
    (GOOD_PGM[:-2], 'cut short: 4 of the 3 x 2 pixels'),
    (b'P5\n3 2\n25', 'the PGM header is cut short'),
    (b'P5\n3 2', 'the PGM header is cut short'),
    (b'P5\n# a comment never ended', 'the PGM header is cut short'),
    (b'', 'the PGM header is cut short'),
    (b'P2\n3 2\n255\n0 0 0 0 0 0', 'not a binary PGM (P5) image'),
    (b'P5\n3 x\n255\n', 'not a binary PGM (P5) image'),
    (b'P5\n0 0\n255\n', 'the image has no pixels (0 x 0)'),
])
def test_a_bad_image_is_refused_naming_it(tmp_path, pgm, says):
    error = _refused(_pair(tmp_path, YAML % ('0.05', '[0, 0, 0]'), pgm))
    assert error == '%s: %s' % (os.path.join(str(tmp_path), 'm.pgm'), says)


@pytest.mark.parametrize('text, says', [
    (YAML % ('0.05', '[.nan, 0, 0]'), 'origin [nan, 0.0, 0.0] is not three finite numbers'),
    (YAML % ('0.05', '[0, 0]'), 'origin [0.0, 0.0] is not three finite numbers'),
    (YAML % ('0.0', '[0, 0, 0]'), 'resolution 0.0 is not a positive length'),
    (YAML % ('-0.05', '[0, 0, 0]'), 'resolution -0.05 is not a positive length'),
    (YAML % ('0.05', '[0, 0, 0'), 'not YAML'),
    ('image: m.pgm\nresolution: [0.05\n', 'not YAML'),
    ('- a list\n', 'not a map_server map description'),
    (YAML.replace('m.pgm', 'gone.pgm') % ('0.05', '[0, 0, 0]'), 'gone.pgm does not exist'),
])
def test_a_bad_description_is_refused_naming_it(tmp_path, text, says):
    error = _refused(_pair(tmp_path, text, GOOD_PGM))
    assert error.startswith(os.path.join(str(tmp_path), 'm.yaml') + ':')
    assert says in error


def test_a_description_that_is_not_text_is_refused_naming_it(tmp_path):
    path = os.path.join(str(tmp_path), 'm.yaml')
    with open(path, 'wb') as stream:
        stream.write(b'image: \xe4\xff\n')
    assert _refused(path).startswith(path + ': not a map description: not text (')


def test_a_missing_description_is_refused_naming_it(tmp_path):
    error = _refused(os.path.join(str(tmp_path), 'none.yaml'))
    assert error.startswith(os.path.join(str(tmp_path), 'none.yaml') + ': cannot read')
