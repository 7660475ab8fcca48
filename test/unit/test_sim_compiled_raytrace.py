"""The raytrace library (src/stage_raytrace.c) against its scalar Python transliteration,
beam for beam, and what happens without the library.

Real Stage's recordings (test_sim_stage_reference.py) take every branch of the
loop but its guards for cells and regions beyond the tables, and only from poses
inside a world with one robot. Here the oracle, stage_raytrace_oracle.py, must
give the same bits on random scans from anywhere in and around each shipped and
reference world, off the grid too, with the own body and another robot in the
way and beams low enough to pass over some blocks.
"""
import glob
import math
import os
import subprocess
import sys

import numpy as np
import pytest

import stage_raytrace_oracle
from wall_follower.sim import compiled_raytrace
from wall_follower.sim.engine import Simulation
from wall_follower.sim.grid import footprint_cells
from wall_follower.sim.raytrace import stage_ranges
from wall_follower.sim.worldfile import load_world

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.join(HERE, os.pardir, os.pardir)
WORLDS = sorted(glob.glob(os.path.join(REPO, 'worlds', '*.world')) +
                glob.glob(os.path.join(HERE, '..', 'data', 'stage_reference', '*.world')))
SCANS = 20   # random scans per world
AXES = np.array([0.0, math.pi / 2, -math.pi / 2, math.pi, -math.pi, math.pi / 4, -3 * math.pi / 4])


def test_the_library_is_built_and_found():
    assert compiled_raytrace.available(), compiled_raytrace.MISSING


@pytest.mark.parametrize('path', WORLDS, ids=lambda p: os.path.basename(p))
def test_the_library_traces_every_beam_as_its_oracle(path, monkeypatch):
    traced = []
    library_trace = compiled_raytrace.trace

    def trace(tables, beams, x, y):
        readings = library_trace(tables, beams, x, y)
        traced.append(stage_raytrace_oracle.trace(tables, beams, x, y))
        return readings

    monkeypatch.setattr(compiled_raytrace, 'trace', trace)
    sim = Simulation(load_world(path))
    grid = sim.grid
    spec = sim.robots[0].spec
    low = np.array([grid.ix0, grid.iy0]) / grid.ppm
    high = low + np.array(grid.occupied.shape[::-1]) / grid.ppm
    rng = np.random.default_rng(7)
    hits = 0
    for scan in range(SCANS):
        x, y = rng.uniform(low - 1.0, high + 1.0)
        angles = np.concatenate([AXES, rng.uniform(-math.pi, math.pi, 353)])
        body = footprint_cells(spec, (x, y, rng.uniform(-math.pi, math.pi)), grid.ppm)
        other = footprint_cells(spec, tuple(rng.uniform(low, high)) + (0.0,), grid.ppm)
        # without a body at the laser, a beam can start beyond the populated regions
        options = dict(robot_cells=[body] if scan % 4 else [], height=(None, 0.05, 0.2)[scan % 3])
        if scan % 2:
            options['other_cells'] = [other + (2.0,)]
        ranges, intensities = stage_ranges(grid, x, y, angles, 3.5, **options)
        expected_ranges, expected_intensities = traced.pop()
        assert np.array_equal(ranges, expected_ranges), 'scan %d from (%g, %g)' % (scan, x, y)
        assert np.array_equal(intensities, expected_intensities), 'scan %d' % scan
        hits += np.count_nonzero(ranges < 3.5)
    assert hits > SCANS * len(AXES)


def _without_the_library():
    """This environment with no LD_LIBRARY_PATH entry that holds the library."""
    env = dict(os.environ)
    env['LD_LIBRARY_PATH'] = os.pathsep.join(
        entry for entry in env.get('LD_LIBRARY_PATH', '').split(os.pathsep)
        if entry and not os.path.exists(os.path.join(entry, compiled_raytrace.LIBRARY)))
    return env


def test_without_the_library_a_scan_says_how_to_build_it():
    probe = ('from wall_follower.sim import compiled_raytrace\n'
             'from wall_follower.sim.engine import Simulation\n'
             'from wall_follower.sim.worldfile import load_world\n'
             'try:\n'
             '    Simulation(load_world(%r)).step()\n'
             'except compiled_raytrace.LibraryMissing as error:\n'
             '    print(error)\n' % WORLDS[0])
    run = subprocess.run([sys.executable, '-c', probe], env=_without_the_library(),
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, universal_newlines=True)
    assert run.returncode == 0, run.stderr
    assert run.stdout.strip() == compiled_raytrace.MISSING
    assert compiled_raytrace.LIBRARY in run.stdout and 'catkin_make' in run.stdout


@pytest.mark.ros
def test_without_the_library_the_node_exits_with_an_error_not_a_traceback():
    run = subprocess.run([sys.executable, os.path.join(REPO, 'scripts', 'stage_sim'),
                          '--simulator', 'builtin', '-g', WORLDS[0]],
                         env=_without_the_library(), stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, universal_newlines=True, timeout=60)
    assert run.returncode == 1
    # The node's own words end its output. ROS may say something first, but
    # never a traceback (nor, since nodes/shared/rosdep_lookup.py, a request
    # for `rosdep init`: test_rosdep_lookup.py).
    assert run.stderr.splitlines()[-1] == 'stage_sim: error: %s' % compiled_raytrace.MISSING
    assert 'Traceback' not in run.stderr, run.stderr
