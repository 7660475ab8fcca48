"""The course's markers for rviz: the band beside the laser, find_wall's answer."""
import pytest
import rospy

from wall_follower.evaluation.scoring.course import BAND
from wall_follower.nodes.shared.course_markers import band_marker, find_wall_marker


@pytest.mark.parametrize('laser_x', [-0.032, -0.064, 0.0])
def test_band_lines_run_along_the_robot_at_the_band_right_of_the_laser(laser_x):
    marker = band_marker(laser_x)
    assert marker.header.frame_id == 'base_link' and marker.frame_locked
    ends = [(p.x, p.y) for p in marker.points]
    assert len(ends) == 4
    for (x0, y0), (x1, y1), distance in zip(ends[::2], ends[1::2], BAND):
        assert y0 == y1 == pytest.approx(-distance)
        assert (x0 + x1) / 2.0 == pytest.approx(laser_x) and x1 > x0


def test_find_wall_answer_stays_where_it_was_given_coloured_by_the_answer():
    stamp = rospy.Time(12, 5)
    found, not_found = find_wall_marker(True, stamp), find_wall_marker(False, stamp)
    for marker in (found, not_found):
        assert marker.header.stamp == stamp and not marker.frame_locked
    assert found.color.g > found.color.r and not_found.color.r > not_found.color.g
