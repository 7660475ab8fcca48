"""A world whose obstacles span more cells of its resolution than the simulator's grid may hold
is refused by the reader, naming the file and line, before any grid is allocated."""
import os
import textwrap

import pytest

from wall_follower.sim.grid import OccupancyGrid
from wall_follower.sim.worldfile import MAX_GRID_CELLS, WorldFileError, load_world

WORLD = """\
    resolution {resolution}
    model ( name "wall" pose [ 0 0 0 0 ] size [ {size} 0.1 0.5 ] )
    position ( name "robot" pose [ 0 1 0 0 ] size [ 0.2 0.2 0.2 ] )
    """


def world_file(tmp_path, resolution, size):
    path = os.path.join(str(tmp_path), 'test.world')
    with open(path, 'w') as stream:
        stream.write(textwrap.dedent(WORLD.format(resolution=resolution, size=size)))
    return path


@pytest.mark.parametrize('resolution, size', [('0.00001', 16.0), ('0.002', 100.0)])
def test_a_grid_too_large_is_refused_at_the_resolution_line(tmp_path, resolution, size):
    path = world_file(tmp_path, resolution, size)
    with pytest.raises(WorldFileError) as refused:
        load_world(path)
    assert str(refused.value).startswith('%s:1: the obstacles span about ' % path)
    assert 'more than the %d the simulator holds' % MAX_GRID_CELLS in str(refused.value)


def test_the_bound_is_never_below_the_grid_it_stands_for(tmp_path):
    world = load_world(world_file(tmp_path, 0.01, 16.0))
    rows, cols = OccupancyGrid.from_world(world).shape
    assert rows * cols <= MAX_GRID_CELLS


@pytest.mark.parametrize('samples', [0, 100001, 1000000000])
def test_a_ranger_with_no_beam_or_beams_beyond_memory_is_refused(tmp_path, samples):
    path = os.path.join(str(tmp_path), 'laser.world')
    with open(path, 'w') as stream:
        stream.write('position\n(\n  name "robot"\n  ranger ( sensor ( samples %d ) )\n)\n'
                     % samples)
    with pytest.raises(WorldFileError) as refused:
        load_world(path)
    assert str(refused.value) == '%s:4: samples must be from 1 to 100000, not %d' % (
        path, samples)
