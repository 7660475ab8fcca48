"""Stage's localization "odom": dead reckoning with scale errors, against the closed form.

Stage 4.3 (ModelPosition::Update) integrates each update's velocity into its
estimate, turning first and then advancing along the new heading, with every
component scaled by (1 + error): after n updates at (v, w) the estimate has
turned n*phi with phi = w*dt*(1 + ea), and advanced by v*dt*(1 + ex) along
each heading phi, 2*phi, ..., n*phi. odom_error's fourth value is read as an
angle (degrees by default), as every 'a' of a Stage tuple is.
"""
import cmath
import math
import os
import textwrap

import numpy as np
import pytest

from wall_follower.sim.engine import DEFAULT_ODOM_ERROR_LIMITS, Simulation
from wall_follower.sim.worldfile import load_world

WORLDS = os.path.join(os.path.dirname(__file__), '..', '..', 'worlds')


def _world(tmp_path, robot_props):
    path = os.path.join(str(tmp_path), 'w.world')
    with open(path, 'w') as stream:
        stream.write(textwrap.dedent('''
            position ( %s pose [ 1 2 0 30 ] velocity_bounds [ -1 1 0 0 0 0 -180 180 ]
                       ranger ( sensor ( samples 2 ) ) )
            model ( size [ 0.1 0.1 0.1 ] pose [ 9 9 0 0 ] )
        ''' % robot_props))
    return load_world(path)


def _drive(sim, v, w, steps):
    frame = None
    for _ in range(steps):
        sim.set_command(0, v, w)
        frame = sim.step()
    return frame.robots[0]


def _closed_form(v, w, dt, steps, ex, ea):
    """Stage's odometry estimate after `steps` updates at (v, w), from (0, 0, 0)."""
    phi = w * dt * (1.0 + ea)
    if phi == 0.0:
        along = complex(steps, 0.0)
    else:   # the geometric sum of exp(i*k*phi), k = 1..steps
        along = cmath.exp(1j * phi) * (1.0 - cmath.exp(1j * steps * phi)) \
            / (1.0 - cmath.exp(1j * phi))
    p = v * dt * (1.0 + ex) * along
    return p.real, p.imag, steps * phi


@pytest.mark.parametrize('v, w, steps', [(0.19, 0.49, 37), (0.1, -0.3, 55), (0.15, 0.0, 20)])
def test_odom_estimate_is_the_closed_form_of_scaled_turn_then_advance(tmp_path, v, w, steps):
    world = _world(tmp_path, 'localization "odom" odom_error [ 0.03 0.01 0 2.0 ]')
    robot = _drive(Simulation(world), v, w, steps)
    x, y, yaw = _closed_form(v, w, 0.1, steps, 0.03, math.radians(2.0))
    assert (robot.odom.x, robot.odom.y) == pytest.approx((x, y), abs=1e-12)
    assert math.cos(robot.odom.yaw - yaw) == pytest.approx(1.0, abs=1e-15)
    assert (robot.odom.vx, robot.odom.wz) == (v, w)    # the twist is the true velocity


def test_odom_error_angle_is_read_in_the_worlds_angle_unit(tmp_path):
    degrees = _world(tmp_path, 'localization "odom" odom_error [ 0 0 0 2.0 ]')
    assert degrees.robots[0].odom_error == pytest.approx((0.0, 0.0, math.radians(2.0)))
    radians = load_world(_write(tmp_path, 'unit_angle "radians"\n'
                                'position ( localization "odom" odom_error [ 0 0 0 0.5 ] )\n'))
    assert radians.robots[0].odom_error == pytest.approx((0.0, 0.0, 0.5))


def _write(tmp_path, text):
    path = os.path.join(str(tmp_path), 'r.world')
    with open(path, 'w') as stream:
        stream.write(text)
    return path


def test_odom_drifts_from_ground_truth_while_gps_reports_it(tmp_path):
    drifting = Simulation(_world(tmp_path, 'localization "odom" odom_error [ 0.02 0.02 0 1.0 ]'))
    exact = Simulation(_world(tmp_path, 'localization "gps"'))
    _drive(exact, 0.19, 0.49, 99)
    before = exact.robots[0].pose
    gps = _drive(exact, 0.19, 0.49, 1)
    assert (gps.odom.x, gps.odom.y, gps.odom.yaw) == before   # the pose before the move
    robot = _drive(drifting, 0.19, 0.49, 100)
    truth = robot.ground_truth
    assert (truth.x, truth.y) == (gps.ground_truth.x, gps.ground_truth.y)
    # odom counts from the start pose and is off by the integrated scale errors.
    sx, sy, syaw = drifting.robots[0].start_pose
    c, s = math.cos(syaw), math.sin(syaw)
    true_x = c * (truth.x - sx) + s * (truth.y - sy)
    true_y = -s * (truth.x - sx) + c * (truth.y - sy)
    assert math.hypot(robot.odom.x - true_x, robot.odom.y - true_y) > 0.01
    assert abs(robot.odom.yaw - (truth.yaw - syaw)) > math.radians(0.5)


def test_reset_and_teleport_move_the_robot_but_not_its_dead_reckoning(tmp_path):
    # stageros' reset_positions (and Stage's SetPose) set the true pose only.
    sim = Simulation(_world(tmp_path, 'localization "odom" odom_error [ 0.03 0.01 0 2.0 ]'))
    before = _drive(sim, 0.19, 0.49, 30).odom
    sim.reset()
    sim.teleport(0, (2.0, 2.0, 1.0))
    after = _drive(sim, 0.0, 0.0, 1).odom
    assert (after.x, after.y, after.yaw) == (before.x, before.y, before.yaw)
    assert sim.robots[0].pose == (2.0, 2.0, 1.0)


def test_without_odom_error_stage_draws_one_within_half_its_maxima(tmp_path):
    world = _world(tmp_path, 'localization "odom"')
    errors = np.array([Simulation(world, seed=seed).robots[0].odom_error for seed in range(50)])
    assert DEFAULT_ODOM_ERROR_LIMITS == (0.015, 0.015, 0.025)
    assert np.all(np.abs(errors) <= DEFAULT_ODOM_ERROR_LIMITS)
    assert np.all(np.abs(errors).max(axis=0) > 0.8 * np.array(DEFAULT_ODOM_ERROR_LIMITS))
    assert np.all(errors.std(axis=0) > 0.003)


@pytest.mark.parametrize('name', ['room', 'arena', 'obstacles'])
def test_each_shipped_world_has_an_odom_variant_with_the_same_geometry(name):
    base = load_world(os.path.join(WORLDS, name + '.world'))
    variant = load_world(os.path.join(WORLDS, name + '_odom.world'))
    assert base.robots[0].localization == 'gps'
    assert variant.robots[0].localization == 'odom'
    assert variant.robots[0].odom_error == pytest.approx((0.02, 0.02, math.radians(1.0)))
    assert variant.robots[0]._replace(localization='gps', odom_error=None) == base.robots[0]
    assert len(variant.obstacles) == len(base.obstacles)
    for mine, theirs in zip(variant.obstacles, base.obstacles):
        assert mine.pose == theirs.pose and np.array_equal(mine.edges, theirs.edges)
