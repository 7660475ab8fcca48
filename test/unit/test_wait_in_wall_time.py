"""wait_in_wall_time: a blocking wait bounded in wall seconds, whatever ROS time does."""
import threading
import time

from wall_follower.nodes.shared.waiting import wait_in_wall_time


def test_a_wait_that_never_ends_gives_up_after_the_timeout():
    never = threading.Event()
    started = time.monotonic()
    assert wait_in_wall_time(never.wait, 0.2) is False
    assert 0.2 <= time.monotonic() - started < 2.0


def test_the_answer_of_a_wait_that_ends_in_time():
    assert wait_in_wall_time(lambda: True, 5.0) is True
    assert wait_in_wall_time(lambda: False, 5.0) is False
