"""A picture of a line-following run: the course's line and the base's true path over it."""
import matplotlib

matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)
from matplotlib.patches import Circle  # noqa: E402

LINE_COLOUR = '#e6c800'


def plot_line_run(centreline, poses, record, filename, title='', end_distance=None):
    """Save a PNG of the line (its true width), the base's true path, where it started,
    the worst cross-track error, where it stopped and, on an open line, its end with the
    circle of end_distance [m] a stop must fall in.

    poses: (N, >=3) true (t, x, y, ...); record: line_record.run_record's.
    """
    fig, ax = plt.subplots(figsize=(6, 5))
    points = centreline.points
    ax.plot(points[:, 0], points[:, 1], '-', color=LINE_COLOUR, lw=4, solid_capstyle='butt',
            label='the line (%.1f cm wide, drawn wider)' % (100.0 * centreline.width))
    ax.plot(points[:, 0], points[:, 1], '-', color='0.4', lw=0.5, label='its centreline')
    if not centreline.closed:
        ax.plot([centreline.end[0]], [centreline.end[1]], 'o', color='black', ms=4,
                label="the line's end")
        if end_distance:
            ax.add_patch(Circle(centreline.end, end_distance, fill=False, ls='--', lw=0.8,
                                color='black'))
    if len(poses):
        ax.plot([p[1] for p in poses], [p[2] for p in poses], '-', color='tab:blue', lw=1,
                label='the base, true path')
        ax.plot([poses[0][1]], [poses[0][2]], 's', color='tab:green', ms=7, label='start')
    tracking = record.get('tracking')
    if tracking:
        worst = tracking['worst']
        ax.plot([worst['x']], [worst['y']], 'x', color='tab:red', ms=9, mew=2,
                label='worst: %.1f cm off' % (100.0 * tracking['max']))
    stop = record.get('stop')
    if stop:
        ax.plot([stop['x']], [stop['y']], 'D', color='black', mfc='none', ms=8,
                label='stop: %.2f m from the end' % stop['end_distance'])
    ax.autoscale()
    ax.set_aspect('equal')
    ax.set_xlabel('x [m]')
    ax.set_ylabel('y [m]')
    ax.set_title(title, fontsize='small')
    ax.legend(loc='best', fontsize='x-small')
    fig.tight_layout()
    fig.savefig(filename, dpi=100)
    plt.close(fig)
