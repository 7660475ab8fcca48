"""When a message's time stamp lies too far ahead of a node's clock for the message to be used.

A header.stamp can hold any unsigned 32-bit seconds: 0 (not set), a clock
set wrong, a driver's bug (2100-01-01, 2**32 - 1 s). rospy's own
arithmetic on such a stamp does not fail (genpy's Time and Duration are
unbounded Python integers), but what a node does with it does: tf2's C++
core aborts the whole process ("out of dual 32-bit range") when a
transform at such a stamp meets its cache, be it one this node looks up
at a message's stamp or one it broadcasts at it (its own listener, and
every other node's, then takes it in); a stamp with a duration added can
pass 2**32 s and no longer be sent; and a node that times its work on
stamps waits for a moment that never comes, or takes every good message
after it for time going back. So a message stamped more than AHEAD_LIMIT
ahead of the node's clock is stale input: the node uses nothing of it (a
node that drives stops) and warns, in words that stay the same while such
messages last.

How far is too far: the clocks of machines never synchronized differ by
seconds to hours (a robot's and a laptop's), and a node's simulated clock
lags the world's by a step or more when the node is starved of CPU; those
stay accepted. No clock runs a day ahead of another. A stamp behind the
node's clock is never refused here: a robot whose clock has no battery (a
Raspberry Pi's) runs days behind, and such messages are aged by their
arrival, not by their stamp.

A node that looks up tf at a message's stamp must also keep away from
stamps its buffer cannot hold, either way (outside_problem): tf2 aborts
on those too.

The time between two stamps (elapsed) is taken to the microsecond: as
floats, two stamps a step apart differ by the step give or take rounding
that depends on how far the clock has run.

Seconds as floats, no ROS: callers pass stamp.to_sec() and rospy.get_time().
Floats hold any stamp a header can carry, where the difference of two
such stamps need not fit a Duration's 32-bit seconds.
"""
AHEAD_LIMIT = 24 * 3600.0   # s a stamp may lie ahead of the node's clock

# Places of decimals of a second to which elapsed() takes the time between stamps.
ELAPSED_PLACES = 6
_DAY = 24 * 3600.0
_YEAR = 365.25 * _DAY


def elapsed(later, earlier):
    """Seconds from stamp `earlier` to stamp `later` (both in s), to the microsecond.

    A simulator's clock is its steps added up in floating point and cut
    to whole nanoseconds in a header, and a stamp as a float is rounded
    according to its size: the same 0.1 s step reads 0.09999999899999779 s
    between one pair of stamps and 0.09999999999999964 s between another.
    A controller that integrates the steps then depends on when it began:
    in lockstep simulation a node started a step later on a busy machine,
    and its lap round the arena went another way round a corner (60.0 s
    instead of 60.9 s) from the same start. Scans and odometry are timed
    far more coarsely than a microsecond, so nothing real is lost.
    """
    return round(later - earlier, ELAPSED_PLACES)


def arrival_time(now, stamp, simulated):
    """When a message that came at `now` by this node's clock is taken to have arrived, for
    its age (all in s): `now`, or on simulated time no earlier than its `stamp`.

    On simulated time a stamp is the world's time, read off the same clock as the node's
    own. A node starved of CPU can have its /clock messages queued while messages on other
    topics still come: it dates them at a time before they were taken, and when its clock
    catches up, in a burst, they look that much older; a scan half a second "old" that way
    stopped a driving node for a step in lockstep simulation. On wall time a stamp is some
    machine's clock, perhaps one running ahead, and proves nothing of freshness. A zero
    stamp or clock (not set; simulated time before the first /clock) leaves `now`.
    """
    if not simulated or stamp == 0.0 or now == 0.0:
        return now
    return max(now, stamp)


def ahead_problem(stamp, now):
    """Why a message stamped `stamp` cannot be used at `now` (both in s), in words
    ("it is stamped over 73 years ahead of this node's clock"); None when it can.

    A zero stamp (not set: the message is taken as of its arrival) and a zero clock
    (simulated time before the node's first /clock: nothing to compare with) are no
    problem. The words name how far ahead in whole years or days only, so that they do
    not change from one message to the next.
    """
    if stamp == 0.0 or now == 0.0 or not stamp - now > AHEAD_LIMIT:
        return None
    return "it is stamped over %s ahead of this node's clock" % _span(stamp - now)


def _span(seconds):
    """A length of time of a day or more, in the largest whole unit it fills."""
    years = int(seconds // _YEAR)
    if years >= 1:
        return '%d year%s' % (years, '' if years == 1 else 's')
    days = int(seconds // _DAY)
    return '%d day%s' % (days, '' if days == 1 else 's')


def outside_problem(stamp, now, span):
    """Why a message stamped `stamp` is more than span s from `now` either way (both in s),
    in words that name the bound, not the stamp; None when it is within, or unset (0)."""
    if stamp == 0.0:
        return None
    if stamp - now > span:
        return 'stamped more than %.3g s ahead of ROS time' % span
    if now - stamp > span:
        return 'stamped more than %.3g s before ROS time' % span
    return None
