"""Bounded waits of the rostests, for what comes on another connection.

A passing test goes on as soon as the condition holds; the limit only
bounds how long a failing one takes.
"""
import time

POLL = 0.01  # wall seconds


def wait_until(condition, limit):
    """Poll condition() until it holds or `limit` wall seconds have passed; its last value."""
    deadline = time.time() + limit
    while not condition() and time.time() < deadline:
        time.sleep(POLL)
    return condition()


def assert_soon(test, limit, condition, what):
    """Fail test (a unittest.TestCase) unless condition() holds within limit wall seconds."""
    test.assertTrue(wait_until(condition, limit), 'timed out waiting for ' + what)
