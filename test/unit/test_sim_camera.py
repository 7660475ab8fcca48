"""The built-in Stage camera against hand-computed geometry, and its world-file syntax.

Expected pixels come from the pinhole model written out here with plain
trigonometry (a ray's angle below the horizon, where it meets the floor or a
wall), not from the renderer's vector arithmetic. Each pixel is sampled at
SAMPLE_POINT, where real Stage's frames sample it (test_sim_camera_reference
holds that to real Stage).
"""
import math
import os
import textwrap

import numpy as np
import pytest

from wall_follower.sim.camera import (BACKGROUND, FLOOR, SAMPLE_POINT, CameraRenderer,
                                      CameraScene, camera_intrinsics, camera_mount, floor_extent)
from wall_follower.sim.engine import Simulation
from wall_follower.sim.worldfile import WorldFileError, load_world

EYE_Z = 0.3   # body height 0.1 + camera pose z 0.2


def _world(directory, camera='pantilt [0 30]', models='', camera_pose='0.3 0.1 0.2 0'):
    """A 0.2 m robot at the origin facing +x, with a camera on a mast, and `models`."""
    text = textwrap.dedent("""
        define cam camera
        (
          resolution [ 160 120 ]
          range [ 0.05 8.0 ]
          fov [ 60 45 ]
          {camera}
        )
        {models}
        position
        (
          name "bot"
          pose [ 0 0 0 0 ]
          size [ 0.2 0.2 0.1 ]
          color "gray20"
          cam( pose [ {camera_pose} ] )
        )
        """).format(camera=camera, models=models, camera_pose=camera_pose)
    path = os.path.join(str(directory), 'camera.world')
    with open(path, 'w') as stream:
        stream.write(text)
    return load_world(path)


def _render(world, pose=(0.0, 0.0, 0.0)):
    robot = world.robots[0]
    renderer = CameraRenderer(CameraScene(world), robot.camera)
    return renderer.render(pose, [(robot, pose)])


def _pixel_rays(camera):
    """(v per row, u per column): a pixel's sample point's offsets from the axis, in focal
    units."""
    fx, fy, cx, cy = camera_intrinsics(camera)
    width, height = camera.resolution
    return ((np.arange(height) + SAMPLE_POINT[1] - cy) / fy,
            (np.arange(width) + SAMPLE_POINT[0] - cx) / fx)


def _is(rgba, color):
    return np.all(rgba[..., :3] == np.round(np.array(color) * 255), axis=-1)


def test_parser_reads_the_camera_and_places_the_eye_on_the_body(tmp_path):
    camera = _world(tmp_path).robots[0].camera
    assert camera.resolution == (160, 120)
    assert camera.range == (0.05, 8.0)
    assert camera.fov == pytest.approx((math.radians(60), math.radians(45)))
    assert camera.pantilt == pytest.approx((0.0, math.radians(30)))
    assert camera.pose == pytest.approx((0.3, 0.1, 0.2, 0.0))
    assert camera.height == pytest.approx(EYE_Z)


def test_parser_defaults_are_stage_ones(tmp_path):
    path = os.path.join(str(tmp_path), 'bare.world')
    with open(path, 'w') as stream:
        stream.write('position( size [0.2 0.2 0.1] camera( ) )\n')
    camera = load_world(path).robots[0].camera
    assert camera.resolution == (32, 32)
    assert camera.range == (0.2, 8.0)
    assert camera.fov == pytest.approx((math.radians(70), math.radians(40)))
    assert camera.pantilt == (0.0, 0.0)


@pytest.mark.parametrize('bad, words', [
    ('resolution [ 0 120 ]', 'resolution'),
    ('resolution [ 10.5 120 ]', 'resolution'),
    ('range [ 2 1 ]', 'range'),
    ('fov [ 200 40 ]', 'fov'),
])
def test_bad_camera_is_a_one_line_error_with_its_line(tmp_path, bad, words):
    with pytest.raises(WorldFileError) as error:
        _world(tmp_path, camera=bad)
    assert words in str(error.value)
    assert 'camera.world:' in str(error.value)


def _load(directory, text):
    path = os.path.join(str(directory), 'camera.world')
    with open(path, 'w') as stream:
        stream.write(textwrap.dedent(text))
    return load_world(path)


def _robot_with(camera_text, before=''):
    return before + textwrap.dedent("""
        position
        (
          name "bot"
          size [ 0.2 0.2 0.1 ]
          %s
        )
        """) % camera_text


def test_a_world_without_surprises_has_no_warnings(tmp_path):
    assert _world(tmp_path).warnings == []
    assert _world(tmp_path).robots[0].camera.color == (0.0, 0.0, 0.0)   # Stage's black
    assert _world(tmp_path, camera='color "red"').robots[0].camera.color == (1.0, 0.0, 0.0)


@pytest.mark.parametrize('window, asked, capped', [
    ('', (1000, 1000), (600, 370)),                             # stageros' own 600 x 400
    ('window( size [ 800 650 ] )', (1000, 700), (800, 620)),
    ('window( size [ 800 650 ] )', (640, 900), (640, 620)),
])
def test_a_resolution_beyond_the_window_is_capped_there_with_a_warning(
        tmp_path, window, asked, capped):
    world = _load(tmp_path, _robot_with('camera( resolution [ %d %d ] )' % asked, window))
    assert world.robots[0].camera.resolution == capped
    warning, = world.warnings
    assert warning.startswith('%s:' % world.path)
    assert 'camera resolution [%d %d] is capped at [%d %d], as real Stage' % (asked + capped) \
        in warning


def test_a_resolution_within_the_window_is_kept(tmp_path):
    world = _load(tmp_path, _robot_with('camera( resolution [ 800 620 ] )',
                                        'window( size [ 800 650 ] )'))
    assert world.robots[0].camera.resolution == (800, 620)
    assert world.warnings == []


def test_more_pixels_than_the_simulator_draws_are_refused_even_in_a_big_window(tmp_path):
    with pytest.raises(WorldFileError) as error:
        _load(tmp_path, _robot_with('camera( resolution [ 10000 10000 ] )',
                                    'window( size [ 3000 3000 ] )'))
    assert 'camera resolution [3000 2970] is more than the 2073600 pixels (1920 x 1080)' in \
        str(error.value)
    assert 'camera.world:' in str(error.value)


def test_a_window_with_no_area_to_draw_in_is_refused(tmp_path):
    with pytest.raises(WorldFileError) as error:
        _load(tmp_path, _robot_with('camera( )', 'window( size [ -1 -1 ] )'))
    assert 'window size [-1 -1] leaves no area to draw a camera in' in str(error.value)


@pytest.mark.parametrize('text, where', [
    ('camera( name "loose" )', 'the world'),
    ('model( name "box" camera( name "loose" ) )', 'model "box"'),
    ('position( size [ 0.2 0.2 0.1 ] ranger( sensor( ) camera( name "loose" ) ) )',
     'a ranger'),
])
def test_a_camera_no_robot_carries_is_left_out_with_a_warning(tmp_path, text, where):
    world = _load(tmp_path, text)
    warning, = world.warnings
    assert 'camera "loose" is in %s, not directly in a robot\'s position: it is not drawn or ' \
        'published' % where in warning
    assert all(robot.camera is None for robot in world.robots)


def test_a_second_camera_on_a_robot_is_left_out_with_a_warning(tmp_path):
    world = _load(tmp_path, _robot_with('camera( name "first" resolution [ 40 30 ] )\n'
                                        'camera( name "second" resolution [ 80 60 ] )'))
    assert world.robots[0].camera.resolution == (40, 30)
    warning, = world.warnings
    assert 'robot "bot" has a second camera: this simulator draws and publishes only its ' \
        'first' in warning
    assert 'image_0, image_1' in warning


@pytest.mark.parametrize('pantilt, meant, backwards', [
    ((1000, -1000), (-80, 80), False),
    ((30, 120), (30, 120), True),
    ((-200, 40), (160, 40), False),
])
def test_pan_and_tilt_beyond_a_half_and_a_quarter_turn_turn_all_the_same_with_a_warning(
        tmp_path, pantilt, meant, backwards):
    models = 'model( color "blue" size [ 0.3 0.3 1 ] pose [ -0.3 0.6 0 0 ] )'
    world = _world(tmp_path, camera='pantilt [ %g %g ]' % pantilt, models=models)
    warning, = world.warnings
    assert 'camera pantilt [%g %g] is beyond [-180, 180] x [-90, 90] deg: real Stage turns by ' \
        'it all the same' % pantilt in warning
    assert '(a pan of %g deg, a tilt of %g deg' % meant in warning
    assert ('looking backwards and upside down' in warning) == backwards
    as_meant = _world(tmp_path, camera='pantilt [ %g %g ]' % meant, models=models)
    assert np.array_equal(_render(world).rgba, _render(as_meant).rgba)


def test_unknown_colour_is_a_one_line_error(tmp_path):
    with pytest.raises(WorldFileError) as error:
        _world(tmp_path, models='model( color "no such colour" )')
    assert 'unknown colour "no such colour"' in str(error.value)


def test_colours_by_name_and_rgba(tmp_path):
    models = ('model( color "gray30" pose [5 0 0 0] )\n'
              'model( color_rgba [0 0.5 1 1] pose [5 2 0 0] )')
    world = _world(tmp_path, models=models)
    assert world.obstacles[0].color == pytest.approx((77 / 255.0,) * 3)
    assert world.obstacles[1].color == (0.0, 0.5, 1.0)
    assert world.robots[0].color == pytest.approx((51 / 255.0,) * 3)


def test_a_point_on_the_floor_lands_on_its_row_and_column(tmp_path):
    # A 2 cm yellow square on the floor 0.6 m ahead and 0.1 m to the right.
    ahead, right = 0.6, 0.1
    world = _world(tmp_path, models=textwrap.dedent("""
        model( color "yellow" size [ 0.02 0.02 0.001 ] pose [ %g %g 0 0 ]
               obstacle_return 0 ranger_return -1 )""" % (ahead, -right)))
    camera = world.robots[0].camera
    tilt = camera.pantilt[1]
    fx, fy, cx, cy = camera_intrinsics(camera)
    # The square's centre in the camera: depth along the axis, then right and down.
    depth = ahead * math.cos(tilt) + EYE_Z * math.sin(tilt)
    down = -ahead * math.sin(tilt) + EYE_Z * math.cos(tilt)
    column = cx + fx * right / depth
    row = cy + fy * down / depth
    yellow = _is(_render(world).rgba, (1.0, 1.0, 0.0))
    rows, columns = np.nonzero(yellow)
    assert len(rows) > 4
    # Pixel i spans [i, i + 1): the blob's centre of sample points sits on the point.
    assert columns.mean() + SAMPLE_POINT[0] == pytest.approx(column, abs=0.5)
    assert rows.mean() + SAMPLE_POINT[1] == pytest.approx(row, abs=0.5)


def _subdivided(corners, per_side):
    """The corners of a polygon with each side cut into per_side collinear edges."""
    corners = np.asarray(corners, dtype=float)
    following = np.roll(corners, -1, axis=0)
    steps = np.arange(per_side)[:, None] / float(per_side)
    return np.concatenate([start + steps * (end - start)
                           for start, end in zip(corners, following)])


def _block_model(points, top, color='yellow'):
    """A floor marking of one block polygon, in world coordinates (its size is the
    points' extent, so that nothing is scaled)."""
    points = np.asarray(points, dtype=float)
    lower, upper = points.min(axis=0), points.max(axis=0)
    centre = (lower + upper) / 2.0
    corners = ' '.join('point[%d] [ %.6f %.6f ]' % (i, x, y)
                       for i, (x, y) in enumerate(points - centre))
    return ('model( color "%s" size [ %.6f %.6f %g ] pose [ %.6f %.6f 0 0 ] '
            'obstacle_return 0 ranger_return -1 block( points %d %s z [ 0 1 ] ) )'
            % (color, upper[0] - lower[0], upper[1] - lower[1], top, centre[0], centre[1],
               len(points), corners))


STRIP = (0.50, 0.56, 0.004)   # near and far edge ahead of the robot, height [m]


def _strip_shapes():
    """The strip across the floor as a box (its sides tested edge by edge) and as a
    polygon of many edges (a raster whose cells are walked), each also hooked round
    under the camera: a concave outline that the eye is over, which hides none of the
    strip's sides."""
    near, far, _ = STRIP
    box = [(near, -1.5), (far, -1.5), (far, 1.5), (near, 1.5)]
    hook = [(near, -1.5), (far, -1.5), (far, 1.5), (-0.1, 1.5), (-0.1, -0.1), (0.1, -0.1),
            (0.1, 1.4), (near, 1.4)]
    return {'box': box, 'box_many_edges': _subdivided(box, 12),
            'hooked': hook, 'hooked_many_edges': _subdivided(hook, 6)}


@pytest.mark.parametrize('shape', sorted(_strip_shapes()))
def test_a_low_strip_across_the_floor_fills_the_rows_whose_rays_meet_its_top_or_near_face(
        tmp_path, shape):
    near_edge, far_edge, top = STRIP
    world = _world(tmp_path, models=_block_model(_strip_shapes()[shape], top))
    camera = world.robots[0].camera
    v, _ = _pixel_rays(camera)
    below_horizon = camera.pantilt[1] + np.arctan(v)
    # Where each ray meets the strip's top face, `top` above the floor, and how high it
    # is where it passes the strip's near edge (its face towards the camera).
    top_distance = (EYE_Z - top) / np.tan(below_horizon)
    at_near_edge = EYE_Z - near_edge * np.tan(below_horizon)
    on_top = (top_distance >= near_edge) & (top_distance <= far_edge)
    on_face = (at_near_edge >= 0.0) & (at_near_edge <= top)
    assert (on_face & ~on_top).any(), 'the near face should show in a row of its own'
    expected = np.nonzero(on_top | on_face)[0]
    frame = _render(world)
    centre = frame.rgba[:, camera.resolution[0] // 2]
    assert list(np.nonzero(_is(centre, (1.0, 1.0, 0.0)))[0]) == list(expected)
    # Depth is along the optical axis: the distance to the point met times cos(off-axis).
    row = expected[-1]
    met = near_edge if on_face[row] and not on_top[row] else top_distance[row]
    assert frame.depth[row, camera.resolution[0] // 2] == pytest.approx(
        math.hypot(met, EYE_Z - (at_near_edge[row] if met == near_edge else top)) *
        math.cos(math.atan(v[row])), rel=1e-5)


def test_a_wall_of_known_height_fills_known_rows(tmp_path):
    distance, thickness, wall_height = 1.0, 0.1, 0.2
    world = _world(tmp_path, camera='pantilt [0 0]', models=textwrap.dedent("""
        model( color "blue" size [ %g 4 %g ] pose [ %g 0 0 0 ] )""" % (
            thickness, wall_height, distance + thickness / 2)))
    camera = world.robots[0].camera
    v, _ = _pixel_rays(camera)
    # Level camera: the ray of row r drops v metres per metre ahead. The eye is above
    # the wall, so it sees the wall's face and, just above it, its top.
    face = (v >= (EYE_Z - wall_height) / distance) & (v <= EYE_Z / distance)
    on_top = (v >= (EYE_Z - wall_height) / (distance + thickness)) & \
        (v < (EYE_Z - wall_height) / distance)
    assert face.sum() > 20 and on_top.sum() >= 1
    frame = _render(world)
    centre = frame.rgba[:, camera.resolution[0] // 2]
    assert list(np.nonzero(_is(centre, (0.0, 0.0, 1.0)))[0]) == \
        list(np.nonzero(face | on_top)[0])
    assert _is(centre[v > EYE_Z / distance], FLOOR).all()
    # Over the wall the floor goes on (the world's extent is a whole superregion, 20.48 m
    # a side) to the far clip, 8 m ahead; beyond is Stage's clear colour.
    over = v < (EYE_Z - wall_height) / (distance + thickness)
    floor_beyond = over & (v > 0) & (EYE_Z / np.maximum(v, 1e-9) < camera.range[1])
    assert floor_beyond.sum() >= 3 and (over & ~floor_beyond).sum() >= 3
    assert _is(centre[floor_beyond], FLOOR).all()
    assert _is(centre[over & ~floor_beyond], BACKGROUND).all()
    assert frame.depth[face, camera.resolution[0] // 2] == pytest.approx(distance)
    assert frame.depth[on_top, camera.resolution[0] // 2] == pytest.approx(
        (EYE_Z - wall_height) / v[on_top])
    assert np.isinf(frame.depth[v < 0, camera.resolution[0] // 2]).all()


def test_the_floor_is_the_world_s_superregions():
    # Stage's world extent: the whole superregions (1024 cells of `resolution` a side,
    # aligned on the origin) that the models touch.
    lower, upper = floor_extent([[-2.0, -1.5], [2.0, 1.5]], 0.02)
    assert list(lower) == pytest.approx([-20.48, -20.48])
    assert list(upper) == pytest.approx([20.48, 20.48])
    lower, upper = floor_extent([[0.1, 0.1], [20.5, 3.0]], 0.05)
    assert list(lower) == pytest.approx([0.0, 0.0])
    assert list(upper) == pytest.approx([51.2, 51.2])


def test_a_camera_ahead_of_the_centre_sees_its_own_box_above_the_horizon(tmp_path):
    # The camera (default box 0.1 x 0.07 x 0.05, black) 0.3 m ahead and 0.1 m left of the
    # robot's centre, level: the eye on the centre, level with the box's base, sees the
    # box's back face (x = 0.25) and its face towards the axis (y = 0.065) above the
    # horizon.
    world = _world(tmp_path, camera='pantilt [0 0]')
    camera = world.robots[0].camera
    x0, x1, y0, y1 = 0.25, 0.35, 0.065, 0.135
    v, u = _pixel_rays(camera)
    up, left = -v[:, None], -u[None, :]
    # A level ray of row/column (v, u) is at (t, -u t, EYE_Z - v t) at depth t.
    back = (left * x0 >= y0) & (left * x0 <= y1) & (up >= 0) & (up * x0 <= 0.05)
    side_depth = np.broadcast_to(y0 / np.where(left > 0, left, np.nan), back.shape)
    side = (side_depth >= x0) & (side_depth <= x1) & (up >= 0) & (up * side_depth <= 0.05)
    assert back.sum() > 50 and (side & ~back).sum() > 5
    frame = _render(world)
    black = _is(frame.rgba, (0.0, 0.0, 0.0))
    assert np.array_equal(black, back | side)
    assert frame.depth[back] == pytest.approx(x0)
    assert frame.depth[side & ~back] == pytest.approx(side_depth[side & ~back])


def test_pan_turns_the_view_right(tmp_path):
    # A blue pillar 1 m away, 45 degrees to the right: in view only when panned right.
    models = 'model( color "blue" size [ 0.1 0.1 1 ] pose [ 0.7071 -0.7071 0 0 ] )'
    ahead = _render(_world(tmp_path, camera='pantilt [0 0]', models=models)).rgba
    panned = _render(_world(tmp_path, camera='pantilt [45 0]', models=models)).rgba
    assert not _is(ahead, (0.0, 0.0, 1.0)).any()
    columns = np.nonzero(_is(panned, (0.0, 0.0, 1.0)).any(axis=0))[0]
    assert abs(columns.mean() + 0.5 - 80) < 3


def test_a_camera_level_with_the_body_top_sees_mostly_its_own_robot(tmp_path):
    world = _world(tmp_path, camera_pose='0 0 0 0')
    frame = _render(world)
    assert _is(frame.rgba, world.robots[0].color).mean() > 0.5


def test_the_camera_model_x_y_are_not_used_for_the_view(tmp_path):
    # As Stage 4.3 draws it: from the robot's centre whatever the camera's own x, y.
    moved = _render(_world(tmp_path, camera_pose='0.3 0.1 0.2 0')).rgba
    centred = _render(_world(tmp_path, camera_pose='0 0 0.2 0')).rgba
    assert np.array_equal(moved, centred)


def test_nothing_beyond_the_far_clip(tmp_path):
    world = _world(tmp_path, camera='pantilt [0 0] range [ 0.05 0.9 ]',
                   models='model( color "blue" size [ 0.1 4 1 ] pose [ 1.0 0 0 0 ] )')
    assert not _is(_render(world).rgba, (0.0, 0.0, 1.0)).any()


def test_mount_is_stageros_optical_frame(tmp_path):
    robot = _world(tmp_path).robots[0]
    mount = camera_mount(robot)
    assert (mount.x, mount.y, mount.z) == pytest.approx((0.3, 0.1, EYE_Z))
    x, y, z, w = mount.rotation
    rotation = np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
    tilt = math.radians(30)
    # Optical frame: z along the view (ahead and down by tilt), x right, y down.
    assert rotation[:, 2] == pytest.approx([math.cos(tilt), 0.0, -math.sin(tilt)])
    assert rotation[:, 0] == pytest.approx([0.0, -1.0, 0.0])
    assert rotation[:, 1] == pytest.approx([-math.sin(tilt), 0.0, -math.cos(tilt)])


def test_simulation_renders_only_when_asked_at_the_pose_before_the_step(tmp_path):
    world = _world(tmp_path)
    sim = Simulation(world)
    assert sim.step(with_scans=False).robots[0].image is None
    sim.set_command(0, 0.2, 0.0)
    before = sim.robots[0].pose
    frame = sim.step(with_scans=False, with_images=True).robots[0].image
    assert sim.robots[0].pose != before
    assert np.array_equal(frame.rgba, _render(world, before).rgba)
