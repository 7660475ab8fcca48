"""Raytracing against real Stage's recordings, analytic walls and Stage's measured quirks.

Two kinds of oracle, and nothing else:

* Real Stage. test/data/stage_reference holds scans that Stage 4.3 recorded at
  exact poses (see its README). test_sim_stage_reference.py checks every beam
  through the engine; here stage_ranges itself is given the engine's inputs for
  chosen beams (those along and just off the axes, where the cell path has no
  or few minor steps and quantisation shows most) and must give what Stage
  recorded, and facts the recordings show are checked on them.
* Geometry. Stage's grid is only as good as its rasterisation: axis-aligned
  walls are exact cells, while a rotated edge drawn between floored vertices
  lies up to about 1.5 cells off the true line, so rotated walls get
  correspondingly wider bounds. On top of that come the quirks the reference
  README documents: a hit lies up to a cell behind the surface, a beam along an
  axis reads whole cells until it flies over an empty region, a miss reads
  range_max exactly with intensity 0, and the Manhattan budget falls a little
  short of range_max.
"""
import json
import math
import os
import textwrap

import numpy as np
import pytest

from cell_geometry import exact_ranges
from wall_follower.sim import engine
from wall_follower.sim.engine import Simulation
from wall_follower.sim.grid import OccupancyGrid, footprint_cells
from wall_follower.sim.raytrace import stage_beam_angles, stage_ranges
from wall_follower.sim.worldfile import load_world

REFERENCE = os.path.join(os.path.dirname(__file__), '..', 'data', 'stage_reference')
WORLDS = ('ref_room', 'ref_shapes', 'ref_lidar270', 'ref_lidar270_yaw', 'ref_margin')
# Recorded ranges are float32 rounded to 4 decimals.
RANGE_ROUNDING = 5.1e-5
# A beam is "near an axis" within this angle of it.
NEAR_AXIS = math.radians(3.0)


def _world(tmp_path, text, name='w.world'):
    path = os.path.join(str(tmp_path), name)
    with open(path, 'w') as stream:
        stream.write(textwrap.dedent(text))
    return load_world(path)


def _recorded_scans(name, monkeypatch):
    """[(snapshot, stage_ranges arguments)]: what the engine traces at each recorded pose."""
    with open(os.path.join(REFERENCE, name + '.json')) as stream:
        reference = json.load(stream)
    world = load_world(os.path.join(REFERENCE, name + '.world'))
    calls = []

    def traced(*args, **kwargs):
        calls.append((args, kwargs))
        return stage_ranges(*args, **kwargs)

    monkeypatch.setattr(engine, 'stage_ranges', traced)
    scans = []
    for snapshot in reference['snapshots']:
        gt = snapshot['gt']
        Simulation(world, poses={0: (gt['x'], gt['y'], gt['yaw'])}).step()
        (call,) = calls
        scans.append((snapshot, call))
        del calls[:]
    return scans, reference['scan_header'], reference['world']['resolution']


def _axis_offsets(angles):
    """Angle between each beam and the nearest axis direction."""
    return np.abs(np.remainder(angles + math.pi / 4, math.pi / 2) - math.pi / 4)


@pytest.mark.parametrize('name', WORLDS)
def test_beams_near_the_axes_equal_real_stage_when_traced_on_their_own(name, monkeypatch):
    scans, _, _ = _recorded_scans(name, monkeypatch)
    exactly_along = 0
    for snapshot, ((grid, x, y, angles, range_max), options) in scans:
        near = np.nonzero(_axis_offsets(angles) < NEAR_AXIS)[0]
        assert len(near) >= 4 * 2
        ranges, intensities = stage_ranges(grid, x, y, angles[near], range_max, **options)
        label = '%s snapshot %d' % (name, snapshot['id'])
        expected = np.array(snapshot['ranges'])[near]
        assert np.all(np.abs(ranges - expected) <= RANGE_ROUNDING), label
        assert np.array_equal(intensities, np.array(snapshot['intensities'])[near]), label
        exactly_along += np.count_nonzero(_axis_offsets(angles[near]) < 1e-6)
    assert exactly_along > 0


def test_along_an_axis_stage_reads_whole_cells_within_reach_of_a_wall(monkeypatch):
    """Beams along an axis (their cell paths have no minor step), from a laser less than a
    region (32 cells) from the wall they read: real Stage reads a whole number of cells
    travelled along the axis, and so does the simulator."""
    checked = 0
    for name in ('ref_room', 'ref_shapes', 'ref_lidar270', 'ref_lidar270_yaw'):
        scans, _, resolution = _recorded_scans(name, monkeypatch)
        for snapshot, ((grid, x, y, angles, range_max), options) in scans:
            offset = _axis_offsets(angles)
            along = np.sin(offset) * range_max / resolution < 1.0
            recorded = np.array(snapshot['ranges'])
            close = np.nonzero(along & (recorded < 32 * resolution))[0]
            travelled = recorded[close] * np.cos(offset[close])
            cells = np.round(travelled / resolution)
            assert np.all(np.abs(travelled - cells * resolution) <= RANGE_ROUNDING)
            ranges, _ = stage_ranges(grid, x, y, angles[close], range_max, **options)
            along_axis = ranges * np.cos(offset[close])
            assert along_axis == pytest.approx(cells * resolution, abs=1e-9)
            checked += len(close)
    assert checked >= 8


def test_a_flight_over_empty_regions_restarts_the_cell_count(tmp_path):
    """Along x, from a fractional start: whole cells near the wall (its region holds the
    laser), but from far away the beam flies to a region border and counts from there."""
    world = _world(tmp_path, '''
        resolution 0.02
        model ( size [ 0.1 4 1 ] pose [ 3.05 0 0 0 ] )
    ''')
    grid = OccupancyGrid.from_world(world)
    # the reference README's examples: 0.108 m from a wall reads 0.12, 0.132 m reads 0.14
    for distance, reading in ((0.108, 0.12), (0.132, 0.14)):
        near, _ = stage_ranges(grid, 3.0 - distance, 0.01, [0.0], 5.0)
        assert near[0] == pytest.approx(reading)
    far, _ = stage_ranges(grid, 0.003, 0.01, [0.0], 5.0)
    assert far[0] == pytest.approx(3.0 - 0.003, abs=1e-9)


def test_walls_just_inside_range_max_can_be_out_of_reach_as_in_stage(monkeypatch):
    """Real Stage reads range_max, intensity 0, for some walls a little closer than that
    (23 of 4320 ref_room beams); the simulator reads the same for each of them."""
    scans, header, _ = _recorded_scans('ref_room', monkeypatch)
    short = 0
    for snapshot, ((grid, x, y, angles, range_max), options) in scans:
        recorded = np.array(snapshot['ranges'])
        missed = np.nonzero((recorded == header['range_max']) &
                            (exact_ranges(grid, x, y, angles, range_max) < range_max - 0.02))[0]
        assert np.array_equal(np.array(snapshot['intensities'])[missed], np.zeros(len(missed)))
        ranges, intensities = stage_ranges(grid, x, y, angles[missed], range_max, **options)
        assert np.all(ranges == range_max) and np.all(intensities == 0.0)
        short += len(missed)
    assert short >= 10


def test_the_budget_runs_out_a_little_short_of_range_max(tmp_path):
    """Each flight costs its Manhattan length rounded up, so flying over empty regions
    along x loses up to a cell per region: at 3.5 m range a wall at 3.39 m is seen, one
    at 3.41 m is not (the README's band: walls from ~3.41 m may read 3.5)."""
    readings = []
    for wall in (3.40, 3.42, 3.44):
        world = _world(tmp_path, '''
            resolution 0.02
            model ( size [ 0.1 4 1 ] pose [ %g 0 0 0 ] )
        ''' % (wall + 0.05))
        grid = OccupancyGrid.from_world(world)
        readings.append(stage_ranges(grid, 0.01, 0.013, [0.0], 3.5))
    assert readings[0][0][0] == pytest.approx(3.39) and readings[0][1][0] == 1.0
    for ranges, intensities in readings[1:]:
        assert ranges[0] == 3.5 and intensities[0] == 0.0


def test_cells_are_the_position_truncated_towards_zero(tmp_path):
    """Stage looks at the cell of the position truncated towards zero (C's double to
    int): from x = -0.01 a beam along +y follows cell column 0, not -1."""
    world = _world(tmp_path, '''
        resolution 0.02
        model ( size [ 0.0199 1.0 1 ] pose [ -0.01005 1.0 0 0 ] )
    ''')
    grid = OccupancyGrid.from_world(world)
    assert list(np.unique(np.nonzero(grid.occupied)[1] + grid.ix0)) == [-1]
    # the wall column is x in [-0.02, 0): geometry hits it from x = -0.01, Stage does not
    assert exact_ranges(grid, -0.01, 0.0, [math.pi / 2], 3.5)[0] == pytest.approx(0.5)
    assert stage_ranges(grid, -0.01, 0.0, [math.pi / 2], 3.5)[0][0] == 3.5
    # from x = -0.03 (truncated to column -1) Stage follows the wall's column
    assert stage_ranges(grid, -0.03, 0.0, [math.pi / 2], 3.5)[0][0] == pytest.approx(0.5)


def test_axis_aligned_walls_within_one_cell():
    world = load_world(os.path.join(REFERENCE, 'ref_room.world'))
    grid = OccupancyGrid.from_world(world)
    res = grid.resolution
    rng = np.random.RandomState(3)
    for _ in range(40):
        x, y = rng.uniform(0.05, 1.7, 2) * rng.choice([-1, 1], 2)
        angles = rng.uniform(-math.pi, math.pi, 100)
        dirs = np.stack([np.cos(angles), np.sin(angles)], axis=1)
        with np.errstate(divide='ignore'):
            to_x = np.where(dirs[:, 0] > 0, 1.9 - x, -1.9 - x) / dirs[:, 0]
            to_y = np.where(dirs[:, 1] > 0, 1.9 - y, -1.9 - y) / dirs[:, 1]
        walls = np.minimum(np.abs(to_x), np.abs(to_y))
        # the perpendicular distance of the hit point from the wall it hit
        x_face = np.abs(to_x) < np.abs(to_y)
        normal = np.where(x_face, np.abs(dirs[:, 0]), np.abs(dirs[:, 1]))
        check = (np.abs(np.abs(to_x) - np.abs(to_y)) > 0.1) & (walls < 3.3)
        stage_depth = (stage_ranges(grid, x, y, angles, 3.5)[0] - walls) * normal
        exact_depth = (exact_ranges(grid, x, y, angles, 3.5) - walls) * normal
        # Stage's range is the major-axis projection of a walk that strays up to a cell
        # from the ray, so its hit point may sit a little over one cell off (real Stage:
        # within 0.022 m at 0.02 m cells in this room) ...
        assert np.all(np.abs(stage_depth[check]) <= 1.1 * res + 1e-9)
        assert np.all(np.abs(exact_depth[check]) <= res + 1e-9)
        # ... and a wall across the beam's major axis is read at most a cell behind its
        # surface, never in front of it.
        head_on = check & (x_face == (np.abs(dirs[:, 0]) > np.abs(dirs[:, 1])))
        assert np.all(stage_depth[head_on] >= -1e-9)
        assert np.all(stage_depth[head_on] < res)


@pytest.mark.parametrize('yaw_deg', [30, -20, 63, 8])
def test_rotated_wall_against_the_analytic_face(tmp_path, yaw_deg):
    res = 0.02
    world = _world(tmp_path, '''
        resolution %g
        model ( name "wall" size [ 3.0 0.3 0.5 ] pose [ 3 3 0 %d ] )
    ''' % (res, yaw_deg))
    grid = OccupancyGrid.from_world(world)
    yaw = math.radians(yaw_deg)
    normal = np.array([-math.sin(yaw), math.cos(yaw)])
    along = np.array([math.cos(yaw), math.sin(yaw)])
    face = np.array([3.0, 3.0]) - 0.15 * normal
    rng = np.random.RandomState(yaw_deg % 97)
    depths = {'stage': [], 'exact': []}
    errors = {'stage': [], 'exact': []}
    for _ in range(60):
        origin = face - normal * rng.uniform(0.2, 1.3) + along * rng.uniform(-0.8, 0.8)
        angles = math.atan2(normal[1], normal[0]) + rng.uniform(-math.pi / 4, math.pi / 4, 40)
        dirs = np.stack([np.cos(angles), np.sin(angles)], axis=1)
        distance = (face - origin).dot(normal) / dirs.dot(normal)
        on_face = np.abs((origin + dirs * distance[:, None] - face).dot(along)) < 1.3
        measured = {'stage': stage_ranges(grid, origin[0], origin[1], angles, 5.0)[0],
                    'exact': exact_ranges(grid, origin[0], origin[1], angles, 5.0)}
        for key, ranges in measured.items():
            hits = origin + dirs * ranges[:, None]
            depths[key].extend((hits - face).dot(normal)[on_face])
            errors[key].extend(np.abs(ranges - distance)[on_face])
    stage_depth, exact_depth = np.array(depths['stage']), np.array(depths['exact'])
    # Stage's cells of the face lie within 1.5 cells of it; the exact traversal stops on
    # their boundary, Stage's walk up to a further cell away along its major axis.
    assert np.all(np.abs(exact_depth) <= 1.6 * res)
    assert np.all(np.abs(stage_depth) <= 2.5 * res)
    assert np.median(np.abs(errors['exact'])) <= res
    assert np.median(np.abs(errors['stage'])) <= res


def test_exact_ranges_are_the_distance_to_the_first_occupied_cell(tmp_path):
    world = _world(tmp_path, '''
        resolution 0.05
        model ( size [ 0.5 0.5 1 ] pose [ 1.0 0.0 0 0 ] )
    ''')
    grid = OccupancyGrid.from_world(world)
    # cells of the box's near face x = 0.75 are [0.75, 0.8): the ray along +x stops at 0.75
    assert exact_ranges(grid, 0.013, 0.01, [0.0], 5.0)[0] == pytest.approx(0.75 - 0.013)
    # the far face x = 1.25 is drawn into cells [1.25, 1.3), seen from behind at 1.3
    assert exact_ranges(grid, 2.0, 0.01, [math.pi], 5.0)[0] == pytest.approx(2.0 - 1.3)
    # a miss reads range_max
    assert exact_ranges(grid, 0.0, 0.0, [math.pi / 2], 2.5)[0] == 2.5


def test_no_hit_reads_range_max_exactly_with_zero_intensity(tmp_path):
    world = _world(tmp_path, 'model ( size [ 0.2 0.2 1 ] pose [ 1 0 0 0 ] )\n')
    grid = OccupancyGrid.from_world(world)
    ranges, intensities = stage_ranges(grid, 0.0, 0.0, np.linspace(2.0, 4.0, 20), 3.5)
    assert np.all(ranges == 3.5) and np.all(intensities == 0.0)


def test_intensity_is_the_ranger_return_of_the_model_hit(tmp_path):
    world = _world(tmp_path, '''
        model ( size [ 0.2 2 1 ] pose [ 1 0 0 0 ] ranger_return 0.5 )
        model ( size [ 0.2 2 1 ] pose [ -1 0 0 0 ] )
        model ( size [ 2 0.2 1 ] pose [ 0 1 0 0 ] ranger_return 0 )
        model ( size [ 2 0.2 1 ] pose [ 0 -1 0 0 ] ranger_return -1 )
    ''')
    grid = OccupancyGrid.from_world(world)
    ranges, intensities = stage_ranges(grid, 0.01, 0.01, [0.0, math.pi, math.pi / 2,
                                                          -math.pi / 2], 3.0)
    assert list(intensities) == [0.5, 1.0, 0.0, 0.0]
    assert ranges[2] < 1.0          # ranger_return 0 is still hit, with intensity 0
    assert ranges[3] == 3.0         # ranger_return -1 is invisible to rangers


def test_beams_pass_over_obstacles_lower_than_the_laser(tmp_path):
    world = _world(tmp_path, '''
        model ( size [ 0.2 2 0.1 ] pose [ 1 0 0 0 ] )
        model ( size [ 0.2 2 0.5 ] pose [ 2 0 0 0 ] )
    ''')
    grid = OccupancyGrid.from_world(world)
    high, _ = stage_ranges(grid, 0.01, 0.01, [0.0], 3.0, height=0.2)
    low, _ = stage_ranges(grid, 0.01, 0.01, [0.0], 3.0, height=0.05)
    assert 1.85 < high[0] < 1.95 and 0.85 < low[0] < 0.95


def test_other_robots_are_seen_and_the_own_body_is_not(tmp_path):
    world = _world(tmp_path, '''
        model ( size [ 0.2 4 1 ] pose [ 2 0 0 0 ] )
        position ( size [ 0.4 0.4 0.2 ] pose [ 0 0 0 0 ] ranger ( sensor ( samples 2 ) ) )
        position ( size [ 0.4 0.4 0.2 ] pose [ 1 0 0 0 ] ranger ( sensor ( samples 2 ) ) )
    ''')
    grid = OccupancyGrid.from_world(world)
    me, other = world.robots
    own = [footprint_cells(me, me.pose, grid.ppm)]
    xs, ys = footprint_cells(other, other.pose, grid.ppm)
    alone, _ = stage_ranges(grid, 0.01, 0.01, [0.0], 3.0, robot_cells=own)
    together, seen = stage_ranges(grid, 0.01, 0.01, [0.0], 3.0, robot_cells=own,
                                  other_cells=[(xs, ys, 1.0)])
    assert 1.85 < alone[0] < 1.95
    assert 0.75 < together[0] < 0.85 and seen[0] == 1.0


def test_stage_beam_angles_are_a_float32_running_sum():
    angles = stage_beam_angles(-math.pi, 2 * math.pi / 359, 360)
    value = np.float32(-math.pi)
    for angle in angles:
        assert angle == float(value)
        value = np.float32(float(value) + np.float32(2 * math.pi / 359))


def test_a_robot_out_of_reach_changes_no_beam():
    # Another robot far off the grid is neither drawn onto it nor walked to, though its
    # region is populated: every beam, with and without it, the same bit for bit.
    world = load_world(os.path.join(REFERENCE, 'ref_room.world'))
    sim = Simulation(world)
    grid = sim.grid
    spec = sim.robots[0].spec
    far = (np.array([400, 401]), np.array([400, 400]), 1.0)
    angles = stage_beam_angles(-math.pi, 2 * math.pi / 359, 360)
    rng = np.random.RandomState(3)
    for x, y, yaw in zip(rng.uniform(-1.5, 1.5, 8), rng.uniform(-1.5, 1.5, 8),
                         rng.uniform(-math.pi, math.pi, 8)):
        own = [footprint_cells(spec, (x, y, yaw), grid.ppm)]
        alone = stage_ranges(grid, x, y, angles + yaw, 3.5, robot_cells=own)
        with_far = stage_ranges(grid, x, y, angles + yaw, 3.5, robot_cells=own,
                                other_cells=[far])
        assert np.array_equal(alone[0], with_far[0])
        assert np.array_equal(alone[1], with_far[1])
