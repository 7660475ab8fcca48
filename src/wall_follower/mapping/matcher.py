"""Scan matching: the pose at which a scan best fits the map built so far.

The map's occupied cells give a distance field: how far each point of the
plane is from the nearest wall cell, capped at `reach`. A scan fits where its
points lie on walls, so Gauss-Newton minimises the sum of their squared
distances (the likelihood-field model of AMCL and Cartographer, solved as
Hector SLAM solves its own), with the field interpolated bilinearly so the
pose comes out finer than a cell, starting from the pose odometry predicts.
Points farther than a reach from any wall (a part of the room not mapped
yet) carry no weight. Matching runs in passes of shrinking reach: a wide
first pass pulls in far points, which alone tell a small turn (near a
wall, turning mostly slides its points along it), and a narrow last pass
keeps stray points from tilting the fit. The field comes from a fine grid, not the published
one, so that walls stay where the beams ended rather than at the centres of
coarse cells.

A match is good only if it explains the scan, closely and without doubt:
- its score: of the scan's points that fall on the part of the map already
  seen, at least `min_explained` must lie within the last reach of a wall,
  and those must lie there within `max_misfit` (RMS). A point on a cell
  never seen is new, and tells nothing; one in a cell the map has seen free
  contradicts the pose. A fit caught on the wrong walls puts points into
  the room's free space, or leaves them centimetres off the walls they
  touch: a pose 10 degrees off in a room of slanted walls still had every
  point within 0.1 m of some wall, 5 cm off them;
- and with it, its covariance: the pose's uncertainty from the fit (the
  residuals' variance through the inverse of the Gauss-Newton Hessian). A
  long corridor, a single wall, a scan mostly of new walls leave a
  direction the fit cannot tell, and the covariance says which.
Whether a good match may move the robot where it says is the mapper's
question (slam.py, tracking.py): a good fit far from where odometry puts
the robot may be the wrong one of two (an octagon fits itself turned 45
degrees).
"""
import math

import numpy as np
from scipy.ndimage import distance_transform_edt

from wall_follower.rotation import wrap_angle

__all__ = ['DistanceField', 'ScanMatcher', 'Match']

# How far a scan's point may lie off the wall it hit for no fault of the pose [m]: the
# floor of the residuals' spread in a match's covariance, and the unit in which a prior
# weighs against the points. A laser's errors are not independent from point to point (a
# simulator raytraces on a grid, a real beam is wide), so this is their common part, not
# the spread of one point alone.
POINT_NOISE = 0.01
# A point this near a wall counts though its cell was never seen: it lies behind the wall
# (a pose a little off puts some there), where no beam looks [m].
BEHIND = 0.03


def _information(covariance, yaw):
    """The information (inverse covariance) in the map frame of a covariance given in the
    frame of a pose heading yaw."""
    c, s = math.cos(yaw), math.sin(yaw)
    turn = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    return np.linalg.inv(turn.dot(covariance).dot(turn.T))


class DistanceField(object):
    """Distance [m] from each cell centre of a LogOddsGrid to its nearest occupied one."""

    def __init__(self, grid, reach):
        self.grid = grid
        self.reach = float(reach)
        self.values = np.full(grid.shape, self.reach, dtype=np.float32)

    def set_reach(self, reach):
        """Cap the distances at reach from now on, recomputed over the observed part."""
        if reach != self.reach:
            self.reach = float(reach)
            self.values.fill(self.reach)
            self.update()

    def update(self):
        """Recompute over the observed part of the grid (after the grid has changed)."""
        margin = int(math.ceil(self.reach / self.grid.resolution)) + 1
        box = self.grid.observed_box(margin=margin)
        if box is None:
            return
        r0, r1, c0, c1 = box
        free = self.grid.logodds[r0:r1, c0:c1] <= 0.0
        if free.all():
            return
        distance = distance_transform_edt(free) * self.grid.resolution
        self.values[r0:r1, c0:c1] = np.minimum(distance, self.reach)

    def sample(self, points):
        """Distance and its gradient at (N, 2) map-frame points; `reach` outside the grid."""
        res = self.grid.resolution
        u = (points[:, 0] - self.grid.origin[0]) / res - 0.5   # cell centres at integers
        v = (points[:, 1] - self.grid.origin[1]) / res - 0.5
        c0 = np.floor(u).astype(np.int64)
        r0 = np.floor(v).astype(np.int64)
        fu, fv = u - c0, v - r0
        rows, cols = self.values.shape
        inside = (c0 >= 0) & (r0 >= 0) & (c0 < cols - 1) & (r0 < rows - 1)
        c0, r0 = np.where(inside, c0, 0), np.where(inside, r0, 0)
        m00 = self.values[r0, c0]
        m01 = self.values[r0, c0 + 1]
        m10 = self.values[r0 + 1, c0]
        m11 = self.values[r0 + 1, c0 + 1]
        value = (1 - fv) * ((1 - fu) * m00 + fu * m01) + fv * ((1 - fu) * m10 + fu * m11)
        du = (1 - fv) * (m01 - m00) + fv * (m11 - m10)
        dv = (1 - fu) * (m10 - m00) + fu * (m11 - m01)
        zero = np.zeros_like(value)
        return (np.where(inside, value, self.reach), np.where(inside, du / res, zero),
                np.where(inside, dv / res, zero))


class Match(object):
    """A matcher's answer: the pose, whether its score is good (see the module), the RMS
    distance of the scan's points within the last reach from the walls there [m],
    the share of its points on the seen part of the map that lie that near a wall
    there, how many points fell on the seen part, the pose's covariance (3 x 3, x y
    yaw; None where the fit could not give one) and why it is not good."""

    __slots__ = ('pose', 'ok', 'misfit', 'explained', 'seen', 'covariance', 'reason')

    def __init__(self, pose, ok, misfit, explained=float('nan'), reason='', seen=0,
                 covariance=None):
        self.pose, self.ok, self.misfit, self.reason = tuple(pose), ok, misfit, reason
        self.explained, self.seen, self.covariance = explained, seen, covariance

    @property
    def sigma(self):
        """The pose's standard deviation along its worst direction [m], the heading's
        counted as the shift it makes 1 m away; inf without a covariance."""
        if self.covariance is None:
            return float('inf')
        return float(math.sqrt(max(np.linalg.eigvalsh(self.covariance).max(), 0.0)))


class ScanMatcher(object):
    """Gauss-Newton alignment of scan points to a DistanceField.

    reaches: the passes, each weighing only points this near a wall [m], at
    most the field's reach. min_points: fewer hits than this are not
    matched, and a match with fewer on the seen part of the map is not
    good. min_explained, max_misfit: a good match's score (see the module).
    """

    def __init__(self, field, reaches=None, iterations=12, min_points=20, damping=1e-3,
                 min_explained=0.8, max_misfit=0.02):
        self.field = field
        self.reaches = tuple(reaches) if reaches else (field.reach,)
        self.iterations = iterations
        self.min_points = min_points
        self.damping = damping
        self.min_explained = min_explained
        self.max_misfit = max_misfit

    def match(self, points, guess, prior=None):
        """Best pose (x, y, yaw) of the robot for base-frame hit points (N, 2), from guess.

        prior: the covariance (3 x 3, in the guess's own frame) of the guess as an
        estimate of its own, or None. With one, the fit weighs the guess too (a
        maximum a posteriori pose): along a direction the scan cannot tell (a
        corridor, one long wall) the pose stays where the guess puts it instead of
        sliding to wherever a wall's mapped end happens to pull, and the match's
        covariance is the two together.
        """
        points = np.asarray(points, dtype=float).reshape(-1, 2)
        if len(points) < self.min_points:
            return Match(guess, False, float('nan'), reason='only %d hits' % len(points))
        information = None if prior is None else _information(prior, guess[2])
        pose = np.array(guess, dtype=float)
        px, py = points[:, 0], points[:, 1]
        step_limit = np.array([self.field.grid.resolution * 2.0] * 2 + [math.radians(2.0)])
        for reach in self.reaches:
            pose = self._descend(pose, px, py, reach, step_limit, guess, information)
        pose[2] = wrap_angle(pose[2])
        return self.judge(tuple(float(p) for p in pose), points, information)

    def judge(self, pose, points, information=None):
        """The Match of the base-frame hit points (N, 2) at pose, as it stands;
        information: a prior's (map frame) to add to the scan's in its covariance."""
        points = np.asarray(points, dtype=float).reshape(-1, 2)
        misfit, explained, seen, covariance = self._fit(pose, points[:, 0], points[:, 1],
                                                        information)
        match = Match(pose, False, misfit, explained, seen=seen, covariance=covariance)
        if seen < self.min_points:
            match.reason = 'only %d points on the part of the map seen so far' % seen
        elif explained < self.min_explained:
            match.reason = ('explains %.0f %% of the points on the map seen so far, under '
                            '%.0f %%' % (100.0 * explained, 100.0 * self.min_explained))
        elif not misfit <= self.max_misfit:
            match.reason = 'its points lie %.1f cm (RMS) off the walls, over %.1f cm' % (
                100.0 * misfit, 100.0 * self.max_misfit)
        else:
            match.ok = True
        return match

    def _fit(self, pose, px, py, information=None):
        """How well the points fit at pose: (misfit, explained, count of points on seen
        cells, covariance), as Match has them."""
        c, s = math.cos(pose[2]), math.sin(pose[2])
        world = np.column_stack((pose[0] + c * px - s * py, pose[1] + s * px + c * py))
        residual, gx, gy = self.field.sample(world)
        seen = self._counted(world, residual)
        near = (residual < self.reaches[-1]) & seen
        misfit = float(np.sqrt(np.mean(residual[near] ** 2))) if near.any() else float('nan')
        count = int(seen.sum())
        explained = float(near[seen].mean()) if count else float('nan')
        return misfit, explained, count, self._covariance(near, residual, gx, gy, c, s, px, py,
                                                          information)

    def _covariance(self, near, residual, gx, gy, c, s, px, py, information):
        """The pose's covariance from the points near a wall (their residuals' variance,
        at least POINT_NOISE's, through the Hessian) and the prior's information;
        None if singular."""
        used = int(near.sum())
        if used <= 3:
            return None
        jac = self._jacobian(gx[near], gy[near], c, s, px[near], py[near])
        variance = max(float((residual[near] ** 2).sum()) / (used - 3), POINT_NOISE ** 2)
        total = jac.T.dot(jac) / variance
        if information is not None:
            total = total + information
        try:
            return np.linalg.inv(total)
        except np.linalg.LinAlgError:
            return None

    def _counted(self, points, residual):
        """Which map-frame points (N, 2), at these distances from the walls, confirm or
        refute a pose: those on cells the map has observed, or just behind a wall
        (within BEHIND; no beam sees behind a wall). A point on a cell never seen,
        further from a wall, is a wall not mapped yet, often the continuation of one
        that is: weighed, it pulls the scan back towards the mapped wall's end, along
        a corridor the robot drives into."""
        rows, cols, inside = self.field.grid.cells(points)
        seen = residual < BEHIND
        seen[inside] |= self.field.grid.observed[rows[inside], cols[inside]]
        return seen

    @staticmethod
    def _jacobian(gx, gy, c, s, px, py):
        return np.column_stack((gx, gy, gx * (-s * px - c * py) + gy * (c * px - s * py)))

    def _descend(self, pose, px, py, reach, step_limit, guess, information):
        """Gauss-Newton steps from pose, weighing the points within reach of a wall,
        and the guess by its information (None: not at all)."""
        for _ in range(self.iterations):
            c, s = math.cos(pose[2]), math.sin(pose[2])
            world = np.column_stack((pose[0] + c * px - s * py, pose[1] + s * px + c * py))
            residual, gx, gy = self.field.sample(world)
            weight = ((residual < reach) & self._counted(world, residual)).astype(float)
            jac = self._jacobian(gx, gy, c, s, px, py)
            hessian = (jac * weight[:, None]).T.dot(jac) + self.damping * np.eye(3)
            gradient = (jac * weight[:, None]).T.dot(residual)
            if information is not None:
                # in units of the points' squared distances: POINT_NOISE each
                prior = information * POINT_NOISE ** 2
                off = pose - np.asarray(guess, dtype=float)
                off[2] = wrap_angle(off[2])
                hessian = hessian + prior
                gradient = gradient + prior.dot(off)
            delta = -np.linalg.solve(hessian, gradient)
            delta = np.clip(delta, -step_limit, step_limit)
            pose += delta
            if abs(delta[0]) < 1e-5 and abs(delta[1]) < 1e-5 and abs(delta[2]) < 1e-5:
                break
        return pose
