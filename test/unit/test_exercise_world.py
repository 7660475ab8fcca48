"""The lab exercises' world, pillars: bitmap as generated, pillars where its header says."""
import math
import os

import numpy as np
import pytest
from PIL import Image

from bitmap_generator import generator
from wall_follower.evaluation.scoring.geometry import cast_rays
from wall_follower.evaluation.scoring.course import CourseMap

REPO = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, os.pardir)
WORLD = os.path.join(REPO, 'worlds', 'pillars.world')


def test_bitmap_matches_its_generator():
    module = generator()
    image, _, _ = module.render(module.OUTLINES['pillars'], module.PILLARS['pillars'])
    committed = Image.open(os.path.join(REPO, 'worlds', 'pillars.png')).convert('L')
    assert np.array_equal(np.asarray(committed), np.asarray(image))


@pytest.mark.parametrize('x, y', [(x, y) for x in (-1.1, 0.0, 1.1) for y in (-1.1, 0.0, 1.1)])
def test_a_pillar_of_radius_015_at_each_grid_point(x, y):
    course = CourseMap(WORLD)
    # from 0.5 m away, looking at the pillar's centre: its face 0.35 m off
    for heading in (0.0, math.pi / 2, math.pi, -math.pi / 2):
        sx, sy = x - 0.5 * math.cos(heading), y - 0.5 * math.sin(heading)
        assert cast_rays(course.edges, sx, sy, [heading])[0] == pytest.approx(0.35, abs=0.021)


def test_the_start_pose_is_clear():
    course = CourseMap(WORLD)
    assert course.clearance(course.robot.pose) > 0.15
