"""The compiled raytrace (src/stage_raytrace.c) against the numpy one, beam for beam.

Both follow the same model of Stage's beam; the numpy one is checked against
real Stage's recordings in test_sim_stage_reference.py (as is the compiled one)
and test_sim_raytrace.py. Here they must agree on every beam of random scans,
from anywhere in and around each shipped and reference world, with robot
bodies in the way: the same intensity and the same range up to the last bits
(C moves its position by a running sum of cell steps, as Stage does, and numpy
by whole numbers of steps at once).
"""
import glob
import math
import os

import numpy as np
import pytest

from wall_follower.sim import compiled_raytrace
from wall_follower.sim.engine import Simulation
from wall_follower.sim.grid import footprint_cells
from wall_follower.sim.raytrace import stage_ranges
from wall_follower.sim.worldfile import load_world

HERE = os.path.dirname(__file__)
WORLDS = sorted(glob.glob(os.path.join(HERE, '..', '..', 'worlds', '*.world')) +
                glob.glob(os.path.join(HERE, '..', 'data', 'stage_reference', '*.world')))
AXES = np.array([0.0, math.pi / 2, -math.pi / 2, math.pi, -math.pi, math.pi / 4, -3 * math.pi / 4])
# Far below a cell (0.02 m): only the last bits of a double may differ.
LAST_BITS = 1e-12


def test_the_library_is_built_and_found():
    assert compiled_raytrace.available(), compiled_raytrace.NOT_FOUND


@pytest.mark.parametrize('path', WORLDS, ids=lambda p: os.path.basename(p))
def test_both_implementations_trace_the_same_beams(path):
    sim = Simulation(load_world(path))
    grid = sim.grid
    spec = sim.robots[0].spec
    low = np.array([grid.ix0, grid.iy0]) / grid.ppm
    high = low + np.array(grid.occupied.shape[::-1]) / grid.ppm
    rng = np.random.default_rng(7)
    beams = differ = 0
    for scan in range(60):
        x, y = rng.uniform(low - 0.5, high + 0.5)
        angles = np.concatenate([AXES, rng.uniform(-math.pi, math.pi, 353)])
        body = footprint_cells(spec, (x, y, rng.uniform(-math.pi, math.pi)), grid.ppm)
        other = footprint_cells(spec, tuple(rng.uniform(low, high)) + (0.0,), grid.ppm)
        options = dict(robot_cells=[body])
        if scan % 2:
            options['other_cells'] = [other + (2.0,)]
        numpy_ranges, numpy_intensities = stage_ranges(grid, x, y, angles, 3.5,
                                                       implementation='numpy', **options)
        ranges, intensities = stage_ranges(grid, x, y, angles, 3.5,
                                           implementation='compiled', **options)
        assert np.array_equal(intensities, numpy_intensities)
        assert np.all(np.abs(ranges - numpy_ranges) <= LAST_BITS)
        beams += len(angles)
        differ += np.count_nonzero(ranges != numpy_ranges)
    assert differ <= 0.01 * beams


def test_an_unknown_implementation_is_an_error():
    grid = Simulation(load_world(WORLDS[0])).grid
    with pytest.raises(ValueError, match='fast'):
        stage_ranges(grid, 0.0, 0.0, [0.0], 3.5, implementation='fast')
