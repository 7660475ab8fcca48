"""The recording fed arbitrary odometry: it never raises, and skips what it cannot use."""
import math

from hypothesis import HealthCheck, given, settings, strategies as st

from wall_follower.control.course.lap import LapRecorder
from wall_follower.control.course.odom_check import odometry_problem

ANY_FLOAT = st.floats(allow_nan=True, allow_infinity=True)
# Stamps as a header holds them: seconds since the epoch, with nanoseconds.
STAMP = st.floats(min_value=0.0, max_value=4.2e9, allow_nan=False)
ODOMETRY = st.tuples(STAMP, ANY_FLOAT, ANY_FLOAT, ANY_FLOAT, ANY_FLOAT, ANY_FLOAT, ANY_FLOAT)
# No example database: nothing is written into the source tree.
# Not timed: on a loaded machine (CI runs this beside the rostests) drawing the messages
# is slow, which says nothing of the code under test.
SETTINGS = settings(database=None, max_examples=300, deadline=None,
                    suppress_health_check=[HealthCheck.too_slow])


def yaw_of(qx, qy, qz, qw):
    return math.atan2(2.0 * (qw * qz + qx * qy), 1.0 - 2.0 * (qy * qy + qz * qz))


@SETTINGS
@given(ANY_FLOAT, ANY_FLOAT, ANY_FLOAT, ANY_FLOAT, ANY_FLOAT, ANY_FLOAT)
def test_odometry_problem_answers_anything(x, y, qx, qy, qz, qw):
    problem = odometry_problem(x, y, qx, qy, qz, qw)
    if problem is None:
        assert math.isfinite(x) and math.isfinite(y)
        assert abs(math.sqrt(qx * qx + qy * qy + qz * qz + qw * qw) - 1.0) <= 0.01
    else:
        assert isinstance(problem, str) and problem


@SETTINGS
@given(st.lists(ODOMETRY, max_size=60))
def test_the_recording_takes_what_passes_the_check_without_raising(messages):
    recorder = LapRecorder(sample_period=1.0, start=0.0)
    for stamp, x, y, qx, qy, qz, qw in messages:
        if odometry_problem(x, y, qx, qy, qz, qw) is None:
            recorder.add(stamp, x, y, yaw_of(qx, qy, qz, qw))
    assert not math.isnan(recorder.total_distance)
    assert recorder.total_distance >= 0.0
    assert all(math.isfinite(x) and math.isfinite(y) for x, y, _ in recorder.points)
