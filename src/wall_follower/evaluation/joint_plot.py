"""The arm's joints against time, as the lab's rqt_plot shows them: positions above,
velocities below, one line a joint. Drawn on a matplotlib Figure of the caller's (a live
window) or saved as a PNG through the Agg canvas, so that no display is needed.

matplotlib is imported only by save(): a recorder stopped before anything
came never loads it, and on a busy machine that is most of a second less
to start and to end (a Ctrl-C should end a node at once)."""
import threading


class JointRecord(object):
    """joint_states as they come: times [s], and positions and velocities by joint name.

    add() may be called from a subscriber's thread while another draws.
    """

    def __init__(self):
        self._lock = threading.Lock()
        self.times = []
        self.positions = {}
        self.velocities = {}

    def add(self, stamp, names, positions, velocities):
        """One joint_states message: stamp [s]; velocities may be empty."""
        with self._lock:
            for name in names:
                if name not in self.positions:
                    self.positions[name] = [float('nan')] * len(self.times)
                    self.velocities[name] = [float('nan')] * len(self.times)
            self.times.append(stamp)
            given = dict(zip(names, positions))
            speeds = dict(zip(names, velocities)) if len(velocities) == len(names) else {}
            for name in self.positions:
                self.positions[name].append(given.get(name, float('nan')))
                self.velocities[name].append(speeds.get(name, float('nan')))

    def copy(self):
        """(times, positions, velocities) as they are now."""
        with self._lock:
            return (list(self.times), dict((k, list(v)) for k, v in self.positions.items()),
                    dict((k, list(v)) for k, v in self.velocities.items()))


def draw(figure, record, window=None):
    """Draw record on figure (cleared first): the last window seconds, or all."""
    times, positions, velocities = record.copy()
    figure.clear()
    above, below = figure.subplots(2, 1, sharex=True)
    start = times[0] if times else 0.0
    first = 0
    if window is not None and times:
        first = next(i for i, t in enumerate(times) if t >= times[-1] - window)
    elapsed = [t - start for t in times[first:]]
    for name in sorted(positions):
        above.plot(elapsed, positions[name][first:], label=name)
        below.plot(elapsed, velocities[name][first:], label=name)
    above.set_ylabel('position [rad]')
    below.set_ylabel('velocity [rad/s]')
    below.set_xlabel('time since the first joint_states [s]')
    above.set_title('joint_states')
    for axes in (above, below):
        axes.grid(True)
        if positions:
            axes.legend(loc='upper right', fontsize='small')


def save(record, filename):
    """Save the whole record as a PNG."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    figure = Figure(figsize=(8, 6))
    FigureCanvasAgg(figure)
    draw(figure, record)
    figure.tight_layout()
    figure.savefig(filename, dpi=100)
