"""The mapper's tracking and its pose graph: what odometry allows a match to change, a
match that holds to the prediction where the scan cannot tell, and loops closed (issue 41).
"""
import math

import numpy as np
import pytest

from wall_follower.mapping.grid import LogOddsGrid
from wall_follower.mapping.matcher import DistanceField, ScanMatcher
from wall_follower.mapping.posegraph import PoseGraph
from wall_follower.mapping.poses import between, compose
from wall_follower.mapping.slam import Mapper, scan_points
from wall_follower.mapping.tracking import FLOOR, LAG, Prediction, in_frame, surprise

import test_mapping_insertion as octagon


def test_a_prediction_grows_with_the_motion_and_its_changes_and_a_match_resets_it():
    prediction = Prediction(0.05)
    assert prediction.sigma == pytest.approx(FLOOR)
    steady = (0.02, 0.0, 0.0)
    for _ in range(10):
        prediction.moved(steady, steady)
    # 5 % of 0.2 m of travel, in ten steps that err independently
    assert prediction.sigma[0] == pytest.approx(math.hypot(FLOOR[0], 0.05 * 0.02 * 10 ** 0.5),
                                                rel=0.05)
    before = prediction.sigma[0]
    prediction.moved((0.0, 0.0, 0.0), steady)       # stopped: the scan may be a step away
    assert prediction.sigma[0] == pytest.approx(math.hypot(before, 0.02), rel=1e-6)
    prediction.moved((0.5, 0.0, 0.0), (0.0, 0.0, 0.0))     # a jump is no step away
    assert prediction.sigma[0] < 0.2 * 0.05 + LAG[0] + before + 0.03
    prediction.fixed()
    assert prediction.sigma == pytest.approx(FLOOR)


def test_a_heading_in_doubt_becomes_a_sideways_doubt_as_the_robot_drives_on():
    prediction = Prediction(0.0)
    prediction.fixed(np.diag([0.0, 0.0, math.radians(2.0) ** 2]))
    for _ in range(50):
        prediction.moved((0.02, 0.0, 0.0), (0.02, 0.0, 0.0))
    sideways = math.sqrt(prediction.covariance()[1, 1])
    heading = math.hypot(math.radians(2.0), FLOOR[1])
    assert sideways == pytest.approx(math.hypot(FLOOR[0], 1.0 * heading), rel=0.02)
    assert math.sqrt(prediction.covariance()[0, 0]) == pytest.approx(FLOOR[0])


def test_surprise_is_the_correction_in_standard_deviations_of_the_prediction():
    prediction = Prediction(0.05)
    predicted = (1.0, 2.0, math.pi / 2)
    correction, distance = surprise(predicted, prediction, compose(predicted, (0.03, 0.0, 0.0)))
    assert correction == pytest.approx([0.03, 0.0, 0.0], abs=1e-12)
    assert distance == pytest.approx(0.03 / FLOOR[0])
    # a map-frame covariance seen from the robot: x of a robot heading +y is the map's y
    assert in_frame(np.diag([1.0, 4.0, 9.0]), math.pi / 2) == pytest.approx(
        np.diag([4.0, 1.0, 9.0]))


def _corridor(mapped=1.5):
    """A matcher on the map of a long corridor's two walls (y = +-0.495) drawn from its
    middle with beams used to `mapped` m (1.5: the walls drawn to x = +-1.4), and the
    hits of a scan from 0.3 m further on, used to 1.5 m: along the corridor nothing
    tells where the scan lies, and its walls run on 0.3 m past the mapped ends."""
    grid = LogOddsGrid(0.01, -3.0, -2.0, 3.0, 2.0)

    def scan(beams, used):
        angles = np.linspace(-math.pi, math.pi, beams, endpoint=False)
        with np.errstate(divide='ignore'):
            ranges = np.abs(0.495 / np.sin(angles))   # walls on cell centres
        return scan_points(ranges, angles, 0.12, 3.5, used)

    ends, hit = scan(3600, mapped)     # beams dense enough to draw the walls whole
    grid.integrate((0.0, 0.0), ends, hit)
    ends, hit = scan(360, 1.5)
    field = DistanceField(grid, 0.3)
    field.update()
    return ScanMatcher(field, (0.3, 0.1)), ends[hit]


def test_walls_not_mapped_yet_do_not_pull_a_scan_back_along_a_corridor():
    """The scan's walls run on 0.3 m past the ends the map has: those points lie within
    reach of the mapped ends, and weighed, they pulled the fit 3 to 18 cm back along
    the corridor (a lap of a corridor beyond the laser's range was lost so)."""
    matcher, points = _corridor()
    free = matcher.match(points, (0.3, 0.03, math.radians(2.0)))
    assert abs(free.pose[0] - 0.3) < 0.01
    assert abs(free.pose[1]) < 0.005 and abs(free.pose[2]) < math.radians(0.2)


def test_where_the_scan_cannot_tell_the_match_keeps_to_the_prediction_and_says_so():
    matcher, points = _corridor(mapped=3.5)      # the walls mapped past the scan's
    guess = (0.3, 0.03, math.radians(2.0))
    free = matcher.match(points, guess)
    held = matcher.match(points, guess, prior=np.diag([0.01 ** 2, 0.01 ** 2,
                                                      math.radians(0.5) ** 2]))
    assert abs(held.pose[1]) < 0.005 and abs(held.pose[2]) < math.radians(0.5)
    assert held.pose[0] == pytest.approx(0.3, abs=0.005)    # along: where odometry says
    along, across = math.sqrt(held.covariance[0, 0]), math.sqrt(held.covariance[1, 1])
    assert 0.004 < along <= 0.01 and across < 0.2 * along   # the prior's, nearly
    assert free.sigma > 10 * held.sigma            # the scan alone cannot tell


def _ring(count=24, radius=2.0, bias=(1.0, 1.0)):
    """Poses round a circle and a chain of ties between them, measured with a travel and
    turn bias, and a loop tie from the last back to the first measured right."""
    truth = [(radius * math.sin(2 * math.pi * k / count),
              radius - radius * math.cos(2 * math.pi * k / count),
              2 * math.pi * k / count) for k in range(count)]
    graph = PoseGraph()
    pose = truth[0]
    graph.add_pose(pose)
    for k in range(1, count):
        step = between(truth[k - 1], truth[k])
        pose = compose(pose, (step[0] * bias[0], step[1] * bias[0], step[2] * bias[1]))
        graph.add_pose(pose)
        graph.tie(k - 1, k, (step[0] * bias[0], step[1] * bias[0], step[2] * bias[1]),
                  (0.01, 0.01, 0.005))
    return truth, graph


def test_the_graph_s_jacobian_is_its_errors_derivative():
    _, graph = _ring(count=6, bias=(1.03, 1.02))
    graph.tie(0, 5, (0.3, -0.2, 0.4), (0.02, 0.01, 0.01))
    poses = np.array(graph.poses) + np.random.RandomState(0).normal(0.0, 0.05, (6, 3))
    free = poses[1:].reshape(-1)

    def errors(values):
        return graph._errors(np.vstack((poses[:1], values.reshape(-1, 3))))[0]

    numeric = np.column_stack([(errors(free + e) - errors(free - e)) / 2e-7
                               for e in np.eye(len(free)) * 1e-7])
    assert graph._jacobian(poses).toarray() == pytest.approx(numeric, abs=1e-5)


def test_relaxing_a_loop_spreads_its_error_and_holds_the_first_pose():
    truth, graph = _ring(bias=(1.0, 1.01))
    loop = between(truth[0], truth[-1])
    drifted = max(math.hypot(p[0] - t[0], p[1] - t[1]) for p, t in zip(graph.poses, truth))
    graph.tie(0, len(truth) - 1, loop, (0.01, 0.01, 0.005))
    moved, turned = graph.relax()
    assert graph.poses[0] == truth[0]
    relaxed = max(math.hypot(p[0] - t[0], p[1] - t[1]) for p, t in zip(graph.poses, truth))
    assert drifted > 0.1 and relaxed < 0.2 * drifted
    assert moved > 0.1 and abs(np.asarray(graph.residuals())).max() < 1.0


def test_a_graph_whose_ties_agree_stays_put():
    truth, graph = _ring()
    graph.tie(0, len(truth) - 1, between(truth[0], truth[-1]), (0.01, 0.01, 0.005))
    assert graph.relax() == pytest.approx((0.0, 0.0), abs=1e-9)
    with pytest.raises(ValueError, match='no tie'):
        graph.tie(3, 3, (0.0, 0.0, 0.0), (1.0, 1.0, 1.0))


# The keyframes of the first 2 m or so: all the loop closure may match the lap's end with.
EARLY = 14


def _octagon_lap(shift_early=None, at=120, **params):
    """The octagon's lap mapped from exact scans; at scan `at`, the first EARLY keyframes
    moved by shift_early (x, y, yaw) as a drift of the early map would have (the map
    redrawn so, unless the shift is only the graph's)."""
    mapper = Mapper(start_patience=0, **params)
    truth = octagon._lap()
    for k, pose in enumerate(truth):
        if k == at and shift_early is not None:
            poses = mapper.keyframes.graph.poses
            for keyframe in mapper.keyframes.frames[:EARLY]:
                poses[keyframe.node] = compose(shift_early, poses[keyframe.node])
        mapper.add_scan(octagon._scan(pose), octagon.BEAMS, octagon.RANGE[0], octagon.RANGE[1],
                        between(truth[0], pose))
    return mapper


def test_back_where_it_began_the_lap_closes_its_loop_once():
    mapper = _octagon_lap()
    assert mapper.counts['loops closed'] == 1
    graph = mapper.keyframes.graph
    assert len(graph.ties) == len(mapper.keyframes)     # a chain, and one loop tie
    (first, last), = [tie[:2] for tie in graph.ties if tie[1] - tie[0] > 1]
    assert first < 8 and last > 40                      # from the lap's end to its start
    assert _octagon_lap(loop_closure=False).counts['loops closed'] == 0


def test_a_loop_that_disagrees_is_relaxed_over_the_lap_and_the_map_redrawn_from_it():
    """The early keyframes 4 cm off the rest: the lap's end, matched against their map
    alone, is 4 cm off too; relaxed, the graph spreads that over the lap, and the map is
    drawn anew from every keyframe at its relaxed pose."""
    mapper = _octagon_lap(shift_early=(0.04, 0.0, 0.0))
    assert mapper.counts['loops closed'] == 1
    poses = mapper.keyframes.graph.poses
    steps = [between(poses[k - 1], poses[k]) for k in range(1, len(poses))]
    assert max(math.hypot(s[0], s[1]) for s in steps) < 0.2      # no jump left anywhere
    redrawn = Mapper(start_patience=0)
    redrawn.keyframes = mapper.keyframes
    redrawn._redraw()
    assert np.array_equal(redrawn.grid.logodds, mapper.grid.logodds)


def test_a_loop_the_early_map_places_too_far_off_is_not_closed():
    """The early keyframes half a metre off: their map places the lap's end further off
    than a lap matched scan by scan drifts, and no loop is closed."""
    mapper = _octagon_lap(shift_early=(0.5, 0.0, 0.0))
    assert mapper.counts['loops closed'] == 0
