"""The world step: timing, odometry, watchdog, collisions, reset, laser profiles."""
import math
import os
import textwrap

import numpy as np
import pytest

from cell_geometry import footprint_clearance
from wall_follower.sim.engine import Simulation
from wall_follower.sim.grid import footprint_collides
from wall_follower.sim.worldfile import load_world

REFERENCE = os.path.join(os.path.dirname(__file__), '..', 'data', 'stage_reference')


def _room():
    return load_world(os.path.join(REFERENCE, 'ref_room.world'))


def _world(tmp_path, text):
    path = os.path.join(str(tmp_path), 'w.world')
    with open(path, 'w') as stream:
        stream.write(textwrap.dedent(text))
    return load_world(path)


def _drive(sim, v, w, steps, index=0):
    frames = []
    for _ in range(steps):
        sim.set_command(index, v, w)
        frames.append(sim.step())
    return frames


def test_each_step_advances_interval_sim_and_stamps_the_frame():
    sim = Simulation(_room())
    assert sim.time == 0.0 and sim.dt == 0.1
    stamps = [sim.step().stamp for _ in range(3)]
    assert stamps == pytest.approx([0.1, 0.2, 0.3])
    assert sim.time == pytest.approx(0.3)


def test_a_command_drives_from_the_next_update_and_odom_lags_one_update():
    sim = Simulation(_room())
    start = sim.robots[0].pose
    assert sim.step().robots[0].ground_truth.vx == 0.0   # no earlier pose to differ from
    sim.set_command(0, 0.19, 0.0)
    first = sim.step().robots[0]
    second = sim.step().robots[0]
    heading = start[2]
    assert first.ground_truth.x == pytest.approx(start[0] + 0.019 * math.cos(heading))
    assert (first.odom.x, first.odom.y) == start[:2]                   # pose before the move
    assert (second.odom.x, second.odom.y) == (first.ground_truth.x, first.ground_truth.y)
    assert (first.odom.vx, first.odom.wz) == (0.19, 0.0)               # commanded twist
    assert first.ground_truth.vx == pytest.approx(0.19 * math.cos(heading))  # world frame
    assert first.ground_truth.vy == pytest.approx(0.19 * math.sin(heading))


def test_scan_is_raytraced_before_the_move():
    sim = Simulation(_room())
    still = sim.step().robots[0].scan.ranges
    sim.set_command(0, 0.19, 0.0)
    moving = sim.step().robots[0].scan.ranges
    assert np.array_equal(still, moving)
    assert not np.array_equal(moving, sim.step().robots[0].scan.ranges)


def test_watchdog_stops_a_single_command_after_two_updates():
    sim = Simulation(_room())
    sim.set_command(0, 0.19, 0.0)
    moved = []
    for _ in range(6):
        before = sim.robots[0].pose
        sim.step()
        moved.append(sim.robots[0].pose != before)
    assert moved == [True, True, False, False, False, False]


def test_watchdog_timeout_is_configurable_and_zero_disables_it():
    slow = Simulation(_room(), watchdog_timeout=0.5)
    off = Simulation(_room(), watchdog_timeout=0.0)
    for sim, expected in ((slow, 5), (off, 20)):
        sim.set_command(0, 0.1, 0.0)
        poses = []
        for _ in range(20):
            sim.step()
            poses.append(sim.robots[0].pose)
        assert len(set(poses)) == expected


def test_a_robot_held_still_is_driven_as_a_moving_one():
    # A lockstep simulator waits for the next command of a driven robot: one
    # its controller holds still, answering every step, is waited for as much
    # as a moving one, so that its move off is not late by however busy the
    # machine is.
    sim = Simulation(_room())
    assert sim.driven() == [False]          # nothing has commanded it yet
    driven = []
    for _ in range(4):
        sim.set_command(0, 0.0, 0.0)
        sim.step()
        driven.append(sim.driven()[0])
    assert driven == [False, True, True, True]
    sim.step()                              # its controller fell silent
    assert sim.driven() == [False]
    sim.set_command(0, 0.1, 0.0)
    assert sim.driven() == [True]


def test_a_last_stop_is_not_waited_for():
    # A controller that ends with a stop, sent once or a few times at once,
    # and goes quiet is not held for: each such end would cost a time-out.
    sim = Simulation(_room())
    sim.set_command(0, 0.1, 0.0)
    sim.step()
    for _ in range(3):
        sim.set_command(0, 0.0, 0.0)
    driven = []
    for _ in range(3):
        sim.step()
        driven.append(sim.driven()[0])
    assert driven == [False, False, False]


def test_velocity_bounds_are_honoured():
    sim = Simulation(_room())    # Stage's default bounds: 1 m/s, 90 deg/s
    sim.step()
    sim.set_command(0, 0.0, 2.84)
    frame = sim.step().robots[0]
    assert frame.odom.wz == pytest.approx(math.pi / 2)
    assert frame.ground_truth.wz == pytest.approx(math.pi / 2)


def test_driving_into_a_wall_stops_without_penetration():
    sim = Simulation(_room(), poses={0: (1.5, 0.3, math.radians(10))})
    spec = sim.robots[0].spec
    frames = _drive(sim, 0.19, 0.0, 60)
    stalled = [f.robots[0].stalled for f in frames]
    assert stalled[-1] and not stalled[0]
    first_stall = stalled.index(True)
    assert all(stalled[first_stall:])
    resting = frames[first_stall].robots[0].ground_truth
    for frame in frames[first_stall:]:
        gt = frame.robots[0].ground_truth
        assert (gt.x, gt.y, gt.yaw) == (resting.x, resting.y, resting.yaw)
        assert frame.robots[0].odom.vx == 0.19
    for frame in frames:
        gt = frame.robots[0].ground_truth
        assert not footprint_collides(sim.grid, spec, (gt.x, gt.y, gt.yaw))
        assert footprint_clearance(sim.grid, spec, (gt.x, gt.y, gt.yaw)) >= 0.0
    # it stopped within one step of the wall, and backing off is not latched
    assert footprint_clearance(sim.grid, spec, (resting.x, resting.y, resting.yaw)) < 0.019
    back = _drive(sim, -0.19, 0.0, 3)
    assert not back[-1].robots[0].stalled
    assert back[-1].robots[0].ground_truth.x < resting.x


def test_turning_against_a_wall_is_blocked_too():
    # side-on, 3 mm from the wall: turning left swings the rear-right corner 5 mm out
    x = 1.9 - 0.089 - 0.003
    sim = Simulation(_room(), poses={0: (x, 0.0, math.pi / 2)})
    frame = _drive(sim, 0.0, 0.5, 1)[0].robots[0]
    assert frame.stalled
    assert (frame.ground_truth.x, frame.ground_truth.yaw) == (x, math.pi / 2)
    assert not _drive(sim, 0.0, -0.5, 1)[0].robots[0].stalled   # turning right is free


def test_reset_restores_start_poses_and_clears_command_and_stall():
    sim = Simulation(_room(), poses={0: (1.7, 0.0, 0.0)})
    _drive(sim, 0.19, 0.0, 10)
    assert sim.robots[0].stalled
    sim.set_command(0, 0.19, 0.0)
    sim.reset()
    assert sim.robots[0].pose == (1.7, 0.0, 0.0)
    assert not sim.robots[0].stalled
    frame = sim.step().robots[0]
    assert (frame.ground_truth.x, frame.ground_truth.y) == (1.7, 0.0)
    assert frame.odom.vx == 0.0


def test_teleport_moves_at_once_keeps_the_command_and_clears_the_stall():
    sim = Simulation(_room(), poses={0: (1.7, 0.0, 0.0)})
    _drive(sim, 0.19, 0.0, 10)
    assert sim.robots[0].stalled
    sim.teleport(0, (0.0, 0.5, 3.5))
    assert sim.robots[0].pose == pytest.approx((0.0, 0.5, 3.5 - 2 * math.pi))
    assert not sim.robots[0].stalled
    frame = _drive(sim, 0.19, 0.0, 2)[-1].robots[0]
    # Heading about -160 deg from the new pose: moving toward -x, off the wall.
    assert frame.ground_truth.x < 0.0
    assert not frame.stalled


def test_pose_override_replaces_the_world_start():
    sim = Simulation(_room(), poses={0: (0.2, -0.4, 4.0)})
    assert sim.robots[0].pose == pytest.approx((0.2, -0.4, 4.0 - 2 * math.pi))


def test_laser_mount_is_stageros_base_laser_link():
    frame = Simulation(_room()).step().robots[0]
    assert frame.laser == (-0.032, 0.0, 0.192, 0.0)


def _facing_wall(profile, seed=0):
    """A robot facing the +x wall with its laser 1.032 m from it."""
    sim = Simulation(_room(), laser_profile=profile, seed=seed, poses={0: (0.9, 0.0, 0.0)})
    return sim.step().robots[0].scan


def test_stage_profile_header():
    scan = _facing_wall('stage')
    assert (scan.angle_min, scan.angle_max) == pytest.approx((-math.pi, math.pi))
    assert scan.angle_increment == pytest.approx(2 * math.pi / 359)
    assert len(scan.ranges) == len(scan.intensities) == 360
    front = int(round((0.0 - scan.angle_min) / scan.angle_increment))
    assert scan.ranges[front] == pytest.approx(1.032, abs=0.02)
    assert scan.ranges[0] == pytest.approx(scan.ranges[-1], abs=1e-6)   # +-pi: same way


@pytest.mark.parametrize('profile', ['lds01', 'gazebo'])
def test_turtlebot_profiles_start_ahead_and_turn_counter_clockwise(profile):
    scan = _facing_wall(profile)
    assert scan.angle_min == 0.0 and len(scan.ranges) == 360
    assert scan.ranges[0] == pytest.approx(1.032, abs=0.05)        # ahead: the wall
    left = int(round(math.pi / 2 / scan.angle_increment))
    assert scan.ranges[left] == pytest.approx(1.9, abs=0.06)       # left: y = +1.9
    right = int(round(3 * math.pi / 2 / scan.angle_increment))
    assert scan.ranges[right] == pytest.approx(1.9, abs=0.06)


def test_lds01_reads_zero_for_no_return_and_drops_about_one_percent():
    world = _room()
    sim = Simulation(world, laser_profile='lds01', seed=3, poses={0: (0.0, 1.9 - 0.2, 0.0)})
    zeros = []
    for _ in range(30):
        scan = sim.step().robots[0].scan
        zeros.append(np.mean(scan.ranges == 0.0))
    # the wall 0.2 m to the left is in range everywhere; corners beyond 3.5 m are not
    assert 0.0 < np.mean(zeros) < 0.2
    scan = _facing_wall('lds01')
    invalid = scan.ranges == 0.0
    assert np.all(scan.intensities[invalid] == 0.0)
    assert np.all((scan.ranges[~invalid] >= 0.12) & (scan.ranges[~invalid] <= 3.5))


def test_lds01_drops_about_one_percent_of_returns():
    # in the middle of the 3.8 m room every beam has a return
    sim = Simulation(_room(), laser_profile='lds01', seed=5, poses={0: (0.0, 0.0, 0.0)})
    dropped = [np.mean(sim.step().robots[0].scan.ranges == 0.0) for _ in range(40)]
    assert 0.005 < np.mean(dropped) < 0.02


def test_gazebo_reads_inf_for_no_return():
    world = _room()
    sim = Simulation(world, laser_profile='gazebo', poses={0: (-1.5, -1.5, math.pi / 4)})
    scan = sim.step().robots[0].scan
    assert np.isinf(scan.ranges[0])                 # ahead: the far corner, beyond 3.5 m
    assert np.all(np.isfinite(scan.ranges[1:90]) | np.isinf(scan.ranges[1:90]))
    assert scan.angle_max == pytest.approx(6.28319)


@pytest.mark.parametrize('profile', ['lds01', 'gazebo'])
def test_noise_has_the_turtlebot_sigma_and_is_seeded(profile):
    world = _room()
    pose = {0: (0.0, 0.0, 0.3)}
    a, b, c = (Simulation(world, laser_profile=profile, seed=seed, poses=pose)
               .step().robots[0].scan.ranges for seed in (11, 11, 12))
    assert np.array_equal(a, b)
    assert not np.array_equal(a, c)
    valid = (a > 0) & (c > 0) & np.isfinite(a) & np.isfinite(c)
    # two independent draws on the same beams differ with sigma * sqrt(2)
    assert np.std((a - c)[valid]) / math.sqrt(2) == pytest.approx(0.01, rel=0.25)


@pytest.mark.parametrize('profile', ['lds01', 'lds02'])
def test_steps_on_which_nobody_drives_leave_the_runs_noise_where_it_was(profile):
    # A lockstep simulator steps by the wall clock while nobody drives, so how
    # many such steps pass before a controller starts depends on the machine.
    # Their scans are all alike, and the lap that follows meets the same noise
    # (lds02 draws its beam count too) however many passed.
    world = _room()

    def lap(idle_steps):
        sim = Simulation(world, laser_profile=profile, seed=5, poses={0: (0.0, 0.0, 0.3)})
        idle = [sim.step(idle=True).robots[0].scan.ranges for _ in range(idle_steps)]
        return idle, [frame.robots[0].scan.ranges for frame in _drive(sim, 0.1, 0.2, 5)]

    _, driven_at_once = lap(0)
    waits, driven_later = lap(3)
    assert all(np.array_equal(waits[0], ranges) for ranges in waits[1:])
    assert all(np.array_equal(a, b) for a, b in zip(driven_at_once, driven_later))
    assert not np.array_equal(waits[0], driven_later[0])    # noisy too, by a stream of their own


def test_two_robots_see_and_block_each_other(tmp_path):
    world = _world(tmp_path, '''
        define bot position ( size [ 0.2 0.2 0.2 ] ranger ( sensor ( range [ 0 3 ] fov 360
                                                                     samples 361 ) ) )
        model ( size [ 0.1 4 0.5 ] pose [ 2 0 0 0 ] )
        bot ( name "a" pose [ 0 0 0 0 ] )
        bot ( name "b" pose [ 0.6 0 0 180 ] )
    ''')
    sim = Simulation(world)
    frame = sim.step()
    assert [r.name for r in frame.robots] == ['a', 'b']
    ahead = frame.robots[0].scan
    front = int(round((0.0 - ahead.angle_min) / ahead.angle_increment))
    assert ahead.ranges[front] == pytest.approx(0.5, abs=0.03)    # b's rear face at 0.5
    for _ in range(20):
        sim.set_command(0, 0.2, 0.0)
        frame = sim.step()
    a, b = sim.robots
    assert frame.robots[0].stalled
    assert b.pose == (0.6, 0.0, math.pi)
    assert 0.6 - a.pose[0] >= 0.2 - 1e-9     # bodies do not overlap


def test_odom_localization_dead_reckons_from_zero(tmp_path):
    world = _world(tmp_path, '''
        position ( localization "odom" odom_error [ 0.1 0 0 0 ] pose [ 1 1 0 90 ]
                   ranger ( sensor ( samples 2 ) ) )
        model ( size [ 0.1 0.1 0.1 ] pose [ 3 3 0 0 ] )
    ''')
    sim = Simulation(world)
    frames = _drive(sim, 0.5, 0.0, 10)
    odom = frames[-1].robots[0].odom
    gt = frames[-1].robots[0].ground_truth
    assert (gt.x, gt.y) == pytest.approx((1.0, 1.5))
    assert (odom.x, odom.y, odom.yaw) == pytest.approx((0.55, 0.0, 0.0))   # 10 % long
