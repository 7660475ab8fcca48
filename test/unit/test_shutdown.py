"""shutdown: waits that rospy's shutdown ends raise rospy.ROSInterruptException, and a node's
main then ends with status 0 and one info line. No master: rospy.is_shutdown() is the
test's."""
import time

import pytest
import rospy

from wall_follower.nodes.shared.shutdown import poll_until, quiet_on_shutdown


@pytest.fixture
def infos(monkeypatch):
    lines = []
    monkeypatch.setattr(rospy, 'loginfo', lambda text, *args: lines.append(text % args))
    return lines


def shut_down(monkeypatch, down=True):
    monkeypatch.setattr(rospy, 'is_shutdown', lambda: down)


def test_a_poll_answers_what_came_or_that_its_limit_passed(monkeypatch):
    shut_down(monkeypatch, False)
    assert poll_until(lambda: True, 0.0) is True
    started = time.monotonic()
    assert poll_until(lambda: False, 0.1, period=0.01) is False
    assert time.monotonic() - started >= 0.1


def test_a_poll_that_shutdown_ends_raises_even_past_its_limit(monkeypatch):
    shut_down(monkeypatch)
    with pytest.raises(rospy.ROSInterruptException):
        poll_until(lambda: False, 0.0)


def test_a_main_whose_wait_shutdown_ended_ends_with_status_0_and_one_line(monkeypatch, infos):
    shut_down(monkeypatch)

    @quiet_on_shutdown
    def main():
        raise rospy.ROSInterruptException('rospy shutdown')   # as rospy's own waits do
    assert main() == 0
    assert len(infos) == 1 and 'shut down' in infos[0]


def test_a_main_that_ends_by_itself_keeps_its_status(monkeypatch, infos):
    shut_down(monkeypatch)
    assert quiet_on_shutdown(lambda: 1)() == 1
    assert infos == []


def test_simulated_time_going_back_is_no_shutdown(monkeypatch, infos):
    """rospy.sleep raises a kind of ROSInterruptException for it too: not a quiet end."""
    shut_down(monkeypatch, False)

    def main():
        raise rospy.exceptions.ROSTimeMovedBackwardsException(1.0)
    with pytest.raises(rospy.exceptions.ROSTimeMovedBackwardsException):
        quiet_on_shutdown(main)()
