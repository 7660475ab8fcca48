"""The angled mapping worlds keep the promises their headers make (issue 31).

octagon: 3.0 m across its flats, its four other walls at 45 degrees;
parallelogram: corners of 60 and 120 degrees; each with a 0.24 m square
pillar and a start 0.5 m from the wall on the robot's right, and an _odom
variant with the same geometry whose odometry drifts as Stage's
odom_error [0.03 0.03 0.00 0.05].
"""
import math
import os

import numpy as np
import pytest
from PIL import Image

from bitmap_generator import generator
from wall_follower.evaluation.scoring.geometry import cast_rays
from wall_follower.evaluation.scoring.course import CourseMap
from wall_follower.sim.worldfile import load_world

REPO = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, os.pardir)
CORNERS = {'octagon': (135.0,), 'parallelogram': (60.0, 120.0)}


def world_path(name):
    return os.path.join(REPO, 'worlds', name + '.world')


def corner_angles(outline):
    """Inner angles [deg] at the corners of a counter-clockwise outline."""
    points = np.asarray(outline, dtype=float)
    before = np.roll(points, 1, axis=0) - points
    after = np.roll(points, -1, axis=0) - points
    cos = (before * after).sum(axis=1) / np.hypot(*before.T) / np.hypot(*after.T)
    return np.degrees(np.arccos(cos))


@pytest.mark.parametrize('name', sorted(CORNERS))
def test_bitmap_matches_its_generator_and_the_world_file(name):
    image, size, centre = generator().render(generator().OUTLINES[name])
    committed = Image.open(os.path.join(REPO, 'worlds', name + '.png')).convert('L')
    assert np.array_equal(np.asarray(committed), np.asarray(image))
    floorplan = [o for o in load_world(world_path(name)).obstacles if o.name == name][0]
    assert floorplan.pose[:2] == pytest.approx(centre)
    corners = floorplan.edges.reshape(-1, 2)
    assert corners.max(axis=0) - corners.min(axis=0) == pytest.approx(size)


@pytest.mark.parametrize('name', sorted(CORNERS))
def test_walls_meet_at_the_promised_angles(name):
    angles = corner_angles(generator().OUTLINES[name])
    assert min(abs(angles[:, None] - np.array(CORNERS[name])[None]).min(axis=1)) < 0.1
    assert abs(angles[:, None] - np.array(CORNERS[name])[None]).min(axis=1).max() < 0.1


def test_the_octagon_is_three_metres_across_its_flats():
    outline = np.asarray(generator().OUTLINES['octagon'])
    assert outline[:, 0].max() - outline[:, 0].min() == pytest.approx(3.0)
    assert outline[:, 1].max() - outline[:, 1].min() == pytest.approx(3.0)


@pytest.mark.parametrize('name', sorted(CORNERS))
def test_a_square_pillar_and_a_start_half_a_metre_from_the_wall_on_the_right(name):
    loaded = load_world(world_path(name))
    pillar, = [o for o in loaded.obstacles if o.name == 'pillar']
    sides = pillar.edges[:, 1] - pillar.edges[:, 0]
    assert len(sides) == 4 and np.hypot(*sides.T) == pytest.approx([0.24] * 4)
    assert pillar.obstacle_return and pillar.ranger_return
    x, y, yaw = loaded.robots[0].pose
    edges = CourseMap(world_path(name)).edges
    right = cast_rays(edges, x, y, [yaw - math.pi / 2])[0]
    around = cast_rays(edges, x, y, yaw + np.linspace(-math.pi, math.pi, 360, endpoint=False))
    assert right == pytest.approx(0.5, abs=0.02)
    assert around.min() > 0.45


@pytest.mark.parametrize('name', sorted(CORNERS))
def test_the_odom_variant_drifts_and_keeps_the_geometry(name):
    base = load_world(world_path(name))
    variant = load_world(world_path(name + '_odom'))
    assert variant.robots[0].localization == 'odom'
    assert variant.robots[0].odom_error == pytest.approx((0.03, 0.03, math.radians(0.05)))
    assert variant.robots[0]._replace(localization='gps', odom_error=None) == base.robots[0]
    assert len(variant.obstacles) == len(base.obstacles)
    for mine, theirs in zip(variant.obstacles, base.obstacles):
        assert mine.pose == theirs.pose and np.array_equal(mine.edges, theirs.edges)
