"""Parameters of the slam node (the package's mapper): the node's own, then the mapper's.

Named as gmapping names the same settings (base_frame, map_update_interval,
delta, xmin, ...), so that a launch file can hand either mapper the same
values. The frames and the grids' cells and extent shape a map being
built and are read at start only (READ_AT_START); the rest can be tuned
live through dynamic_reconfigure and applies from the next scan.
"""
import math

from wall_follower.params import Parameter as P, Section, names

FRAMES = Section('frames', (
    P('base_frame', 'base_footprint', "the robot's frame in the odometry's tf; read at start"),
    P('odom_frame', 'odom', "the odometry's frame; read at start"),
    P('map_frame', 'map', 'the frame of the map, published as map_frame -> odom_frame; '
      'read at start'),
))

NODE = (
    FRAMES,
    Section('publishing', (
        P('map_update_interval', 2.0, 'publish map and map_metadata every this many seconds '
          'of ROS time [s]; 0: at every scan', 0.0, 3600.0),
        P('odom_timeout', 1.0, "how long to wait for odometry at or after a scan's stamp "
          'before skipping the scan [wall s]', 0.01, 60.0),
    )),
)
"""The node's own parameters (wall_follower.nodes.mapping.slam)."""

GRID = Section('grid', (
    P('delta', 0.05, "cell of the published map [m], as gmapping's delta; read at start",
      0.005, 1.0),
    P('xmin', -10.0, 'the map frame the grids cover, from xmin ... [m]; the published map is '
      'cropped to the part observed; read at start', -100.0, 100.0),
    P('ymin', -10.0, '... and ymin ... [m]; read at start', -100.0, 100.0),
    P('xmax', 10.0, '... to xmax ... [m]; read at start', -100.0, 100.0),
    P('ymax', 10.0, '... and ymax [m]; read at start', -100.0, 100.0),
    P('match_resolution', 0.01, 'cell of the fine grid scans are matched against [m]; read at '
      'start', 0.002, 0.5),
))

MAPPER = (
    GRID,
    Section('updates', (
        P('max_range', 3.5, 'beams are used up to this range; longer ones only clear space [m]',
          0.1, 100.0),
        P('linear_update', 0.15, 'draw a scan into the map after this much travel [m] ...',
          0.0, 10.0),
        P('angular_update', 0.15, '... or this much turning since the last one drawn [rad]',
          0.0, math.pi),
        P('hit_logodds', 0.85, 'log-odds added to the cell a beam ends in', 0.0, 10.0),
        P('miss_logodds', -0.4, 'log-odds added to each cell a beam crosses', -10.0, 0.0),
        P('start_patience', 100, 'the map starts at the first scan taken at rest, or after this '
          'many scans at the first that did not turn', 0, 100000),
    )),
    Section('matching', (
        P('scan_matching', True, 'false: odometry alone places every scan (to compare)'),
        P('match_capture', 0.3, "the matcher's first pass weighs scan points this near a "
          'mapped wall [m] ...', 0.01, 2.0),
        P('match_reach', 0.1, '... its last pass those this near; farther ones are not matched '
          '[m]', 0.01, 2.0),
        P('search_window_linear', 0.15, "a match may move the robot at most this far from "
          "odometry's prediction [m] ...", 0.0, 5.0),
        P('search_window_angular', math.radians(10.0), '... and turn it at most this much '
          '[rad]; beyond either, the prediction is kept (unless it no longer fits the scan and '
          'the match is certain)', 0.0, math.pi),
        P('odom_drift', 0.05, "the share of its travel and turn the odometry may get wrong (one "
          "standard deviation): the prediction's uncertainty grows by it", 0.001, 1.0),
        P('match_gate', 3.0, "a match may correct the odometry's prediction by at most this "
          'many standard deviations of the two together; beyond, the prediction is kept and '
          'the scan not drawn', 0.5, 100.0),
        P('match_join_gap', 0.1, 'the hits of neighbouring beams this close are joined by a '
          'wall in the fine grid scans are matched against; 0: never [m]', 0.0, 1.0),
        P('match_min_explained', 0.8, 'a match is trusted only if this share of the scan '
          "points on the map's seen part lie within match_reach of a wall; a scan not trusted "
          'is not drawn', 0.0, 1.0),
        P('match_max_misfit', 0.02, '... and those lie this near it (RMS) [m]', 0.001, 1.0),
        P('match_max_sigma', 0.02, "a scan is drawn only where the pose (match and odometry's "
          'prediction together) is this certain along its worst direction (one standard '
          'deviation, a heading as the shift it makes 1 m away) [m]', 0.0001, 1.0),
    )),
    Section('loop closure', (
        P('loop_closure', True, 'close loops: back where it has been, tie the scan to the '
          'early ones, relax the pose graph and redraw the map'),
        P('loop_min_travel', 3.0, 'a loop is closed with scans at least this much travel '
          'before [m] ...', 0.1, 1000.0),
        P('loop_radius', 0.5, '... that lie within this distance of the robot [m]', 0.05,
          10.0),
    )),
)
"""The mapper's parameters (wall_follower.mapping.slam.Mapper)."""

# The most cells the two grids may hold together. Each cell of the fine grid takes about
# ten bytes (log-odds, observed, distance field) and scipy's distance transform several
# times that over the observed part while it runs: this bounds the mapper to a few hundred
# MB, where a slip in the extent or a cell could otherwise ask for many GB at start.
MAX_CELLS = 20000000


def grid_shape(resolution, xmin, ymin, xmax, ymax):
    """(rows, cols) of the mapper's grid of `resolution` over [xmin, xmax) x [ymin, ymax)."""
    cols = int(math.ceil((xmax - xmin) / resolution - 1e-9))
    rows = int(math.ceil((ymax - ymin) / resolution - 1e-9))
    return rows, cols


def grid_cells(resolution, xmin, ymin, xmax, ymax):
    rows, cols = grid_shape(resolution, xmin, ymin, xmax, ymax)
    return rows * cols


def _extent_not_empty(values):
    for low, high in (('xmin', 'xmax'), ('ymin', 'ymax')):
        if values[high] <= values[low]:
            return '%s (%r) must be above %s (%r)' % (high, values[high], low, values[low])
    return None


def _cells_within_memory(values):
    if _extent_not_empty(values) is not None:
        return None     # said by that rule
    box = (values['xmin'], values['ymin'], values['xmax'], values['ymax'])
    cells = grid_cells(values['delta'], *box) + grid_cells(values['match_resolution'], *box)
    if cells > MAX_CELLS:
        return ('xmin, xmax, ymin, ymax, delta and match_resolution ask for %d cells in the '
                'two grids, more than the %d allowed: narrow the extent or coarsen the cells' % (
                    cells, MAX_CELLS))
    return None


RULES = (_extent_not_empty, _cells_within_memory)
"""What the grids' values must satisfy together (params.checked's rules): an extent that is
not empty, and cells in total that fit in memory."""

TABLE = NODE + MAPPER

READ_AT_START = names((FRAMES, GRID))
"""What a live map cannot change: a change through dynamic_reconfigure is refused."""
