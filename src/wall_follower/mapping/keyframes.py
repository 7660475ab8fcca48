"""The scans drawn into the map (keyframes), as a pose graph, and when a loop closes.

Each keyframe keeps its beams' ends in the robot's frame, so that the map
can be drawn anew from it where the pose graph (posegraph.py) moves it.
Each is tied to the one before by the poses matching found, with a
keyframe's uncertainty (TIE_SIGMA) growing a little with the travel and
turn between them. Back where it has been, `loop_min_travel` or more before
and within `loop_radius`, the robot's newest keyframe may be tied to the
early one it is beside: the mapper matches it against the map the early
keyframes alone make (slam.py), and `close` ties and relaxes.
"""
import math

import numpy as np

from .posegraph import PoseGraph
from .poses import between
from .tracking import FLOOR

__all__ = ['Keyframe', 'Keyframes']

# The standard deviations (along, across [m], yaw [rad]) of the tie between two keyframes
# in a row and of a loop closure: a match's own, and per metre and radian between them.
TIE_SIGMA = (0.005, 0.005, math.radians(0.25))
TIE_GROWTH = 0.01
# How far (one standard deviation) a lap matched scan by scan may have drifted from its
# start, per metre travelled and radian turned: a loop tie further off than the gate's
# standard deviations of these is a wrong fit of the early map, not a lap's error.
LOOP_DRIFT = 0.01
# Loops are tried at most once every this many metres of travel; after one is closed,
# the next only loop_min_travel later.
LOOP_EVERY = 0.3
# A relaxed graph that moved no keyframe this much [m, rad] leaves the map as it is: half
# a fine cell, or a turn that moves a wall 3 m off by as much.
REDRAW = (0.005, 0.005 / 3.0)


class Keyframe(object):
    """A scan drawn into the map: its node in the graph, its beams' ends in the robot's
    frame and which hit, and how far the robot had travelled and turned in all when it
    was taken [m, rad]."""

    __slots__ = ('node', 'ends', 'hit', 'travel', 'turned')

    def __init__(self, node, ends, hit, travel, turned):
        self.node, self.ends, self.hit = node, ends.astype(np.float32), hit
        self.travel, self.turned = travel, turned


class Keyframes(object):
    """The keyframes in order, and their pose graph."""

    def __init__(self):
        self.graph = PoseGraph()
        self.frames = []
        self._tried = None        # travel from which the next loop may be tried

    def __len__(self):
        return len(self.frames)

    def __iter__(self):
        return iter(self.frames)

    def pose(self, keyframe):
        return self.graph.poses[keyframe.node]

    def add(self, pose, ends, hit, travel, turned):
        """A keyframe at pose, tied to the one before; returns it."""
        node = self.graph.add_pose(pose)
        if self.frames:
            before = self.frames[-1]
            grow = TIE_GROWTH * ((travel - before.travel) + (turned - before.turned))
            self.graph.tie(before.node, node, between(self.pose(before), pose),
                           tuple(sigma + grow for sigma in TIE_SIGMA))
        self.frames.append(Keyframe(node, ends, hit, travel, turned))
        return self.frames[-1]

    def loop(self, min_travel, radius):
        """(the early keyframe the newest is back beside, the early keyframes within
        twice radius of its travel) when a loop is due to be tried; else None."""
        newest = self.frames[-1]
        if self._tried is not None and newest.travel < self._tried:
            return None
        here = self.pose(newest)
        early = [k for k in self.frames if newest.travel - k.travel >= min_travel]
        near = [(math.hypot(self.pose(k)[0] - here[0], self.pose(k)[1] - here[1]), k.node, k)
                for k in early]
        near = [item for item in near if item[0] <= radius]
        if not near:
            return None
        self._tried = newest.travel + LOOP_EVERY
        anchor = min(near)[2]
        return anchor, [k for k in early if abs(k.travel - anchor.travel) <= 2.0 * radius]

    def allowed(self, anchor, gate):
        """The largest loop error (metres, radians) a lap from anchor to the newest
        keyframe may have gathered."""
        newest = self.frames[-1]
        return (gate * (FLOOR[0] + LOOP_DRIFT * (newest.travel - anchor.travel)),
                gate * (FLOOR[1] + LOOP_DRIFT * (newest.turned - anchor.turned)))

    def close(self, anchor, measured, min_travel):
        """Tie the newest keyframe to anchor, measured (its pose seen from anchor's),
        and relax the graph; returns the largest move and turn [m, rad] of a keyframe.
        The next loop is tried min_travel later."""
        newest = self.frames[-1]
        self.graph.tie(anchor.node, newest.node, measured, TIE_SIGMA)
        self._tried = newest.travel + min_travel
        return self.graph.relax()
