"""arm_plot's record and picture: joint_states in any joint order, saved as a PNG."""
import math
import subprocess
import sys

import pytest
from matplotlib.figure import Figure
from PIL import Image

from wall_follower.evaluation.joint_plot import JointRecord, draw, save


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


@pytest.mark.ros
def test_the_recorder_loads_matplotlib_only_to_save():
    # A recorder stopped before any joint_states came ends without matplotlib
    # ever loaded: on a busy machine its import and teardown took arm_plot
    # past the two seconds a Ctrl-C may take (signals.test).
    loaded = subprocess.check_output([sys.executable, '-c', (
        'import sys\n'
        'import wall_follower.nodes.arm_plot\n'
        'print(sorted(m for m in sys.modules if m.split(".")[0] == "matplotlib"))')],
        universal_newlines=True)
    assert loaded.strip() == '[]'
