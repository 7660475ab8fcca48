"""The built-in simulator's localization "odom" against real Stage 4.3's, recorded.

test/data/stage_reference/stage_odometry.json (tools/record_stage_odometry.py)
holds real stageros driving robots with given odom_error values (in degrees
and in a unit_angle "radians" world) and without any (a world recorded in two
runs) through straight, turn-in-place, past-the-bounds, sideways-commanded and
reverse arcs, with a /reset_positions between, one of them into a post: /odom
and ground truth of every update. Each run is replayed through `Simulation` on
the same world file, read by sim.worldfile: the recorded commands in, the
odometry and ground truth out.
"""
import json
import math
import os

import numpy as np
import pytest

from wall_follower.evaluation.scoring.stage_odometry import step_scale_errors
from wall_follower.sim.engine import DEFAULT_ODOM_ERROR_LIMITS, Simulation, _dead_reckoning
from wall_follower.sim.kinematics import diff_drive_step
from wall_follower.sim.worldfile import load_world

DATA = os.path.join(os.path.dirname(__file__), '..', 'data', 'stage_reference')
GIVEN = ('degrees', 'radians')
DEFAULT = ('default-1', 'default-2')
# The recording rounds poses to 12 decimals; the replay's float arithmetic is
# Stage's, so nothing larger than that rounding may remain.
TOLERANCE = 2e-12
# Errors fitted from 12-decimal poses: one update's step is 0.01-0.05, so its
# ratio to the commanded step is known to about 1e-10.
FIT_TOLERANCE = 1e-9


@pytest.fixture(scope='module')
def reference():
    with open(os.path.join(DATA, 'stage_odometry.json')) as stream:
        return json.load(stream)


def _run(reference, name):
    return next(run for run in reference['runs'] if run['name'] == name)


def _world(run):
    return load_world(os.path.join(DATA, run['world']))


def _replay(run, odom_errors=None):
    """Run the recorded commands through the built-in simulator: per robot, the
    (odom rows, ground-truth rows) at the recorded stamps.

    A command sent on the clock tick T drives the update stamped T + dt, as in
    stageros. odom_errors, if given, replace the errors the simulator took.
    """
    sim = Simulation(_world(run))
    if odom_errors is not None:
        for robot, error in zip(sim.robots, odom_errors):
            robot.odom_error = error
    dt = sim.dt
    while sim.time < run['stamps'][0] - 1.5 * dt:
        sim.step(with_scans=False)
    commands = {_tick(clock, dt): (v, w) for clock, v, _, w in run['cmd_log']}
    replayed = [([], []) for _ in sim.robots]
    for stamp in run['stamps']:
        if stamp == run['reset']['first_stamp_at_start']:
            sim.reset()
        v, w = commands.get(_tick(stamp, dt) - 1, (0.0, 0.0))
        for number in range(len(sim.robots)):
            sim.set_command(number, v, w)
        frame = sim.step(with_scans=False)
        assert frame.stamp == pytest.approx(stamp)
        for (odom, gt), robot in zip(replayed, frame.robots):
            odom.append(list(robot.odom))
            gt.append(list(robot.ground_truth[:3]))
    return replayed


def _tick(stamp, dt):
    return int(round(stamp / dt))


def _largest_difference(rows, recorded):
    """The largest |difference| of x, y and (wrapped) yaw over all rows."""
    mine, theirs = np.asarray(rows)[:, :3], np.asarray(recorded)[:, :3]
    position = np.max(np.abs(mine[:, :2] - theirs[:, :2]))
    heading = np.max(np.abs(np.remainder(mine[:, 2] - theirs[:, 2] + math.pi, 2 * math.pi)
                            - math.pi))
    return max(position, heading)


@pytest.mark.parametrize('name', GIVEN)
def test_given_odom_error_is_reproduced_at_every_update(reference, name):
    run = _run(reference, name)
    for (odom, gt), robot in zip(_replay(run), run['robots']):
        assert _largest_difference(odom, robot['odom']) <= TOLERANCE, robot['name']
        assert np.abs(np.asarray(odom)[:, 3:] - np.asarray(robot['odom'])[:, 3:]).max() <= TOLERANCE
        assert _largest_difference(gt, robot['gt']) <= TOLERANCE, robot['name']


def test_a_stalled_robot_is_held_where_stage_holds_it_while_its_odometry_counts_on(
        reference):
    # "pusher" drives into a post and then turns against it: Stage rejects a
    # step whose body outline shares a cell with the post's, even where the
    # body itself would not yet touch the post.
    run = _run(reference, 'degrees')
    number = next(i for i, robot in enumerate(run['robots']) if robot['name'] == 'pusher')
    recorded = run['robots'][number]
    odom, gt = _replay(run)[number]
    held = [i for i in range(1, len(gt)) if recorded['gt'][i] == recorded['gt'][i - 1]
            and recorded['odom'][i][:3] != recorded['odom'][i - 1][:3]]
    assert len(held) > 30
    assert _largest_difference(gt, recorded['gt']) <= TOLERANCE
    assert _largest_difference(odom, recorded['odom']) <= TOLERANCE


@pytest.mark.parametrize('name', GIVEN)
def test_stage_scales_by_the_given_errors_every_update(reference, name):
    # Used as given, not as the bound of a draw: each update's step is scaled by
    # exactly the value in the world file, with the angle in the world's unit.
    run = _run(reference, name)
    for spec, robot in zip(_world(run).robots, run['robots']):
        ex, ea = step_scale_errors(robot['odom'], reference['interval_sim'])
        assert len(ex) > 50 and len(ea) > 50
        assert np.abs(ex - spec.odom_error[0]).max() < FIT_TOLERANCE, robot['name']
        assert np.abs(ea - spec.odom_error[2]).max() < FIT_TOLERANCE, robot['name']


def test_odom_errors_angle_is_in_the_worlds_angle_unit(reference):
    # odom_degrees' "big" gives 10: a turn scaled by 1 + 10 degrees, not 1 + 10;
    # odom_radians' "plus" gives 0.2: scaled by 1.2, not 1 + 0.2 degrees.
    for name, robot, scale in (('degrees', 0, math.radians(10.0)), ('radians', 0, 0.2)):
        odom = _run(reference, name)['robots'][robot]['odom']
        _, ea = step_scale_errors(odom, reference['interval_sim'])
        assert np.median(ea) == pytest.approx(scale, abs=FIT_TOLERANCE)


def test_a_diff_drive_robot_never_uses_the_y_error(reference):
    # "negative" has odom_error y 0.2 and was commanded sideways (vy 0.1) in the
    # arc: Stage's diff drive drops vy, so neither its pose nor its odometry moves
    # sideways and the y error never shows.
    run = _run(reference, 'degrees')
    assert any(row[2] != 0.0 for row in run['cmd_log'])
    robot = next(robot for robot in run['robots'] if robot['name'] == 'negative')
    assert _world(run).robots[1].odom_error[1] == 0.2
    odom = np.asarray(robot['odom'])
    assert np.all(odom[:, 4] == 0.0)
    step = np.diff(odom[:, :2], axis=0)
    sideways = -step[:, 0] * np.sin(odom[1:, 2]) + step[:, 1] * np.cos(odom[1:, 2])
    assert np.abs(sideways).max() < 1e-11


@pytest.mark.parametrize('name', GIVEN)
def test_odometry_integrates_the_velocity_clamped_to_the_default_bounds(reference, name):
    # Commanded 1.5 m/s and 2 rad/s; Stage's default velocity_bounds are 1 m/s and
    # pi/2 rad/s, whatever the world's angle unit.
    run = _run(reference, name)
    commanded = np.asarray(run['cmd_log'])
    assert commanded[:, 1].max() == 1.5 and commanded[:, 3].max() == 2.0
    for robot in run['robots']:
        odom = np.asarray(robot['odom'])
        assert odom[:, 3].max() == pytest.approx(1.0, abs=TOLERANCE)
        assert odom[:, 5].max() == pytest.approx(math.pi / 2, abs=TOLERANCE)


def _integrate(odom, dt, step):
    pose, poses = (0.0, 0.0, 0.0), []
    for row in odom:
        pose = step(pose, row[3], row[5], dt)
        poses.append(pose)
    return poses


def test_stage_turns_before_it_advances_the_odometry(reference):
    # "zero" has no error at all: its odometry is the velocities integrated
    # turn first, not advance first as the true pose moves.
    run = _run(reference, 'degrees')
    odom = next(robot for robot in run['robots'] if robot['name'] == 'zero')['odom']
    dt = reference['interval_sim']
    turn_first = _integrate(odom, dt, lambda p, v, w, t: _dead_reckoning(p, v, w, t, (0, 0, 0)))
    advance_first = _integrate(odom, dt, diff_drive_step)
    assert _largest_difference(turn_first, odom) <= TOLERANCE
    assert _largest_difference(advance_first, odom) > 1e-3


def _default_errors(reference):
    """{(run, robot): (ex, ea)} fitted from the runs without odom_error."""
    fitted = {}
    for name in DEFAULT:
        for robot in _run(reference, name)['robots']:
            ex, ea = step_scale_errors(robot['odom'], reference['interval_sim'])
            assert ex.max() - ex.min() < FIT_TOLERANCE and ea.max() - ea.min() < FIT_TOLERANCE
            fitted[name, robot['name']] = (float(np.median(ex)), float(np.median(ea)))
    return fitted


def test_without_odom_error_stage_draws_within_the_builtin_limits(reference):
    fitted = _default_errors(reference)
    limit_x, _, limit_a = DEFAULT_ODOM_ERROR_LIMITS
    for key, (ex, ea) in fitted.items():
        assert abs(ex) <= limit_x and abs(ea) <= limit_a, key
    # One draw per robot, another for each run: no two alike.
    assert len(set(fitted.values())) == len(fitted)


def test_builtin_draws_one_error_per_robot(reference):
    sim = Simulation(_world(_run(reference, 'default-1')))
    first, second = (robot.odom_error for robot in sim.robots)
    assert first != second


@pytest.mark.parametrize('name', DEFAULT)
def test_runs_without_odom_error_are_reproduced_with_their_drawn_errors(reference, name):
    # Each robot keeps its one draw for the whole run, across the reset too.
    run = _run(reference, name)
    fitted = _default_errors(reference)
    errors = [(fitted[name, robot['name']][0], 0.0, fitted[name, robot['name']][1])
              for robot in run['robots']]
    for (odom, _), robot in zip(_replay(run, errors), run['robots']):
        assert _largest_difference(odom, robot['odom']) <= 1e-9, robot['name']
