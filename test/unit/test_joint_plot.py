"""arm_plot's record and picture: joint_states in any joint order, saved as a PNG."""
import math
import os
import subprocess
import sys
import tempfile

import pytest
from matplotlib.figure import Figure
from PIL import Image

from wall_follower.evaluation.pictures.joint_plot import (DEFAULT_NAME, JointRecord, RecordingSpan,
                                                          draw, output_path, save, save_somewhere)


def test_the_record_keeps_each_joint_by_name_whatever_the_order():
    record = JointRecord()
    record.add(1.0, ['hip', 'elbow'], [0.1, 0.2], [1.0, 2.0])
    record.add(1.1, ['elbow', 'hip'], [0.3, 0.4], [])
    times, positions, velocities = record.copy()
    assert times == [1.0, 1.1]
    assert positions == {'hip': [0.1, 0.4], 'elbow': [0.2, 0.3]}
    assert velocities['hip'][0] == 1.0 and math.isnan(velocities['hip'][1])


def test_a_joint_heard_late_is_blank_before(tmp_path):
    record = JointRecord()
    record.add(0.0, ['hip'], [0.0], [0.0])
    record.add(0.5, ['hip', 'wrist'], [0.1, 0.2], [0.0, 0.0])
    assert math.isnan(record.copy()[1]['wrist'][0])


def test_saves_a_png_of_positions_and_velocities(tmp_path):
    record = JointRecord()
    for step in range(100):
        t = 0.02 * step
        record.add(10.0 + t, ['hip', 'shoulder'], [math.sin(t), t], [math.cos(t), 1.0])
    path = tmp_path / 'joints.png'
    save(record, str(path))
    with Image.open(str(path)) as image:
        assert image.format == 'PNG' and image.size == (800, 600)
    figure = Figure()
    draw(figure, record, window=0.5)
    above, below = figure.axes
    assert [line.get_label() for line in above.lines] == ['hip', 'shoulder']
    assert len(above.lines[0].get_xdata()) == 26     # the last half second
    assert below.get_ylabel() == 'velocity [rad/s]'


def a_record():
    record = JointRecord()
    for step in range(10):
        record.add(0.1 * step, ['hip'], [0.01 * step], [0.1])
    return record


def is_png(path):
    with Image.open(str(path)) as image:
        return image.format == 'PNG'


def test_a_directory_given_as_the_file_holds_the_picture_under_a_name_of_its_own(tmp_path):
    assert output_path(str(tmp_path)) == str(tmp_path / DEFAULT_NAME)
    assert output_path(str(tmp_path / 'new') + os.sep) == str(tmp_path / 'new' / DEFAULT_NAME)
    assert output_path(str(tmp_path / 'joints')) == str(tmp_path / 'joints.png')
    assert output_path(str(tmp_path / 'joints.png')) == str(tmp_path / 'joints.png')


def test_a_file_that_cannot_be_written_is_saved_next_to_it(tmp_path):
    taken = tmp_path / 'joints.png'
    taken.mkdir()                          # the name is a directory's: no file can be it
    saved, failures = save_somewhere(a_record(), str(taken))
    assert [path for path, _ in failures] == [str(taken)]
    assert os.path.dirname(saved) == str(tmp_path) and saved.endswith('.png')
    assert os.path.basename(saved).startswith('joints-') and is_png(saved)


def test_a_directory_that_cannot_be_written_has_the_picture_saved_in_the_temporary_one(
        tmp_path, monkeypatch):
    blocker = tmp_path / 'file'
    blocker.write_text('not a directory')
    temporary = tmp_path / 'tmp'
    temporary.mkdir()
    monkeypatch.setattr(tempfile, 'tempdir', str(temporary))
    saved, failures = save_somewhere(a_record(), str(blocker / 'joints.png'))
    assert len(failures) == 2 and os.path.dirname(saved) == str(temporary) and is_png(saved)


def test_nowhere_to_save_is_said_not_raised(tmp_path, monkeypatch):
    blocker = tmp_path / 'file'
    blocker.write_text('not a directory')
    monkeypatch.setattr(tempfile, 'tempdir', str(blocker))
    saved, failures = save_somewhere(a_record(), str(blocker / 'joints.png'))
    assert saved is None and len(failures) == 3
    assert os.listdir(str(tmp_path)) == ['file']


def test_a_recording_span_counts_ros_time_where_it_goes_forward():
    span = RecordingSpan(2.0, 100.0, 0.0)
    assert not span.update(101.0, 10.0)      # simulated time slower than the wall's
    assert span.update(102.0, 20.0)
    fast = RecordingSpan(2.0, 100.0, 0.0)
    assert fast.update(110.0, 0.5)           # and faster


@pytest.mark.parametrize('ros_times', [
    [0.0] * 6,                               # no /clock at all
    [50.0] * 6,                              # a frozen simulation
    [50.0, 49.0, 48.0, 47.0, 46.0, 45.0],    # a clock running backwards
])
def test_a_recording_span_ends_on_wall_time_while_ros_time_stands_still(ros_times):
    span = RecordingSpan(2.0, ros_times[0], 0.0)
    ended = [span.update(ros, 0.5 * (n + 1)) for n, ros in enumerate(ros_times[1:])]
    assert ended == [False, False, False, True, True]


def test_a_clock_that_starts_late_is_counted_from_its_start():
    span = RecordingSpan(2.0, 0.0, 0.0)
    assert not span.update(1000.0, 0.5)      # /clock came: 0.5 s of wall time so far
    assert not span.update(1001.0, 5.0)
    assert span.update(1001.5, 5.1)


def test_zero_is_until_stopped():
    span = RecordingSpan(0.0, 0.0, 0.0)
    assert not any(span.update(0.0, t) for t in (1.0, 1e6))


@pytest.mark.ros
def test_the_recorder_loads_matplotlib_only_to_save():
    # A recorder stopped before any joint_states came ends without matplotlib
    # ever loaded: on a busy machine its import and teardown took arm_plot
    # past the two seconds a Ctrl-C may take (signals.test).
    loaded = subprocess.check_output([sys.executable, '-c', (
        'import sys\n'
        'import wall_follower.nodes.arm.arm_plot\n'
        'print(sorted(m for m in sys.modules if m.split(".")[0] == "matplotlib"))')],
        universal_newlines=True)
    assert loaded.strip() == '[]'
