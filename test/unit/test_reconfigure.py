"""Controllers take new parameters between two scans, as dynamic_reconfigure hands them over."""
from laser_conventions import STAGE, scan_view
from wall_follower.control.following.follower import FOLLOW, FollowerParams, WallFollower

PARALLEL_AT_DEFAULT = scan_view([((-5.0, -0.25), (5.0, -0.25))], (0.0, 0.0, 0.0), STAGE)


def test_the_follower_steers_for_a_new_target_distance_at_the_next_scan():
    controller = WallFollower(FollowerParams(range_bias=0.0, laser_x=0.0))
    assert abs(controller.update(PARALLEL_AT_DEFAULT, 0.0).angular) < 0.01
    controller.reconfigure(FollowerParams(range_bias=0.0, laser_x=0.0, target_distance=0.22))
    command = controller.update(PARALLEL_AT_DEFAULT, 0.1)
    assert controller.state == FOLLOW
    assert command.angular < -0.2   # towards the wall on the right, now too far away


def test_a_new_turn_is_planned_with_the_new_parameters():
    controller = WallFollower(FollowerParams())
    controller.reconfigure(FollowerParams(inner_corner_radius=0.12, wide_start=0.0,
                                          outer_corner_radius=0.3))
    turn = controller.inner_corner.left_turn
    assert turn.radius == 0.12 and turn.wide_start == 0.0
    assert controller.params.outer_corner_radius == 0.3
    assert controller.outer_corner.params is controller.params
