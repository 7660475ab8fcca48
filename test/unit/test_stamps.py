"""control.stamps: which stamps lie too far ahead of a node's clock, and the words that say so."""
import pytest

from wall_follower.control.stamps import AHEAD_LIMIT, ahead_problem, arrival_time, outside_problem

NOW = 1795878000.0               # a clock of 2026
YEAR_2100 = 4102444800.0         # 2100-01-01, as a header's seconds
LARGEST = 4294967295.999999999   # the largest stamp a header can carry (uint32 seconds)


@pytest.mark.parametrize('stamp, words', [
    (YEAR_2100, 'over 73 years'),
    (LARGEST, 'over 79 years'),
    (NOW + AHEAD_LIMIT + 1.0, 'over 1 day'),
    (NOW + 3.5 * AHEAD_LIMIT, 'over 3 days'),
    (NOW + 400 * AHEAD_LIMIT, 'over 1 year'),
])
def test_a_stamp_more_than_a_day_ahead_is_refused_saying_how_far(stamp, words):
    assert ahead_problem(stamp, NOW) == "it is stamped %s ahead of this node's clock" % words


@pytest.mark.parametrize('stamp', [
    NOW, NOW + 0.1, NOW + 3600.0, NOW + AHEAD_LIMIT,   # clocks that differ by up to a day
    NOW - 3.0e6, 1.0,                                    # behind: a robot without a clock battery
    0.0,                                                 # not set
])
def test_a_stamp_up_to_a_day_ahead_or_behind_or_unset_is_taken(stamp):
    assert ahead_problem(stamp, NOW) is None


def test_nothing_is_refused_before_the_clock_runs():
    """On simulated time the clock reads 0 until the first /clock."""
    assert ahead_problem(YEAR_2100, 0.0) is None


def test_the_words_stay_the_same_while_the_stamps_stay_as_far_ahead():
    """A clock set to 2100 stamps each message a little later; the warning repeats the same."""
    words = set(ahead_problem(YEAR_2100 + t, NOW + t) for t in range(0, 3600, 7))
    assert len(words) == 1


@pytest.mark.parametrize('stamp, words', [
    (1000.2, None),
    (995.0, None),
    (1010.5, 'more than 10 s ahead'),
    (YEAR_2100, 'more than 10 s ahead'),
    (LARGEST, 'more than 10 s ahead'),
    (1e-9, 'more than 10 s before'),
    (0.0, None),                                      # not set: as of its arrival
])
def test_a_stamp_outside_a_span_either_way_is_named_by_the_span(stamp, words):
    problem = outside_problem(stamp, 1000.0, 10.0)
    assert problem is None if words is None else words in problem


def test_on_simulated_time_a_message_arrives_no_earlier_than_it_was_taken():
    # The node's clock lags the world's: a scan of 6.8 s came at 6.3 s by it.
    assert arrival_time(6.3, 6.8, simulated=True) == 6.8
    assert arrival_time(6.9, 6.8, simulated=True) == 6.9


@pytest.mark.parametrize('now,stamp,simulated', [
    (6.3, 6.8, False),   # wall time: the stamp is another machine's clock
    (6.3, 0.0, True),    # no stamp
    (0.0, 6.8, True),    # no clock yet
])
def test_otherwise_a_message_arrives_when_this_nodes_clock_says(now, stamp, simulated):
    assert arrival_time(now, stamp, simulated) == now
