"""The wall follower's states, and what the manoeuvre that drives each one offers.

The follower (follower.py) is a state machine with one manoeuvre per
state: follow_wall.FollowWall (FOLLOW), inner_corner.InnerCorner
(WALL_AHEAD), outer_corner.OuterCorner (OUTER_CORNER) and search.Search
(SEARCH). Each owns what it has to remember while it is flown and says
when it is done; the machine decides what comes next.
"""

FOLLOW = 'FOLLOW'
WALL_AHEAD = 'WALL_AHEAD'
OUTER_CORNER = 'OUTER_CORNER'
SEARCH = 'SEARCH'


class Manoeuvre(object):
    """One state's behaviour, fed an Observation at every update.

    The machine calls begin() on entering the state, carry_on() at every
    later update in it and end() on leaving it, and then command() at every
    update in it. The hooks do nothing unless a manoeuvre has something to
    carry from one scan to the next.
    """

    def __init__(self, params):
        self.params = params

    def begin(self, obs, previous):
        """Start, on an Observation, from the state previous."""

    def carry_on(self, obs, motion, dt):
        """Move on by one update: motion, the Command driven for the last dt seconds."""

    def end(self):
        """Forget what was only meant for this time round."""

    def done(self, obs):
        """True when this manoeuvre has reached its end on this Observation."""
        raise NotImplementedError

    def command(self, obs):
        """The Command to drive now, before the follower's limits."""
        raise NotImplementedError
