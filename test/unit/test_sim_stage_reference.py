"""The built-in simulator against recordings of real Stage 4.3 + stage_ros 1.8.

The recordings (test/data/stage_reference, see its README) hold scans taken
at exact poses in five worlds and, in ref_room, drive sequences with their
command logs. Each scan is reproduced from the recorded ground-truth pose,
as stage_sim starts there (its start check first: real Stage started every
one of them, two a centimetre from a wall); each drive is replayed with
stageros' timing: a command published after the update stamped T takes
effect in the update stamped T + interval.
"""
import json
import math
import os

import numpy as np
import pytest

from wall_follower.sim.engine import Simulation
from wall_follower.sim.start_check import start_problems
from wall_follower.sim.worldfile import load_world

DATA = os.path.join(os.path.dirname(__file__), '..', 'data', 'stage_reference')
WORLDS = ('ref_room', 'ref_shapes', 'ref_lidar270', 'ref_lidar270_yaw', 'ref_margin')
DRIVES = ('(i)', '(ii)', '(iii)', '(iv)', '(iv-b)', '(v)')
# Poses with a recorded scan, over all the worlds.
SNAPSHOTS = 54
# Drive records and snapshot ranges are rounded to 7 and 4 decimals in the recordings.
POSE_TOLERANCE = 1e-6
RANGE_ROUNDING = 5.1e-5


def _reference(name):
    with open(os.path.join(DATA, name + '.json')) as stream:
        return json.load(stream)


def _world(name):
    return load_world(os.path.join(DATA, name + '.world'))


def _scan_at(world, gt):
    """The scan a simulation of `world` publishes with the robot started at ground truth `gt`
    (as stage_sim starts it: only where its start check lets it)."""
    pose = (gt['x'], gt['y'], gt['yaw'])
    sim = Simulation(world, poses={0: pose})
    assert start_problems(world, sim.grid, [pose]) == []
    return sim.step().robots[0]


def test_every_recorded_pose_is_replayed():
    assert sum(len(_reference(name)['snapshots']) for name in WORLDS) == SNAPSHOTS


@pytest.mark.parametrize('name', WORLDS)
def test_scan_header_matches_stageros(name):
    header = _reference(name)['scan_header']
    scan = _scan_at(_world(name), _reference(name)['snapshots'][0]['gt']).scan
    # LaserScan fields are float32 in the message
    for field in ('angle_min', 'angle_max', 'angle_increment', 'range_min', 'range_max'):
        assert np.float32(getattr(scan, field)) == np.float32(header[field]), field
    assert len(scan.ranges) == header['len_ranges']
    assert len(scan.intensities) == header['len_intensities']


@pytest.mark.parametrize('name', WORLDS)
def test_laser_tf_matches_stageros(name):
    reference = _reference(name)['laser_tf']
    laser = _scan_at(_world(name), _reference(name)['snapshots'][0]['gt']).laser
    assert (laser.x, laser.y, laser.z) == pytest.approx(tuple(reference['translation']), abs=1e-9)
    assert laser.yaw == pytest.approx(reference['yaw'], abs=1e-6)


@pytest.mark.parametrize('name', WORLDS)
def test_every_snapshot_scan_matches_real_stage(name):
    world = _world(name)
    for snapshot in _reference(name)['snapshots']:
        robot = _scan_at(world, snapshot['gt'])
        ranges = robot.scan.ranges
        expected = np.array(snapshot['ranges'])
        error = np.abs(ranges - expected)
        label = '%s snapshot %d (%s)' % (name, snapshot['id'], snapshot['label'])
        assert np.mean(error <= 0.02) >= 0.99, label
        # Stage's quantisation is reproduced, not just approximated: every beam equals
        # real Stage's up to the recording's rounding (float32 and 4 decimals).
        assert np.all(error <= RANGE_ROUNDING), label
        assert np.array_equal(robot.scan.intensities, np.array(snapshot['intensities'])), label


def test_no_hit_reads_range_max_and_short_beams_are_kept():
    reference = _reference('ref_room')
    world = _world('ref_room')
    header = reference['scan_header']
    for snapshot in reference['snapshots']:
        scan = _scan_at(world, snapshot['gt']).scan
        expected = np.array(snapshot['ranges'])
        no_hit = np.array(snapshot['intensities']) == 0.0
        assert np.all(scan.ranges[no_hit] == header['range_max'])
        short = expected < header['range_min']
        assert np.all(scan.ranges[short] < header['range_min'])


def _sequences():
    return _reference('ref_room')['drives']['sequences']


def _key(sequence):
    """'(iv)' of '(iv) v=0.19 into wall'."""
    return sequence['name'].split(' ')[0]


def _tick(stamp):
    return int(round(stamp * 10))


def _replay(sim, sequence, after_tick=None):
    """Replay `sequence` on `sim`; yield (record, robot frame, pose before) per update.

    The simulation is taken to be at the sequence's first record (or at `after_tick`
    when it continues an earlier sequence without a reset).
    """
    commands = {}
    for command in sequence['cmd_log']:
        commands.setdefault(_tick(command['clock_before']), []).append(command)
    records = sequence['records']
    if after_tick is None:
        first = records[0]
        _assert_pose(sim.robots[0].pose, first['gt'], 'start of %s' % sequence['name'])
        after_tick = _tick(first['stamp'])
    for record in records:
        tick = _tick(record['stamp'])
        if tick <= after_tick:
            continue
        assert tick == after_tick + 1, 'records are one per update'
        for command in commands.get(after_tick, []):
            sim.set_command(0, command['v'], command['w'])
        before = sim.robots[0].pose
        frame = sim.step()
        yield record, frame.robots[0], before
        after_tick = tick


def _assert_pose(pose, expected, label):
    assert pose[0] == pytest.approx(expected['x'], abs=POSE_TOLERANCE), label
    assert pose[1] == pytest.approx(expected['y'], abs=POSE_TOLERANCE), label
    assert math.remainder(pose[2] - expected['yaw'], 2 * math.pi) == \
        pytest.approx(0.0, abs=POSE_TOLERANCE), label


def _assert_twist(odometry, expected, label):
    assert (odometry.vx, odometry.vy, odometry.wz) == pytest.approx(
        (expected['vx'], expected['vy'], expected['wz']), abs=POSE_TOLERANCE), label


def _replay_all():
    """Replay every drive sequence in recorded order on one simulation: [(sequence, steps)]."""
    sim = Simulation(_world('ref_room'))
    results = []
    last_tick = None
    for sequence in _sequences():
        continuing = not sequence['reset_before']
        if not continuing:
            sim.reset()
            # Updates passed between the reset and the first record; the first one
            # carries stageros' ground-truth velocity spike of the jump back.
            sim.step()
        steps = list(_replay(sim, sequence, after_tick=last_tick if continuing else None))
        results.append((sequence, steps))
        last_tick = _tick(sequence['records'][-1]['stamp'])
    return results


@pytest.fixture(scope='module')
def replayed():
    return _replay_all()


def _moved(steps):
    return [robot for _, robot, before in steps
            if (robot.ground_truth.x, robot.ground_truth.y, robot.ground_truth.yaw) != before]


@pytest.mark.parametrize('key', DRIVES)
def test_drive_matches_every_recorded_update(replayed, key):
    runs = [(sequence, steps) for sequence, steps in replayed if _key(sequence) == key]
    assert runs
    for sequence, steps in runs:
        assert steps, sequence['name']
        for record, robot, _ in steps:
            label = '%s at %.1f' % (sequence['name'], record['stamp'])
            # (a message the recorder missed is null)
            if record['gt'] is not None:
                _assert_pose((robot.ground_truth.x, robot.ground_truth.y,
                              robot.ground_truth.yaw), record['gt'], label)
                _assert_twist(robot.ground_truth, record['gt'], label)
            if record['odom'] is not None:
                _assert_pose((robot.odom.x, robot.odom.y, robot.odom.yaw), record['odom'], label)
                _assert_twist(robot.odom, record['odom'], label)
        end = steps[-1][1].ground_truth
        _assert_pose((end.x, end.y, end.yaw), sequence['end_gt'], sequence['name'] + ' end')
        assert len(_moved(steps)) == sequence['moved_steps'], sequence['name']


def _run(replayed, key):
    (run,) = [(sequence, steps) for sequence, steps in replayed if _key(sequence) == key]
    return run


def test_contact_stops_at_stages_pose_and_stays(replayed):
    _, steps = _run(replayed, '(iv)')
    contact = _reference('ref_room')['drives']['contact_iv']
    last_moving = _tick(contact['last_moved_stamp'])
    stop_command = _tick(contact['stop_cmd_after_clock'])
    pushing = [(record, robot) for record, robot, _ in steps
               if last_moving < _tick(record['stamp']) <= stop_command]
    assert len(pushing) == contact['stalled_pushing_updates']
    for record, robot in pushing:
        gt = robot.ground_truth
        _assert_pose((gt.x, gt.y, gt.yaw), contact['contact_gt'],
                     'pushing at %.1f' % record['stamp'])
        assert robot.stalled
        assert robot.odom.vx == pytest.approx(0.19)   # odometry still reports the command
        assert (gt.vx, gt.vy, gt.wz) == (0.0, 0.0, 0.0)


def test_backing_out_of_contact_is_not_latched(replayed):
    sequence, steps = _run(replayed, '(iv-b)')
    moved = _moved(steps)
    assert len(moved) == sequence['moved_steps'] == 10
    assert not moved[0].stalled


def test_single_command_moves_exactly_two_updates(replayed):
    runs = [steps for sequence, steps in replayed if _key(sequence) == '(v)']
    assert len(runs) == 8
    for steps in runs:
        moved = _moved(steps)
        assert len(moved) == 2
        assert moved[1].ground_truth.x - moved[0].ground_truth.x == pytest.approx(
            0.19 * 0.1 * math.cos(math.radians(30.0)))


def test_reset_shows_as_one_update_velocity_spike():
    sim = Simulation(_world('ref_room'))
    sim.set_command(0, 0.19, 0.0)
    for _ in range(3):
        sim.step()
    moved = sim.robots[0].pose
    sim.reset()
    spike = sim.step().robots[0].ground_truth
    start = _world('ref_room').robots[0].pose
    assert spike.vx == pytest.approx((start[0] - moved[0]) / 0.1)
    assert spike.vy == pytest.approx((start[1] - moved[1]) / 0.1)
    assert sim.step().robots[0].ground_truth.vx == 0.0
