"""The arm's joints against time, as the lab's rqt_plot shows them: positions above,
velocities below, one line a joint. Drawn on a matplotlib Figure of the caller's (a live
window) or saved as a PNG through the Agg canvas, so that no display is needed; with
how long a recording has run (RecordingSpan), where its picture goes (output_path) and
a save that loses no recording to a path it cannot write (save_somewhere).

matplotlib is imported only by save(): a recorder stopped before anything
came never loads it, and on a busy machine that is most of a second less
to start and to end (a Ctrl-C should end a node at once)."""
import os
import tempfile
import threading

# The file a recording is saved as in a directory given as its ~file.
DEFAULT_NAME = 'joint_states.png'


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


def save_somewhere(record, filename):
    """Save the record as filename or, where that cannot be written, next to it under a
    fresh name, or else in the temporary directory: (the path saved, or None if none could
    be written; [(path tried, error)] of the tries that failed)."""
    failures = []
    try:
        save(record, filename)
        return filename, failures
    except (OSError, ValueError) as error:    # ValueError: a format matplotlib lacks
        failures.append((filename, error))
    stem = os.path.splitext(os.path.basename(filename))[0] or 'joint_states'
    for directory in (os.path.dirname(filename), tempfile.gettempdir()):
        try:
            handle, path = tempfile.mkstemp(prefix=stem + '-', suffix='.png', dir=directory)
            os.close(handle)
        except OSError as error:
            failures.append((os.path.join(directory, stem + '-*.png'), error))
            continue
        try:
            save(record, path)
            return path, failures
        except (OSError, ValueError) as error:
            failures.append((path, error))
            os.unlink(path)
    return None, failures


def output_path(name):
    """The absolute path a recording given ~file name is saved as: a directory (one that
    exists, or a name ending in a separator) holds it as DEFAULT_NAME; a name with no
    extension gets .png (as matplotlib would add it)."""
    path = os.path.abspath(os.path.expanduser(name))
    if os.path.isdir(path) or name.endswith(os.sep):
        return os.path.join(path, DEFAULT_NAME)
    if not os.path.splitext(path)[1]:
        return path + '.png'
    return path


class RecordingSpan(object):
    """How long a recording has run, against the duration it is to run [s] (0: until
    stopped): ROS time (simulated time under /use_sim_time) where it goes forward, and
    wall time while it does not (no /clock yet, a paused or frozen simulation, a clock
    set back), so that a recording ends after its duration whatever comes."""

    def __init__(self, duration, ros_now, wall_now):
        self.duration = duration
        self.elapsed = 0.0
        self._ros, self._wall = ros_now, wall_now

    def update(self, ros_now, wall_now):
        """Count the time since the last call (ROS and wall time now [s]); True once the
        duration has passed."""
        ros_step, wall_step = ros_now - self._ros, wall_now - self._wall
        # ROS time 0 is no time yet: its first jump to the clock's value is not run time
        self.elapsed += ros_step if self._ros > 0.0 and ros_step > 0.0 else max(wall_step, 0.0)
        self._ros, self._wall = ros_now, wall_now
        return self.duration > 0.0 and self.elapsed >= self.duration
