"""Straight walls extracted from synthetic scans."""
import math

import numpy as np
import pytest

from laser_conventions import CONVENTIONS, STAGE, box, cast, scan_view
from wall_follower.control.sensing.lines import Line
from wall_follower.control.sensing.scan import ScanView
from wall_follower.control.sensing.walls import (
    Wall, closest_match, extract_walls, nearest_seen_point, path_is_clear, path_to_is_clear,
    refine)

ROOM = box(-2.0, -1.5, 2.0, 1.5)


def degrees(wall):
    return math.degrees(wall.angle)


@pytest.mark.parametrize('convention', CONVENTIONS, ids=[c.name for c in CONVENTIONS])
def test_the_four_walls_of_a_room_nearest_first(convention):
    walls = extract_walls(scan_view(ROOM, (0.5, 0.3, 0.0), convention), min_length=0.5)
    assert [round(w.distance, 2) for w in walls] == [1.2, 1.5, 1.8, 2.5]
    # Modulo 360: the wall behind may come out at +180 or -180 deg, by a
    # rounding that differs between numpy versions.
    assert [round(degrees(w)) % 360 for w in walls] == [90, 0, 270, 180]
    assert all(w.rms < 0.005 and w.foot_inside(0.5) for w in walls)


def test_a_turned_laser_sees_the_walls_turned_the_other_way():
    walls = extract_walls(scan_view(ROOM, (0.5, 0.3, 0.5), STAGE), min_length=0.5)
    assert degrees(walls[0]) == pytest.approx(90.0 - math.degrees(0.5), abs=0.5)


def test_a_lone_spurious_beam_neither_makes_a_wall_nor_cuts_one():
    ranges = cast(ROOM, (1.0, 0.0, 0.0), STAGE)
    ahead = int(np.argmin(np.abs(STAGE.angle_min + STAGE.increment * np.arange(360))))
    ranges[ahead] = 0.3
    view = ScanView(ranges, STAGE.angle_min, STAGE.increment, STAGE.range_min, STAGE.range_max)
    walls = extract_walls(view)
    assert walls[0].distance == pytest.approx(1.0, abs=0.005)
    assert walls[0].foot_inside(0.5)


def test_a_noisy_wall_stays_one_piece_or_is_gathered_by_refine():
    rng = np.random.RandomState(0)
    ranges = cast(ROOM, (1.7, 0.0, 0.0), STAGE) + rng.normal(0.0, 0.01, 360)
    view = ScanView(ranges, STAGE.angle_min, STAGE.increment, STAGE.range_min, STAGE.range_max)
    pieces = [w for w in extract_walls(view) if abs(degrees(w)) < 10.0 and w.distance < 0.4]
    assert pieces
    wall = refine(view, pieces[0])
    assert wall.distance == pytest.approx(0.3, abs=0.005)
    assert degrees(wall) == pytest.approx(0.0, abs=1.0)
    assert wall.length > 1.5


def test_hidden_ends_are_open_and_corners_are_not():
    # A box 0.3 m in front of the bottom wall hides part of it.
    world = ROOM + box(0.3, -1.0, 0.6, -0.7)
    walls = extract_walls(scan_view(world, (0.0, 0.0, 0.0), STAGE), min_length=0.5)
    bottom = [w for w in walls if abs(degrees(w) + 90.0) < 2.0]
    assert len(bottom) == 2
    # Counter-clockwise from the left corner to the box's shadow, then on
    # from the shadow to the right corner.
    left, right = sorted(bottom, key=lambda w: w.foot, reverse=True)
    assert (left.start_open, left.end_open) == (False, True)
    assert (right.start_open, right.end_open) == (True, False)


def test_path_to_a_wall_is_blocked_by_a_box_in_the_way():
    world = ROOM + box(-0.1, -1.0, 0.1, -0.8)
    view = scan_view(world, (0.0, 0.0, 0.0), STAGE)
    bottom = [w for w in extract_walls(view, min_length=0.5) if abs(degrees(w) + 90.0) < 2.0]
    top = [w for w in extract_walls(view, min_length=0.5) if abs(degrees(w) - 90.0) < 2.0]
    assert not any(path_is_clear(view, w, 0.15) for w in bottom)
    assert path_is_clear(view, top[0], 0.15)


def test_the_way_to_a_wall_is_clear_from_the_rotation_centre_not_from_the_laser():
    # A box's edge 0.17 m to the right of the way from the laser to the wall
    # ahead is 0.13 m from the way there from 0.04 m to the laser's right.
    world = ROOM + box(0.8, -0.5, 1.6, -0.17)
    view = scan_view(world, (0.0, 0.0, 0.0), STAGE)
    ahead = [w for w in extract_walls(view, min_length=0.5) if abs(degrees(w)) < 2.0][0]
    assert path_is_clear(view, ahead, 0.15)
    assert not path_is_clear(view, ahead, 0.15, origin=(0.0, -0.04))
    target = nearest_seen_point(ahead)
    assert path_to_is_clear(view, target, 0.15, wall=ahead)
    assert not path_to_is_clear(view, target, 0.15, wall=ahead, origin=(0.0, -0.04))


def test_a_wall_seen_only_round_its_end_is_reached_at_its_nearest_seen_point():
    # A bar ahead on the left: the point of its near side straight across
    # from the laser, (0, 0.5), lies beyond the bar's end at x = 0.5.
    bar = box(0.5, 0.5, 2.5, 0.6)
    view = scan_view(bar, (0.0, 0.0, 0.0), STAGE)
    side = [w for w in extract_walls(view, min_length=0.5) if abs(degrees(w) - 90.0) < 2.0][0]
    assert not side.foot_inside()
    # Within a Stage grid cell (the STAGE laser reads long by up to one).
    assert nearest_seen_point(side, 0.2) == pytest.approx((0.7, 0.5), abs=0.02)
    target = nearest_seen_point(side, 0.2)
    # The bar's own near end lies along the way there, and is not in it.
    assert not path_to_is_clear(view, target, 0.15)
    assert path_to_is_clear(view, target, 0.15, wall=side)
    blocked = scan_view(bar + box(0.3, 0.2, 0.4, 0.3), (0.0, 0.0, 0.0), STAGE)
    assert not path_to_is_clear(blocked, target, 0.15, wall=side)


def test_the_nearest_seen_point_of_a_wall_seen_across_is_its_foot():
    wall = extract_walls(scan_view(ROOM, (0.5, 0.3, 0.0), STAGE), min_length=0.5)[0]
    assert nearest_seen_point(wall, 0.2) == pytest.approx((0.0, 1.2), abs=0.01)


def test_refine_does_not_gather_a_wall_in_line_beyond_an_opening():
    # The wall ahead has an opening 0.6 m wide straight ahead of the laser (the
    # mouth of a wing 1.5 m deep), with wall in line on either side of it.
    # Refitted to every hit near its line, the piece below the opening took
    # in the piece above it, and the opening read as seen wall: a search
    # driving to the nearest seen point of that wall drove into the wing.
    world = [((1.0, -1.5), (1.0, -0.2)), ((1.0, 0.4), (1.0, 1.5)),
             ((1.0, -0.2), (2.5, -0.2)), ((2.5, -0.2), (2.5, 0.4)), ((2.5, 0.4), (1.0, 0.4))]
    view = scan_view(world, (0.0, 0.0, 0.0), STAGE)
    below = [w for w in extract_walls(view, min_length=0.5)
             if abs(degrees(w)) < 2.0 and w.distance < 1.5 and w.foot > w.end]
    assert below
    wall = refine(view, below[0])
    assert wall.distance == pytest.approx(1.0, abs=0.005)
    assert not wall.foot_inside()
    assert nearest_seen_point(wall, 0.2)[1] == pytest.approx(-0.4, abs=0.03)


def test_closest_match_keeps_the_same_wall_and_ignores_the_next_one():
    before = extract_walls(scan_view(ROOM, (1.0, 1.0, 0.0), STAGE))
    after = extract_walls(scan_view(ROOM, (1.0, 1.0, 0.05), STAGE))
    tracked = before[0]  # the top wall, 0.5 m to the left
    match = closest_match(after, tracked, math.radians(25.0), 0.2)
    assert match.distance == pytest.approx(0.5, abs=0.005)
    assert degrees(match) == pytest.approx(90.0 - math.degrees(0.05), abs=0.5)
    turned = tracked._replace(line=tracked.line._replace(angle=0.0))
    assert closest_match(after, turned, math.radians(25.0), 0.05) is None


def straight_ahead(distance, low, high):
    """A wall on the line x = distance in the laser frame, seen from y = low to y = high."""
    middle = (low + high) / 2.0
    return Wall(line=Line(distance, 0.0), length=high - low, rms=0.005, count=50,
                start=low - middle, end=high - middle, foot=-middle,
                start_open=False, end_open=False)


def test_closest_match_ignores_a_piece_of_a_far_wall_in_line_with_the_tracked_one():
    tracked = straight_ahead(0.778, -1.0, 0.8)
    # The same wall a step later, and 2.5 m to its right a piece of another wall that
    # lies on the same line and matches the line even better (generated world 116/21).
    same = straight_ahead(0.759, -1.0, 0.8)
    far_piece = straight_ahead(0.763, -3.0, -2.5)
    assert closest_match([far_piece, same], tracked, math.radians(25.0), 0.2) is same
    assert closest_match([far_piece], tracked, math.radians(25.0), 0.2) is None
    assert far_piece.point_at(far_piece.start) == pytest.approx((0.763, -3.0))
    # A piece of the wall itself, anywhere along it, still matches.
    piece = straight_ahead(0.763, -0.2, 0.25)
    assert closest_match([piece], tracked, math.radians(25.0), 0.2) is piece
