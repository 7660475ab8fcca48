"""slam's grids: what the extent and the cells ask for together is bounded before anything
is allocated, so a slip in a launch file is an error naming the values, not a MemoryError."""
import pytest

from wall_follower.mapping.grid import LogOddsGrid
from wall_follower.mapping.slam import Mapper
from wall_follower.params import ParameterError, checked
from wall_follower.params.mapping.slam import MAX_CELLS, RULES, TABLE, grid_cells

WIDE = dict(xmin=-100.0, xmax=100.0, ymin=-100.0, ymax=100.0)


def test_the_defaults_fit():
    checked(TABLE, {}, RULES)


@pytest.mark.parametrize('values', [
    dict(WIDE, delta=0.005),                   # the case: about 6 GiB
    WIDE,                                      # the default match_resolution over +-100 m
    dict(xmin=-40.0, xmax=40.0, ymin=-40.0, ymax=40.0),
])
def test_an_extent_and_cells_that_ask_too_much_are_refused_by_name(values):
    with pytest.raises(ParameterError) as refused:
        checked(TABLE, values, RULES)
    (problem,) = refused.value.problems
    assert problem.startswith('xmin, xmax, ymin, ymax, delta and match_resolution ask for ')
    assert str(MAX_CELLS) in problem


def test_a_wide_extent_at_coarse_cells_is_accepted():
    values = checked(TABLE, dict(WIDE, delta=0.1, match_resolution=0.1), RULES)
    assert grid_cells(0.1, -100.0, -100.0, 100.0, 100.0) * 2 <= MAX_CELLS
    assert values['xmin'] == -100.0


def test_the_limit_counts_the_cells_as_the_grids_have_them():
    box = (-3.0, -2.0, 4.01, 5.0)
    rows, cols = LogOddsGrid(0.05, *box).shape
    assert grid_cells(0.05, *box) == rows * cols


@pytest.mark.parametrize('values, says', [
    (dict(xmax=-20.0), 'xmax (-20.0) must be above xmin (-10.0)'),
    (dict(ymin=5.0, ymax=5.0), 'ymax (5.0) must be above ymin (5.0)'),
])
def test_an_empty_extent_is_refused_once_by_name(values, says):
    with pytest.raises(ParameterError) as refused:
        checked(TABLE, values, RULES)
    assert refused.value.problems == [says]


def test_the_mapper_refuses_before_allocating():
    with pytest.raises(ParameterError, match='ask for'):
        Mapper(**dict(WIDE, delta=0.005))
