"""Raytracing against analytic walls and the measured quirks of Stage's raytrace.

The beam-for-beam oracle is real Stage itself: test_sim_stage_reference.py
compares every recorded beam. Here the oracle is geometry. Stage's grid is
only as good as its rasterisation: axis-aligned walls are exact cells, while
a rotated edge drawn between floored vertices lies up to about 1.5 cells off
the true line, so rotated walls get correspondingly wider bounds.
"""
import math
import os
import textwrap

import numpy as np
import pytest

from wall_follower.sim.grid import OccupancyGrid, footprint_cells
from wall_follower.sim.raytrace import exact_ranges, stage_beam_angles, \
    stage_ranges
from wall_follower.sim.worldfile import load_world

REFERENCE = os.path.join(os.path.dirname(__file__), '..', 'data', 'stage_reference')


def _world(tmp_path, text, name='w.world'):
    path = os.path.join(str(tmp_path), name)
    with open(path, 'w') as stream:
        stream.write(textwrap.dedent(text))
    return load_world(path)


def test_region_jumps_change_the_reading_as_in_stage(tmp_path):
    """A beam along x from a fractional start reads whole cells unless a jump re-anchors it."""
    world = _world(tmp_path, '''
        resolution 0.02
        model ( size [ 0.1 4 1 ] pose [ 3.05 0 0 0 ] )
    ''')
    grid = OccupancyGrid.from_world(world)
    # near the wall (same region): whole cells from the start, 0.108 m -> 0.12
    near, _ = stage_ranges(grid, 3.0 - 0.108, 0.01, [0.0], 5.0)
    assert near[0] == pytest.approx(0.12)
    # from far away the empty regions are jumped and the beam lands on a region border
    far, _ = stage_ranges(grid, 0.003, 0.01, [0.0], 5.0)
    assert far[0] == pytest.approx(3.0 - 0.003, abs=1e-9)


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
        normal = np.where(np.abs(to_x) < np.abs(to_y), np.abs(dirs[:, 0]), np.abs(dirs[:, 1]))
        away_from_corners = np.abs(np.abs(to_x) - np.abs(to_y)) > 0.1
        check = away_from_corners & (walls < 3.3)
        # Stage's range is the major-axis projection of a walk that strays up to a cell
        # from the ray, so its hit point may sit a little over one cell off (real Stage:
        # within 0.022 m at 0.02 m cells in this room).
        for ranges, bound in ((stage_ranges(grid, x, y, angles, 3.5)[0], 1.1 * res),
                              (exact_ranges(grid, x, y, angles, 3.5), res)):
            depth = (ranges - walls) * normal
            assert np.all(np.abs(depth[check]) <= bound + 1e-9)


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
