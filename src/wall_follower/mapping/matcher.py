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

A match is trusted only if it explains the scan: of the scan's points that
fall on the part of the map already seen, at least `min_explained` must lie
within the last reach of a wall. It must also stay within the search window
of the prediction, unless the prediction does not explain the scan and the
match does: the odometry slipped, and keeping its prediction would leave
the robot lost for good. A point on a cell never seen is new, and tells
nothing; one in a cell the map has seen free contradicts the pose. A scan
placed wrong, by odometry that slipped beyond the window or by a fit
caught on the wrong walls, puts many of its points into the room's free
space, and would draw walls where there are none (beyond the true ones,
where no later beam ever clears them).
"""
import math

import numpy as np
from scipy.ndimage import distance_transform_edt

__all__ = ['DistanceField', 'ScanMatcher', 'Match']


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
    """A matcher's answer: the pose, whether it is trusted, the RMS distance of the
    scan's points within the last reach from the walls there [m], the share of its
    points on the seen part of the map that lie that near a wall there, and why it
    is not trusted."""

    __slots__ = ('pose', 'ok', 'misfit', 'explained', 'reason')

    def __init__(self, pose, ok, misfit, explained=float('nan'), reason=''):
        self.pose, self.ok, self.misfit, self.reason = pose, ok, misfit, reason
        self.explained = explained


class ScanMatcher(object):
    """Gauss-Newton alignment of scan points to a DistanceField.

    window: (metres, radians) the match may move from the odometry's
    prediction; a match that goes farther is not trusted and the prediction
    is kept, unless the prediction does not explain the scan and the match
    does. reaches: the passes, each weighing only points this near a
    wall [m], at most the field's reach. min_points: fewer hits than this
    are not matched, and a match with fewer on the seen part of the map is
    not trusted. min_explained: the share of those a trusted match puts
    within the last reach of a wall.
    """

    def __init__(self, field, window, reaches=None, iterations=12, min_points=20, damping=1e-3,
                 min_explained=0.8):
        self.field = field
        self.window = window
        self.reaches = tuple(reaches) if reaches else (field.reach,)
        self.iterations = iterations
        self.min_points = min_points
        self.damping = damping
        self.min_explained = min_explained

    def match(self, points, guess):
        """Best pose (x, y, yaw) of the robot for base-frame hit points (N, 2), from guess."""
        points = np.asarray(points, dtype=float).reshape(-1, 2)
        if len(points) < self.min_points:
            return Match(tuple(guess), False, float('nan'), reason='only %d hits' % len(points))
        pose = np.array(guess, dtype=float)
        px, py = points[:, 0], points[:, 1]
        step_limit = np.array([self.field.grid.resolution * 2.0] * 2 + [math.radians(2.0)])
        for reach in self.reaches:
            pose = self._descend(pose, px, py, reach, step_limit)
        pose[2] = math.atan2(math.sin(pose[2]), math.cos(pose[2]))
        moved = math.hypot(pose[0] - guess[0], pose[1] - guess[1])
        turned = abs(math.atan2(math.sin(pose[2] - guess[2]), math.cos(pose[2] - guess[2])))
        misfit, explained, seen = self._fit(pose, px, py)
        pose = tuple(float(p) for p in pose)
        if moved > self.window[0] or turned > self.window[1]:
            kept = self._fit(guess, px, py)
            if not (seen >= self.min_points and explained >= self.min_explained
                    > kept[1]):
                return Match(tuple(guess), False, kept[0], kept[1],
                             'moved %.3f m, %.1f deg from odometry: beyond the search window'
                             % (moved, math.degrees(turned)))
        if seen < self.min_points:
            return Match(tuple(guess), False, misfit, explained,
                         'only %d points on the part of the map seen so far' % seen)
        if explained < self.min_explained:
            return Match(tuple(guess), False, misfit, explained,
                         'explains %.0f %% of the points on the map seen so far, under %.0f %%'
                         % (100.0 * explained, 100.0 * self.min_explained))
        return Match(pose, True, misfit, explained)

    def _fit(self, pose, px, py):
        """How well the points fit at pose: (misfit, explained, count of points on seen
        cells), as Match has them."""
        c, s = math.cos(pose[2]), math.sin(pose[2])
        world = np.column_stack((pose[0] + c * px - s * py, pose[1] + s * px + c * py))
        residual = self.field.sample(world)[0]
        near = residual < self.reaches[-1]
        misfit = float(np.sqrt(np.mean(residual[near] ** 2))) if near.any() else float('nan')
        rows, cols, inside = self.field.grid.cells(world)
        seen = np.zeros(len(world), dtype=bool)
        seen[inside] = self.field.grid.observed[rows[inside], cols[inside]]
        count = int(seen.sum())
        explained = float(near[seen].mean()) if count else float('nan')
        return misfit, explained, count

    def _descend(self, pose, px, py, reach, step_limit):
        """Gauss-Newton steps from pose, weighing the points within reach of a wall."""
        for _ in range(self.iterations):
            c, s = math.cos(pose[2]), math.sin(pose[2])
            world = np.column_stack((pose[0] + c * px - s * py, pose[1] + s * px + c * py))
            residual, gx, gy = self.field.sample(world)
            weight = (residual < reach).astype(float)
            jac = np.column_stack((gx, gy, gx * (-s * px - c * py) + gy * (c * px - s * py)))
            hessian = (jac * weight[:, None]).T.dot(jac) + self.damping * np.eye(3)
            delta = -np.linalg.solve(hessian, (jac * weight[:, None]).T.dot(residual))
            delta = np.clip(delta, -step_limit, step_limit)
            pose += delta
            if abs(delta[0]) < 1e-5 and abs(delta[1]) < 1e-5 and abs(delta[2]) < 1e-5:
                break
        return pose
