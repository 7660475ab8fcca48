"""The mapper's parts: the grid update, scan matching, map files, the map's score."""
import math
import os

import numpy as np
import pytest

from wall_follower.evaluation.scoring.map_quality import map_quality
from wall_follower.mapping.grid import LogOddsGrid
from wall_follower.mapping.mapfile import SavedMap, load_map, save_map
from wall_follower.mapping.matcher import DistanceField
from wall_follower.mapping.poses import between, compose, inverse
from wall_follower.mapping.slam import NOT_TRUSTED, TRUSTED, Mapper, scan_points

ROOM = os.path.join(os.path.dirname(__file__), '..', '..', 'worlds', 'room.world')


def _state(grid, x, y):
    rows, cols, _ = grid.cells([(x, y)])
    return grid.observed[rows[0], cols[0]], grid.logodds[rows[0], cols[0]]


def test_a_beam_clears_its_way_marks_its_end_and_leaves_what_is_beyond_unknown():
    grid = LogOddsGrid(0.1, -1.0, -1.0, 3.0, 1.0, hit=0.9, miss=-0.4)
    grid.integrate((0.05, 0.05), [(1.55, 0.05)], [True])
    for x in (0.05, 0.55, 1.35):
        assert _state(grid, x, 0.05) == (True, pytest.approx(-0.4))
    assert _state(grid, 1.55, 0.05) == (True, pytest.approx(0.9))
    for x in (1.65, 2.5):
        assert _state(grid, x, 0.05) == (False, 0.0)
    assert _state(grid, 0.55, 0.25) == (False, 0.0)      # nothing beside the beam


def test_a_free_beam_clears_to_its_end_and_a_cell_counts_once_per_scan():
    grid = LogOddsGrid(0.1, -1.0, -1.0, 3.0, 1.0, hit=0.9, miss=-0.4)
    # Two beams through the same cells: one miss each per scan, not two.
    grid.integrate((0.05, 0.05), [(1.05, 0.05), (1.05, 0.06)], [False, False])
    assert _state(grid, 0.55, 0.05) == (True, pytest.approx(-0.4))
    assert _state(grid, 1.05, 0.05) == (True, pytest.approx(-0.4))
    values = grid.occupancy()
    rows, cols, _ = grid.cells([(0.55, 0.05), (2.5, 0.5)])
    assert values[rows[0], cols[0]] == round(100 / (1 + math.exp(0.4)))
    assert values[rows[1], cols[1]] == -1


def test_scan_points_sort_hits_from_free_beams_and_drop_unknown_ones():
    ranges = [1.0, 3.5, float('inf'), 0.0, float('nan'), 0.05, 3.2]
    angles = np.radians([0, 90, 180, 270, 45, 135, 10])
    ends, hit = scan_points(ranges, angles, 0.12, 3.5, 3.0)
    assert list(hit) == [True, False, False, False]
    assert ends[0] == pytest.approx([1.0, 0.0])
    assert ends[1] == pytest.approx([0.0, 3.0], abs=1e-12)        # range_max: free to the cut
    assert ends[2] == pytest.approx([-3.0, 0.0], abs=1e-12)       # inf: the same
    assert np.hypot(*ends[3]) == pytest.approx(3.0)               # a hit beyond max_range


def _room_scan(pose, beams=360, half=(1.5, 1.2)):
    """Ranges from pose (x, y, yaw) to the walls of an empty box |x| = 1.5, |y| = 1.2."""
    angles = np.linspace(-math.pi, math.pi, beams, endpoint=False)
    world = pose[2] + angles
    c, s = np.cos(world), np.sin(world)
    with np.errstate(divide='ignore'):
        tx = np.where(c > 0, (half[0] - pose[0]) / c, (-half[0] - pose[0]) / c)
        ty = np.where(s > 0, (half[1] - pose[1]) / s, (-half[1] - pose[1]) / s)
    return np.minimum(np.abs(tx), np.abs(ty)), angles


@pytest.mark.parametrize('offset', [(0.06, -0.04, math.radians(4.0)),
                                    (-0.05, 0.03, math.radians(-3.0)),
                                    (0.0, 0.0, math.radians(6.0))])
def test_the_matcher_recovers_a_known_offset_of_a_synthetic_scan(offset):
    # The map from a few scans at known poses, so the far walls are drawn without gaps.
    mapper = Mapper(scan_matching=False, linear_update=0.0, start_patience=0)
    for k in range(4):
        ranges, angles = _room_scan((0.0, 0.0, math.radians(0.25 * k)))
        mapper.add_scan(ranges, angles, 0.12, 3.5, (0.0, 0.0, math.radians(0.25 * k)))
    true_pose = (0.20, -0.10, math.radians(20.0))
    ranges, angles = _room_scan(true_pose)
    ends, hit = scan_points(ranges, angles, 0.12, 3.5, 3.5)
    guess = (true_pose[0] + offset[0], true_pose[1] + offset[1], true_pose[2] + offset[2])
    match = mapper.matcher.match(ends[hit], guess)
    assert match.ok
    # Within one cell of the fine grid: walls on cell edges, as here and in Stage's
    # worlds, are drawn half a cell into their cells, and the scan is matched to those.
    error = math.hypot(match.pose[0] - true_pose[0], match.pose[1] - true_pose[1])
    assert error < mapper.config['match_resolution']
    assert abs(math.degrees(match.pose[2] - true_pose[2])) < 0.1
    assert match.misfit < 0.005


def test_the_mapper_keeps_the_prediction_when_a_match_leaves_the_window():
    mapper = Mapper(start_patience=0, search_window_linear=0.01)
    ranges, angles = _room_scan((0.0, 0.0, 0.0))
    mapper.add_scan(ranges, angles, 0.12, 3.5, (0.0, 0.0, 0.0))
    # The robot stands, its odometry says it moved 1.5 cm: beyond the window, and the
    # prediction still explains the scan (within match_reach, 1.5 cm RMS off).
    pose = mapper.add_scan(ranges, angles, 0.12, 3.5, (0.015, 0.0, 0.0))
    assert pose == (0.015, 0.0, 0.0) and mapper.drawn == 1
    assert 'from the prediction' in mapper.decision and mapper.counts['not trusted'] == 1
    assert mapper.outcome == NOT_TRUSTED
    mapper.reconfigure(start_patience=0, search_window_linear=0.15)
    pose = mapper.add_scan(ranges, angles, 0.12, 3.5, (0.015, 0.0, 0.0))
    assert math.hypot(pose[0], pose[1]) < mapper.config['match_resolution']
    assert mapper.decision == 'matched' and mapper.outcome == TRUSTED


def test_the_mapper_corrects_drifting_odometry_and_publishes_map_to_odom():
    mapper = Mapper()
    truth = (0.0, 0.0, 0.0)
    odom = truth
    for _ in range(2):    # standing: the map starts
        ranges, angles = _room_scan(truth)
        mapper.add_scan(ranges, angles, 0.12, 3.5, odom)
    assert mapper.started
    for _ in range(40):   # 2 cm and 1 degree a scan; odometry believes 2 % more of both
        step = (0.02, 0.0, math.radians(1.0))
        truth = compose(truth, step)
        odom = compose(odom, (0.0204, 0.0, math.radians(1.02)))
        ranges, angles = _room_scan(truth)
        pose = mapper.add_scan(ranges, angles, 0.12, 3.5, odom)
    assert math.hypot(pose[0] - truth[0], pose[1] - truth[1]) < 0.02
    assert abs(math.degrees(pose[2] - truth[2])) < 0.5
    assert math.hypot(odom[0] - truth[0], odom[1] - truth[1]) > 0.015
    assert math.degrees(odom[2] - truth[2]) > 0.7
    assert compose(mapper.map_to_odom(), odom) == pytest.approx(pose)


def test_the_map_starts_at_rest_or_once_patience_runs_out():
    ranges, angles = _room_scan((0.0, 0.0, 0.0))
    mapper = Mapper(start_patience=5)
    for k in range(3):    # turning: odometry a step ahead of the laser would tilt the map
        assert mapper.add_scan(ranges, angles, 0.12, 3.5, (0.0, 0.0, 0.05 * (k + 1))) is None
    assert mapper.add_scan(ranges, angles, 0.12, 3.5, (0.0, 0.0, 0.15)) == (0.0, 0.0, 0.15)
    assert mapper.started and mapper.drawn == 1
    impatient = Mapper(start_patience=5)
    poses = [impatient.add_scan(ranges, angles, 0.12, 3.5, (0.01 * (k + 1), 0.0, 0.0))
             for k in range(7)]
    assert poses[:5] == [None] * 5 and poses[5] is not None
    # Patience run out while the robot turns (find_wall): the map waits for a step that
    # does not turn, where the odometry's lead cannot tilt it.
    turning = Mapper(start_patience=5)
    poses = [turning.add_scan(ranges, angles, 0.12, 3.5, (0.0, 0.0, 0.05 * (k + 1)))
             for k in range(9)]
    poses.append(turning.add_scan(ranges, angles, 0.12, 3.5, (0.01, 0.0, 0.45)))
    assert poses[:9] == [None] * 9 and poses[9] == (0.01, 0.0, 0.45)
    # The odometry still at its origin: nothing has moved yet, the map starts there, before
    # the turn and the odometry's error since.
    fresh = Mapper(start_patience=5)
    assert fresh.add_scan(ranges, angles, 0.12, 3.5, (0.0, 0.0, 0.0)) == (0.0, 0.0, 0.0)


def test_new_parameters_apply_from_the_next_scan():
    ranges, angles = _room_scan((0.0, 0.0, 0.0))
    mapper = Mapper(scan_matching=False, start_patience=0)
    for x in (0.0, 0.05):   # the second scan is nearer than linear_update: not drawn
        mapper.add_scan(ranges, angles, 0.12, 3.5, (x, 0.0, 0.0))
    assert mapper.drawn == 1
    mapper.reconfigure(scan_matching=False, start_patience=0, linear_update=0.04,
                       hit_logodds=1.2, miss_logodds=-0.3)
    mapper.add_scan(ranges, angles, 0.12, 3.5, (0.1, 0.0, 0.0))
    assert mapper.drawn == 2
    assert (mapper.grid.hit, mapper.grid.miss) == (mapper.fine.hit, mapper.fine.miss) == (
        1.2, -0.3)


def test_a_new_match_window_and_reach_apply_to_the_map_already_built():
    mapper = Mapper(scan_matching=False, start_patience=0)
    ranges, angles = _room_scan((0.0, 0.0, 0.0))
    mapper.add_scan(ranges, angles, 0.12, 3.5, (0.0, 0.0, 0.0))
    mapper.reconfigure(search_window_linear=0.02, match_capture=0.5, odom_drift=0.1,
                       match_max_misfit=0.03)
    assert mapper.matcher.reaches == (0.5, mapper.config['match_reach'])
    assert mapper.prediction.drift == 0.1 and mapper.matcher.max_misfit == 0.03
    fresh = DistanceField(mapper.fine, 0.5)
    fresh.update()
    assert mapper.field.reach == 0.5
    assert np.array_equal(mapper.field.values, fresh.values)


@pytest.mark.parametrize('name, value', [('delta', 0.1), ('xmax', 5.0),
                                         ('match_resolution', 0.02)])
def test_the_grids_cannot_change_on_a_map_being_built(name, value):
    mapper = Mapper()
    with pytest.raises(ValueError, match='%s cannot change' % name):
        mapper.reconfigure(**{name: value})
    assert mapper.config[name] != value


def test_poses_compose_invert_and_relate():
    a, b = (1.0, 2.0, 0.5), (-0.3, 0.4, -1.2)
    assert compose(a, inverse(a)) == pytest.approx((0.0, 0.0, 0.0))
    assert compose(a, between(a, b)) == pytest.approx(b)


# A 3 x 2 map, row 0 at the bottom: values 0 (free), 100, -1 (unknown), 25 (free at
# map_saver's --free 25), 65 (occupied at --occ 65) and 50 (neither: unknown).
SMALL = np.array([[0, 100, -1], [25, 65, 50]], dtype=np.int8)
# What map_server's `map_saver -f small` writes for it: the top row first.
SMALL_PGM = (b'P5\n# CREATOR: map_saver.cpp 0.050 m/pix\n3 2\n255\n'
             + bytes([254, 0, 205]) + bytes([254, 0, 205]))


def test_map_files_are_byte_for_byte_map_savers(tmp_path):
    name = os.path.join(str(tmp_path), 'small')
    image, meta = save_map(name, SMALL, 0.05, (-1.25, 0.5, 0.0))
    with open(image, 'rb') as stream:
        assert stream.read() == SMALL_PGM
    with open(meta) as stream:
        assert stream.read() == ('image: %s.pgm\nresolution: 0.050000\n'
                                 'origin: [-1.250000, 0.500000, 0.000000]\nnegate: 0\n'
                                 'occupied_thresh: 0.65\nfree_thresh: 0.196\n\n' % name)
    assert sorted(os.listdir(str(tmp_path))) == ['small.pgm', 'small.yaml']


def test_the_loader_reads_a_saved_map_back_as_map_server_does(tmp_path):
    name = os.path.join(str(tmp_path), 'small')
    save_map(name, SMALL, 0.05, (-1.25, 0.5, 0.0))
    loaded = load_map(name + '.yaml')
    assert loaded.resolution == pytest.approx(0.05)
    assert loaded.origin == (-1.25, 0.5, 0.0)
    assert loaded.data.tolist() == [[0, 100, -1], [0, 100, -1]]


def test_the_loader_refuses_what_is_not_a_map(tmp_path):
    path = os.path.join(str(tmp_path), 'x.yaml')
    with open(path, 'w') as stream:
        stream.write('image: x.pgm\n')
    with pytest.raises(ValueError):
        load_map(path)


def _true_map(resolution=0.05):
    """The room's walls drawn straight into a map frame at the start pose (-0.8, -0.95, 0)."""
    grid = LogOddsGrid(resolution, -1.5, -1.0, 3.0, 3.0)
    xs = np.arange(-1.5, 1.5, 0.005)
    ys = np.arange(-1.2, 1.2, 0.005)
    walls = np.concatenate([np.column_stack((xs, np.full_like(xs, -1.2))),
                            np.column_stack((xs, np.full_like(xs, 1.2 - 1e-9))),
                            np.column_stack((np.full_like(ys, -1.5), ys)),
                            np.column_stack((np.full_like(ys, 1.5 - 1e-9), ys))])
    rows, cols, inside = grid.cells(walls - (-0.8, -0.95))
    data = np.zeros(grid.shape, dtype=np.int8)
    data[rows[inside], cols[inside]] = 100
    return data, (grid.origin[0], grid.origin[1], 0.0)


@pytest.mark.parametrize('origin', [-2.0, -2.05, -2.5, -3.0, -2.0125])
def test_the_seen_walls_do_not_depend_on_where_the_maps_cells_fall(origin):
    """The room's walls lie on cell boundaries for most of these origins, and float
    rounding put some of their points on one side of a boundary, some on the other."""
    path = [(-0.8 + 0.1 * k, -0.95, 0.0) for k in range(20)]
    unknown = SavedMap(np.full((200, 200), -1, dtype=np.int8), 0.05, (origin, origin, 0.0))
    quality = map_quality(unknown, ROOM, (-0.8, -0.95, 0.0), path, 3.5)
    reference = map_quality(unknown._replace(origin=(-2.0125, -2.0125, 0.0)), ROOM,
                            (-0.8, -0.95, 0.0), path, 3.5)
    assert abs(quality.seen_walls - reference.seen_walls) <= 2


def test_a_true_map_scores_full_and_a_shifted_one_does_not(tmp_path):
    data, origin = _true_map()
    path = [(-0.8 + 0.1 * k, -0.95, 0.0) for k in range(20)]
    name = os.path.join(str(tmp_path), 'room')
    save_map(name, data, 0.05, origin)
    quality = map_quality(load_map(name + '.yaml'), ROOM, (-0.8, -0.95, 0.0), path, 3.5)
    assert quality.precision == 1.0 and quality.recall == 1.0
    save_map(name, np.roll(data, (3, 3), axis=(0, 1)), 0.05, origin)   # 15 cm off in x and y
    shifted = map_quality(load_map(name + '.yaml'), ROOM, (-0.8, -0.95, 0.0), path, 3.5)
    assert shifted.precision < 0.6 and shifted.recall < 0.1


def test_a_wall_seen_at_a_slant_after_head_on_stays_a_wall():
    # The top wall at y = 1.21 lies a centimetre into its cells (the map's cells start at
    # multiples of 0.05 m): seen head on, then twelve times from near the room's ends, at
    # 85 degrees from its normal, beams 0.6 m apart on it. Each beam crossed the wall's
    # cells on its way to its end and cleared them, and the wall came out with gaps
    # (issue 41, a generated room).
    half = (3.0, 1.21)
    poses = [(0.0, 0.9, 0.0)] + [(x, y, 0.0) for x in (-2.8, -2.7, 2.7, 2.8)
                                 for y in (0.95, 1.0, 1.05)]
    mapper = Mapper(scan_matching=False, linear_update=0.0, start_patience=0)
    for pose in poses:
        ranges, angles = _room_scan(pose, half=half)
        mapper.add_scan(ranges, angles, 0.12, 3.5, pose)
    assert mapper.drawn == len(poses)
    xs = np.arange(-0.3, 0.3, mapper.grid.resolution) + 0.025
    rows, cols, _ = mapper.grid.cells(np.column_stack((xs, np.full(len(xs), half[1]))))
    occupancy = mapper.grid.occupancy()[rows, cols]
    assert (occupancy > 50).all(), occupancy
