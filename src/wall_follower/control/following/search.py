"""SEARCH: no wall near, so straight ahead until one comes up."""
from wall_follower.control.following.manoeuvre import Manoeuvre
from wall_follower.control.motion import Command


class Search(Manoeuvre):
    """Straight ahead at search_speed until a wall is seen on the right.

    A wall that comes up ahead instead is turned for by the left turn,
    which takes over from any state.
    """

    def done(self, obs):
        return obs.wall is not None

    def command(self, obs):
        return Command(self.params.search_speed, 0.0)
