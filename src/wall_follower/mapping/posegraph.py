"""A 2-D pose graph: poses tied by measured relative poses, relaxed by least squares.

The mapper's poses of its drawn scans (keyframes) are the nodes; each
keyframe is tied to the one before by the relative pose scan matching
found between them, and a lap's end to its beginning by a match of the
last scan against the map the first scans made (a loop closure). Each
tie alone is nearly right, together they disagree by whatever error the
lap gathered; least squares spreads that error over the lap, each tie
taking a share by its uncertainty, instead of leaving it all at the seam
where the lap closes (a wall drawn twice there).

scipy's least_squares (trust region, sparse Jacobian) solves it, with a
soft-l1 loss so that one tie far off its measurement gives way rather than
bending the whole lap to it. The first pose is held where it is: it is the
map frame's anchor.
"""
import numpy as np
from scipy.optimize import least_squares
from scipy.sparse import coo_matrix

from wall_follower.rotation import wrap_angle

__all__ = ['PoseGraph']


class PoseGraph(object):
    """Poses (x, y, yaw) and ties between them: (i, j, measured pose of j seen from i,
    standard deviations (along, across, yaw) of that measurement)."""

    def __init__(self):
        self.poses = []
        self.ties = []

    def __len__(self):
        return len(self.poses)

    def add_pose(self, pose):
        """A new node at pose; returns its index."""
        self.poses.append(tuple(float(v) for v in pose))
        return len(self.poses) - 1

    def tie(self, i, j, measured, sigma):
        """Pose j measured as `measured` (x, y, yaw) in the frame of pose i, with standard
        deviations sigma (x, y, yaw)."""
        if not (0 <= i < len(self.poses) and 0 <= j < len(self.poses)) or i == j:
            raise ValueError('no tie from pose %d to pose %d in a graph of %d'
                             % (i, j, len(self.poses)))
        self.ties.append((i, j, tuple(float(v) for v in measured),
                          tuple(float(v) for v in sigma)))

    def residuals(self, poses=None):
        """The ties' whitened errors (3 per tie) at poses (the graph's own by default)."""
        poses = np.asarray(poses if poses is not None else self.poses, dtype=float)
        return self._errors(poses)[0]

    def relax(self, max_evaluations=50):
        """Move every pose but the first to fit the ties best; returns the largest move
        [m] and turn [rad] any pose made."""
        if len(self.poses) < 2 or not self.ties:
            return 0.0, 0.0
        start = np.asarray(self.poses, dtype=float)

        def poses(free):
            return np.vstack((start[:1], free.reshape(-1, 3)))

        solution = least_squares(lambda free: self._errors(poses(free))[0],
                                 start[1:].reshape(-1),
                                 jac=lambda free: self._jacobian(poses(free)),
                                 method='trf', tr_solver='lsmr',
                                 max_nfev=max_evaluations)
        relaxed = poses(solution.x)
        relaxed[:, 2] = wrap_angle(relaxed[:, 2])
        moved = float(np.hypot(*(relaxed[:, :2] - start[:, :2]).T).max())
        turned = float(np.abs(wrap_angle(relaxed[:, 2] - start[:, 2])).max())
        self.poses = [tuple(float(v) for v in pose) for pose in relaxed]
        return moved, turned

    def _arrays(self):
        i = np.array([t[0] for t in self.ties])
        j = np.array([t[1] for t in self.ties])
        measured = np.array([t[2] for t in self.ties], dtype=float)
        weights = 1.0 / np.array([t[3] for t in self.ties], dtype=float)
        return i, j, measured, weights

    def _errors(self, poses):
        """Whitened errors (3 per tie, flat) at poses (n, 3), and the parts the Jacobian
        is made of."""
        i, j, measured, weights = self._arrays()
        ci, si = np.cos(poses[i, 2]), np.sin(poses[i, 2])
        cm, sm = np.cos(measured[:, 2]), np.sin(measured[:, 2])
        dx, dy = poses[j, 0] - poses[i, 0], poses[j, 1] - poses[i, 1]
        # pose j seen from pose i, less the measurement, turned into the measurement's frame
        lx, ly = ci * dx + si * dy - measured[:, 0], -si * dx + ci * dy - measured[:, 1]
        turn = poses[j, 2] - poses[i, 2] - measured[:, 2]
        errors = np.column_stack((weights[:, 0] * (cm * lx + sm * ly),
                                  weights[:, 1] * (-sm * lx + cm * ly),
                                  weights[:, 2] * wrap_angle(turn)))
        return errors.reshape(-1), (i, j, ci, si, cm, sm, dx, dy, weights)

    def _jacobian(self, poses):
        """The errors' sparse Jacobian in the poses after the first (held)."""
        i, j, ci, si, cm, sm, dx, dy, weights = self._errors(poses)[1]
        count = len(i)
        # d(lx, ly) / d(xi, yi, yaw i) and / d(xj, yj), per tie: (count, 2, k)
        local_i = np.stack((np.column_stack((-ci, -si, -si * dx + ci * dy)),
                            np.column_stack((si, -ci, -ci * dx - si * dy))), axis=1)
        local_j = np.stack((np.column_stack((ci, si)), np.column_stack((-si, ci))), axis=1)
        turn = np.stack((np.column_stack((cm, sm)), np.column_stack((-sm, cm))), axis=1)
        white = weights[:, :2, None]
        block_i = white * np.einsum('nab,nbk->nak', turn, local_i)    # (count, 2, 3)
        block_j = white * np.einsum('nab,nbk->nak', turn, local_j)    # (count, 2, 2)
        rows, cols, values = [], [], []
        tie_rows = 3 * np.arange(count)
        for index, block, sign in ((i, block_i, -1.0), (j, block_j, 1.0)):
            free = index > 0
            base = 3 * (index[free] - 1)
            for r in range(2):
                for k in range(block.shape[2]):
                    rows.append(tie_rows[free] + r)
                    cols.append(base + k)
                    values.append(block[free, r, k])
            rows.append(tie_rows[free] + 2)
            cols.append(base + 2)
            values.append(sign * weights[free, 2])
        return coo_matrix((np.concatenate(values), (np.concatenate(rows), np.concatenate(cols))),
                          shape=(3 * count, 3 * (len(poses) - 1))).tocsr()
