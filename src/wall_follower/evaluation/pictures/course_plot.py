"""A picture of a run: the recorded points and the true path over the world's map."""
import matplotlib

matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)
from matplotlib.collections import LineCollection  # noqa: E402


def points_label(count, span=None):
    """The legend of the recorded points: what they are, how many, over how long."""
    label = '%d record_odom point%s' % (count, '' if count == 1 else 's')
    if span is not None and count > 1:
        label += ' over %.0f s' % span
    return label


def plot_course(course_map, trail, points, filename, title='', start=None, points_span=None):
    """Save a PNG of the map's obstacles, the true path and the recorded points.

    trail: (x, y) ground-truth positions; points: (x, y, yaw) as recorded
    by record_odom; start: the robot's true start (x, y, ...), marked even
    when it never moved; points_span: simulated seconds from the first
    point to the last, for the legend.
    """
    fig, ax = plt.subplots(figsize=(7, 6))
    ax.add_collection(LineCollection(course_map.edges, colors='black', linewidths=1.5))
    if trail:
        xs, ys = zip(*trail)
        ax.plot(xs, ys, '-', color='tab:blue', lw=1, label='true path')
    if start is not None:
        ax.plot([start[0]], [start[1]], '^', color='black', ms=9, label='start')
    if points:
        xs, ys, yaws = zip(*points)
        ax.plot(xs, ys, 'o', color='tab:red', ms=3, label=points_label(len(points), points_span))
        ax.plot(xs[:1], ys[:1], 's', color='tab:green', ms=8, label='first point')
    ax.autoscale()
    ax.set_aspect('equal')
    ax.set_xlabel('x [m]')
    ax.set_ylabel('y [m]')
    ax.set_title(title)
    ax.legend(loc='best', fontsize='small')
    fig.tight_layout()
    fig.savefig(filename, dpi=120)
    plt.close(fig)
