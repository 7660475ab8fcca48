"""A parsed world file interpreted as real Stage would: defines applied, models placed and
sized, robots with their ranger and camera, Stage's defaults where a property is missing."""
import math
import os
from collections import OrderedDict

import numpy as np

from ..colors import color_by_name
from ..kinematics import normalize_angle
from .bitmaps import bitmap_edges, black_pixels, boundary_blocks, fit_to_size, polygon_edges
from .parser import Parser, Prop
from .specs import (MAX_CAMERA_PIXELS, MAX_GRID_CELLS, MAX_SAMPLES, STAGE_MENU_BAR,
                    STAGE_VELOCITY_BOUNDS, STAGEROS_WINDOW, CameraSpec, Obstacle, RangerSpec,
                    RobotSpec, World, WorldFileError)
from .tokens import tokenize


# Entity types real Stage knows but this simulator does not model; they are skipped.
_SKIPPED_MODEL_TYPES = frozenset((
    'actuator', 'blinkenlight', 'blobfinder', 'bumper', 'fiducial', 'gripper',
    'laser', 'lightindicator', 'powerpack'))


_TOP_LEVEL_IGNORED = frozenset(('window', 'gui'))


# Stage 4.3's defaults (model_camera.cc, model_ranger.cc).
_CAMERA_RESOLUTION = (32.0, 32.0)


_CAMERA_RANGE = (0.2, 8.0)


_CAMERA_FOV = (70.0, 40.0)


_CAMERA_SIZE = (0.1, 0.07, 0.05)


_CAMERA_COLOR = (0.0, 0.0, 0.0)


_RANGER_SIZE = (0.15, 0.15, 0.2)


_RANGER_COLOR = (0.0, 0.0, 0.5)


_MODEL_COLOR = (1.0, 0.0, 0.0)   # Stage's Model colour and unknown colour names: red


class _Resolved(object):
    """An entity with its define chain applied: base type, merged properties, children."""

    def __init__(self, base, name, props, children, path, line):
        self.base = base
        self.name = name
        self.props = props
        self.children = children
        self.path = path
        self.line = line


class _Interpreter(object):
    def __init__(self, path, parser, root):
        self.path = path
        self.defines = parser.defines
        self.root = root
        self.unknown = []
        self.unit_length = 1.0
        self.unit_angle = math.pi / 180.0
        self.obstacles = []
        self.robots = []
        self.counts = {}
        self.warnings = []
        self.window_area = STAGEROS_WINDOW[0], STAGEROS_WINDOW[1] - STAGE_MENU_BAR

    # -- define chains -------------------------------------------------------------------
    def resolve(self, entity):
        chain = []
        kind = entity.kind
        seen = set()
        while kind in self.defines:
            if kind in seen:
                raise WorldFileError(entity.path, entity.line, 'define cycle through "%s"' % kind)
            seen.add(kind)
            parent, body = self.defines[kind]
            chain.append(body)
            if parent not in self.defines and not _is_base_type(parent):
                raise WorldFileError(body.path, body.line,
                                     'unknown define parent "%s" (define %s %s)'
                                     % (parent, kind, parent))
            kind = parent
        props = OrderedDict()
        children = []
        for body in reversed(chain):
            props.update(body.props)
            children.extend(body.children)
        props.update(entity.props)
        children.extend(entity.children)
        name = _prop_string(props, 'name', None)
        return _Resolved(kind, name, props, children, entity.path, entity.line)

    # -- property access -----------------------------------------------------------------
    def numbers(self, resolved, key, count, default, kinds=None):
        """Tuple property `key` with at least `count` numbers, unit-converted by `kinds`."""
        prop = resolved.props.get(key)
        if prop is None:
            return default
        if len(prop.values) < count:
            raise WorldFileError(prop.path, prop.line, '"%s" needs %d values, got %d'
                                 % (key, count, len(prop.values)))
        out = []
        for i, value in enumerate(prop.values[:count]):
            if not isinstance(value, float):
                raise WorldFileError(prop.path, prop.line, 'bad number %r in "%s"' % (value, key))
            kind = kinds[i] if kinds else 'f'
            out.append(value * (self.unit_length if kind == 'l' else
                                self.unit_angle if kind == 'a' else 1.0))
        return tuple(out)

    def number(self, resolved, key, default, kind='f'):
        value = self.numbers(resolved, key, 1, None, kind)
        return default if value is None else value[0]

    def pose(self, resolved, key='pose'):
        return self.numbers(resolved, key, 4, (0.0, 0.0, 0.0, 0.0), 'llla')

    # -- world ---------------------------------------------------------------------------
    def interpret(self):
        top = _Resolved('', None, self.root.props, self.root.children, self.path, 1)
        length_unit = _prop_string(top.props, 'unit_length', 'm')
        angle_unit = _prop_string(top.props, 'unit_angle', 'degrees')
        self.unit_length = {'m': 1.0, 'cm': 0.01, 'mm': 0.001}.get(length_unit, 1.0)
        self.unit_angle = math.pi / 180.0 if angle_unit.startswith('deg') else 1.0
        resolution = self.number(top, 'resolution', 0.02)
        interval_ms = self.number(top, 'interval_sim', 100.0)
        if resolution <= 0.0:
            prop = top.props['resolution']
            raise WorldFileError(prop.path, prop.line, 'resolution must be positive')
        if interval_ms < 1.0:
            prop = top.props['interval_sim']
            raise WorldFileError(prop.path, prop.line, 'interval_sim must be at least 1 ms')
        known = ('resolution', 'interval_sim', 'speedup', 'quit_time', 'paused', 'unit_length',
                 'unit_angle')
        for key in top.props:
            if key not in known:
                self.unknown.append(key)
        for child in self.root.children:
            if child.kind == 'window':
                self.window(self.resolve(child))
        for child in self.root.children:
            self.top_level_entity(child)
        cells = _cells_spanned(self.obstacles, resolution)
        if cells > MAX_GRID_CELLS:
            prop = top.props.get('resolution') or Prop((), self.path, 0)
            raise WorldFileError(prop.path, prop.line, 'the obstacles span about %d cells of '
                                 'resolution %g m, more than the %d the simulator holds: a '
                                 'coarser resolution or smaller models' % (
                                     cells, resolution, MAX_GRID_CELLS))
        return World(
            path=self.path, resolution=resolution, interval_sim=int(interval_ms) / 1000.0,
            speedup=self.number(top, 'speedup', 1.0), quit_time=self.number(top, 'quit_time', 0.0),
            paused=bool(self.number(top, 'paused', 0.0)), obstacles=self.obstacles,
            robots=self.robots, unknown_keywords=sorted(set(self.unknown)),
            warnings=self.warnings)

    def top_level_entity(self, entity):
        if entity.kind in _TOP_LEVEL_IGNORED:
            return
        resolved = self.resolve(entity)
        if resolved.base == 'model':
            self.model(resolved, parent_pose=None, parent_height=0.0)
        elif resolved.base == 'position':
            self.robot(resolved)
        elif resolved.base == 'camera':
            self.stray_camera(resolved, 'the world')
        else:
            self.unknown.append(entity.kind)

    def window(self, resolved):
        """The drawing area of Stage's window, where real Stage draws (and caps) cameras."""
        width, height = self.numbers(resolved, 'size', 2, STAGEROS_WINDOW)
        if width < 1 or height <= STAGE_MENU_BAR:
            prop = resolved.props['size']
            raise WorldFileError(prop.path, prop.line, 'window size [%g %g] leaves no area to '
                                 'draw a camera in (Stage draws it in the window, below a %d px '
                                 'menu bar; the screen\'s size, asked by a negative size, is not '
                                 'known here)' % (width, height, STAGE_MENU_BAR))
        self.window_area = int(width), int(height) - STAGE_MENU_BAR

    def warn(self, resolved, message):
        self.warnings.append('%s:%d: %s' % (resolved.path, resolved.line, message))

    def stray_camera(self, resolved, where):
        """A camera that is no position's own child: stageros publishes none of it."""
        self.warn(resolved, 'camera "%s" is in %s, not directly in a robot\'s position: it is '
                  'not drawn or published (stageros publishes only the cameras of positions)'
                  % (resolved.name or 'camera', where))

    def _default_name(self, base):
        count = self.counts.get(base, 0)
        self.counts[base] = count + 1
        return '%s:%d' % (base, count)

    # -- static models -------------------------------------------------------------------
    def model(self, resolved, parent_pose, parent_height):
        name = resolved.name or self._default_name('model')
        local = self.pose(resolved)
        size = self.numbers(resolved, 'size', 3, (0.4, 0.4, 1.0), 'lll')
        origin = self.pose(resolved, 'origin')
        if parent_pose is None:
            pose = (local[0], local[1], local[2], normalize_angle(local[3]))
        else:
            pose = _compose4(parent_pose, local, parent_height)
        edges, z_range = self.model_shape(resolved, size)
        base_z = pose[2] + origin[2]
        if len(edges):
            self.obstacles.append(Obstacle(
                name=name, pose=pose, origin=origin, edges=edges,
                z_range=(base_z + z_range[0], base_z + z_range[1]),
                ranger_return=self.number(resolved, 'ranger_return', 1.0),
                obstacle_return=self.number(resolved, 'obstacle_return', 1.0) != 0.0,
                color=self.color(resolved)))
        for child in resolved.children:
            sub = self.resolve(child)
            if sub.base == 'model':
                self.model(sub, pose, size[2])
            elif sub.base == 'camera':
                self.stray_camera(sub, 'model "%s"' % name)
            elif sub.base != 'block':
                self.unknown.append(child.kind)
        self.note_unknown_props(resolved, _MODEL_KEYS)

    def model_shape(self, resolved, size):
        """Edges of a model in its frame, scaled and centred as Stage's CalcSize does."""
        blocks = []   # (directed edges (M, 2, 2), zmin, zmax)
        bitmap = resolved.props.get('bitmap')
        if bitmap is not None:
            blocks.extend(self.bitmap_blocks(bitmap))
        for child in resolved.children:
            if child.kind == 'block':
                blocks.append(self.block(child))
        if not blocks and not self.number(resolved, 'noblocks', 0.0):
            square = np.array([[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]])
            blocks.append((polygon_edges(square), 0.0, 1.0))
        if not blocks:
            return np.zeros((0, 2, 2)), (0.0, 0.0)
        if self.number(resolved, 'boundary', 0.0):
            blocks.extend(boundary_blocks(blocks, size))
        return fit_to_size(blocks, size)

    def block(self, entity):
        block = self.resolve(entity)
        count = int(self.number(block, 'points', 0.0))
        if count < 3:
            raise WorldFileError(entity.path, entity.line,
                                 'block needs "points N" with N >= 3, got %d' % count)
        points = []
        for i in range(count):
            key = 'point[%d]' % i
            if key not in block.props:
                raise WorldFileError(entity.path, entity.line, 'block is missing %s' % key)
            points.append(self.numbers(block, key, 2, None, 'll'))
        zmin, zmax = self.numbers(block, 'z', 2, (0.0, 1.0), 'll')
        return polygon_edges(np.array(points, dtype=float)), zmin, zmax

    def bitmap_blocks(self, prop):
        name = prop.values[0] if prop.values else ''
        if not isinstance(name, str) or not name:
            raise WorldFileError(prop.path, prop.line, 'bitmap needs a file name')
        full = name if os.path.isabs(name) else os.path.join(os.path.dirname(prop.path), name)
        if not os.path.isfile(full):
            raise WorldFileError(prop.path, prop.line, 'missing bitmap file "%s"' % name)
        try:
            black = black_pixels(full)
        except (IOError, OSError, ValueError) as err:
            raise WorldFileError(prop.path, prop.line, 'cannot read bitmap "%s" (%s)' % (name, err))
        edges = bitmap_edges(black)
        if not len(edges):
            raise WorldFileError(prop.path, prop.line, 'bitmap "%s" has no black pixels' % name)
        return [(edges, 0.0, 1.0)]

    # -- robots --------------------------------------------------------------------------
    def robot(self, resolved):
        name = resolved.name or self._default_name('position')
        pose = self.pose(resolved)
        size = self.numbers(resolved, 'size', 3, (0.4, 0.4, 1.0), 'lll')
        origin = self.pose(resolved, 'origin')
        drive = _prop_string(resolved.props, 'drive', 'diff')
        if drive != 'diff':
            prop = resolved.props['drive']
            raise WorldFileError(prop.path, prop.line,
                                 'drive "%s" is not supported (only "diff")' % drive)
        bounds = self.numbers(resolved, 'velocity_bounds', 8, STAGE_VELOCITY_BOUNDS, 'llllllaa')
        odom_error = self.numbers(resolved, 'odom_error', 4, None, 'llla')
        if odom_error is not None:
            odom_error = (odom_error[0], odom_error[1], odom_error[3])
        ranger = None
        camera = None
        for child in resolved.children:
            sub = self.resolve(child)
            if sub.base == 'ranger' and ranger is None:
                ranger = self.ranger(sub, size)
            elif sub.base == 'camera' and camera is None:
                camera = self.camera(sub, size)
            elif sub.base == 'camera':
                self.warn(sub, 'robot "%s" has a second camera: this simulator draws and '
                          'publishes only its first (as image, depth, camera_info), where '
                          'stageros would number them all (image_0, image_1, ...)' % name)
            elif sub.base != 'block':
                self.unknown.append(child.kind)
        self.robots.append(RobotSpec(
            name=name, pose=(pose[0], pose[1], normalize_angle(pose[3])), size=size,
            origin=(origin[0], origin[1], origin[3]), drive=drive,
            localization=_prop_string(resolved.props, 'localization', 'gps'),
            velocity_bounds=bounds, ranger=ranger, odom_error=odom_error,
            color=self.color(resolved), camera=camera))
        self.note_unknown_props(resolved, _POSITION_KEYS)

    def ranger(self, resolved, robot_size):
        for child in resolved.children:
            sub = self.resolve(child)
            if sub.base == 'camera':
                self.stray_camera(sub, 'a ranger')
        sensors = [self.resolve(child) for child in resolved.children if child.kind == 'sensor']
        if not sensors:
            raise WorldFileError(resolved.path, resolved.line, 'ranger has no sensor( ... )')
        sensor = sensors[0]
        pose = self.pose(resolved)
        sensor_pose = self.pose(sensor)
        sensor_size = self.numbers(sensor, 'size', 3, (0.02, 0.02, 0.02), 'lll')
        range_min, range_max = self.numbers(sensor, 'range', 2, (0.0, 5.0), 'll')
        samples = int(self.number(sensor, 'samples', 1.0))
        if not 1 <= samples <= MAX_SAMPLES:
            prop = sensor.props['samples']
            raise WorldFileError(prop.path, prop.line, 'samples must be from 1 to %d, not %d'
                                 % (MAX_SAMPLES, samples))
        noise = self.numbers(sensor, 'noise', 3, (0.0, 0.0, 0.0), 'lfa')
        height = robot_size[2] + pose[2] + sensor_pose[2] + sensor_size[2] / 2.0
        return RangerSpec(pose=pose, sensor_pose=sensor_pose, sensor_height=height,
                          range_min=range_min, range_max=range_max,
                          fov=self.number(sensor, 'fov', 0.1 / self.unit_angle, 'a'),
                          samples=samples, noise=noise,
                          size=self.numbers(resolved, 'size', 3, _RANGER_SIZE, 'lll'),
                          color=self.color(resolved, _RANGER_COLOR))

    def camera(self, resolved, robot_size):
        """A Stage `camera` model; its defaults are Stage 4.3's ModelCamera ones."""
        pose = self.pose(resolved)
        width, height = self.camera_resolution(resolved)
        near, far = self.numbers(resolved, 'range', 2, _CAMERA_RANGE, 'll')
        if not 0.0 < near < far:
            prop = resolved.props['range']
            raise WorldFileError(prop.path, prop.line, 'camera range needs 0 < near < far, got '
                                 '[%g %g]' % (near, far))
        # fov and pantilt are degrees whatever unit_angle says: Stage reads them as "ff".
        hfov, vfov = (math.radians(v) for v in self.numbers(resolved, 'fov', 2, _CAMERA_FOV))
        if not (0.0 < hfov < math.pi and 0.0 < vfov < math.pi):
            prop = resolved.props['fov']
            raise WorldFileError(prop.path, prop.line, 'camera fov must lie between 0 and 180 '
                                 'degrees')
        pan, tilt = self.pantilt(resolved)
        self.note_unknown_props(resolved, _CAMERA_KEYS)
        return CameraSpec(pose=pose, size=self.numbers(resolved, 'size', 3, _CAMERA_SIZE, 'lll'),
                          color=self.color(resolved, _CAMERA_COLOR), resolution=(width, height),
                          range=(near, far),
                          fov=(hfov, vfov), pantilt=(pan, tilt),
                          height=robot_size[2] + pose[2])

    def camera_resolution(self, resolved):
        """(width, height) of a camera's frames: its `resolution`, capped at the window's
        drawing area as real Stage caps it (a warning says so), and refused beyond
        MAX_CAMERA_PIXELS even so."""
        width, height = self.numbers(resolved, 'resolution', 2, _CAMERA_RESOLUTION)
        prop = resolved.props.get('resolution') or Prop((), resolved.path, resolved.line)
        if width < 1 or height < 1 or width != int(width) or height != int(height):
            raise WorldFileError(prop.path, prop.line, 'camera resolution must be two positive '
                                 'whole numbers, got [%g %g]' % (width, height))
        area_width, area_height = self.window_area
        capped = min(int(width), area_width), min(int(height), area_height)
        if capped[0] * capped[1] > MAX_CAMERA_PIXELS:
            raise WorldFileError(prop.path, prop.line, 'camera resolution [%d %d] is more than '
                                 'the %d pixels (1920 x 1080) this simulator draws: it draws '
                                 'on the CPU, about 0.1 us a pixel, and a world step waits for '
                                 'the frame' % (capped + (MAX_CAMERA_PIXELS,)))
        if capped != (width, height):
            self.warnings.append(
                '%s:%d: camera resolution [%d %d] is capped at [%d %d], as real Stage caps it: '
                'it draws the frame in its window, whose drawing area is %d x %d (window size '
                'less the %d px menu bar; stageros opens %d x %d unless `window( size [w h] )` '
                'says)' % ((prop.path, prop.line, width, height) + capped + self.window_area
                           + (STAGE_MENU_BAR,) + STAGEROS_WINDOW))
        return capped

    def pantilt(self, resolved):
        """(pan, tilt) [rad] of a camera. Real Stage turns the view by any angle (a pan
        of 370 deg is one of 10 deg, a tilt beyond 90 deg looks backwards, upside down),
        and so does this simulator; beyond a half turn of pan or a quarter turn of tilt a
        warning says what the angles come to."""
        pan, tilt = self.numbers(resolved, 'pantilt', 2, (0.0, 0.0))
        if abs(pan) > 180.0 or abs(tilt) > 90.0:
            prop = resolved.props['pantilt']
            self.warnings.append(
                '%s:%d: camera pantilt [%g %g] is beyond [-180, 180] x [-90, 90] deg: real '
                'Stage turns by it all the same, and so does this simulator (a pan of %g deg, '
                'a tilt of %g deg%s)' % (prop.path, prop.line, pan, tilt, _half_turn(pan),
                                         _half_turn(tilt), ', looking backwards and upside down'
                                         if abs(_half_turn(tilt)) > 90.0 else ''))
        return math.radians(pan), math.radians(tilt)

    def color(self, resolved, default=_MODEL_COLOR):
        """A model's `color` (a colour name) or `color_rgba`, as (r, g, b) in [0, 1]."""
        if 'color_rgba' in resolved.props:
            rgb = self.numbers(resolved, 'color_rgba', 3, None)
            return tuple(min(max(value, 0.0), 1.0) for value in rgb)
        prop = resolved.props.get('color')
        if prop is None:
            return default
        name = _prop_string(resolved.props, 'color', '')
        try:
            return color_by_name(name)
        except KeyError:
            raise WorldFileError(prop.path, prop.line, 'unknown colour "%s"' % name)

    def note_unknown_props(self, resolved, known):
        for key in resolved.props:
            if key not in known:
                self.unknown.append(key)


_COMMON_KEYS = frozenset((
    'name', 'pose', 'size', 'origin', 'color', 'color_rgba', 'ranger_return', 'obstacle_return',
    'gui_nose', 'gui_grid', 'gui_move', 'gui_outline', 'gripper_return', 'fiducial_return',
    'blob_return', 'laser_return', 'visual_return', 'boundary', 'mass', 'update_interval',
    'noblocks', 'stack_children', 'fiducial_key', 'map_resolution', 'say', 'alwayson', 'watts'))


_MODEL_KEYS = _COMMON_KEYS | frozenset(('bitmap',))


_CAMERA_KEYS = _COMMON_KEYS | frozenset(('resolution', 'range', 'fov', 'pantilt'))


_POSITION_KEYS = _COMMON_KEYS | frozenset((
    'drive', 'localization', 'velocity_bounds', 'acceleration_bounds', 'localization_origin',
    'odom_error', 'wheelbase', 'velocity', 'bitmap'))


def _half_turn(degrees):
    """The same angle in (-180, 180] degrees."""
    turned = (degrees + 180.0) % 360.0 - 180.0
    return 180.0 if turned == -180.0 else turned + 0.0


def _is_base_type(kind):
    return kind in ('model', 'position', 'ranger', 'sensor', 'block', 'camera') or \
        kind in _SKIPPED_MODEL_TYPES


def _prop_string(props, key, default):
    prop = props.get(key)
    if prop is None or not prop.values:
        return default
    value = prop.values[0]
    return value if isinstance(value, str) else default


def _compose4(parent, local, parent_height):
    cosa, sina = math.cos(parent[3]), math.sin(parent[3])
    return (parent[0] + local[0] * cosa - local[1] * sina,
            parent[1] + local[0] * sina + local[1] * cosa,
            parent[2] + parent_height + local[2],
            normalize_angle(parent[3] + local[3]))


def _cells_spanned(obstacles, resolution):
    """About how many cells of resolution the box round every obstacle holds (not fewer):
    each obstacle is taken as the disc round its geometry's centre that holds its edges."""
    if not obstacles:
        return 0
    low, high = np.full(2, np.inf), np.full(2, -np.inf)
    for obstacle in obstacles:
        gx, gy, _, ga = obstacle.pose
        ox, oy = obstacle.origin[0], obstacle.origin[1]
        centre = np.array([gx + ox * math.cos(ga) - oy * math.sin(ga),
                           gy + ox * math.sin(ga) + oy * math.cos(ga)])
        reach = float(np.hypot(obstacle.edges[..., 0], obstacle.edges[..., 1]).max())
        low, high = np.minimum(low, centre - reach), np.maximum(high, centre + reach)
    cols, rows = (high - low) / resolution + 1.0
    return int(math.ceil(cols) * math.ceil(rows))


def load_world(path):
    """Parse the Stage world file at `path` into a World (raises WorldFileError)."""
    if not os.path.isfile(path):
        raise WorldFileError(path, 0, 'world file not found')
    tokens = tokenize(path)
    parser = Parser(tokens, path)
    root = parser.parse()
    return _Interpreter(path, parser, root).interpret()
