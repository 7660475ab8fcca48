"""The built-in Stage camera against hand-computed geometry, and its world-file syntax.

Expected pixels come from the pinhole model written out here with plain
trigonometry (a ray's angle below the horizon, where it meets the floor or a
wall), not from the renderer's vector arithmetic.
"""
import math
import os
import textwrap

import numpy as np
import pytest

from wall_follower.sim.camera import (BACKGROUND, FLOOR, CameraRenderer, CameraScene,
                                      camera_intrinsics, camera_mount)
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
    """(v per row, u per column): a pixel centre's offsets from the axis, in focal units."""
    fx, fy, cx, cy = camera_intrinsics(camera)
    width, height = camera.resolution
    return (np.arange(height) + 0.5 - cy) / fy, (np.arange(width) + 0.5 - cx) / fx


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
    # Pixel i spans [i, i + 1): the blob's centre of pixel centres sits on the point.
    assert columns.mean() + 0.5 == pytest.approx(column, abs=0.5)
    assert rows.mean() + 0.5 == pytest.approx(row, abs=0.5)


def test_a_strip_across_the_floor_fills_the_rows_whose_rays_meet_it(tmp_path):
    near_edge, far_edge, top = 0.50, 0.56, 0.001
    world = _world(tmp_path, models=textwrap.dedent("""
        model( color "yellow" size [ %g 3 %g ] pose [ %g 0 0 0 ]
               obstacle_return 0 ranger_return -1 )""" % (far_edge - near_edge, top,
                                                          (near_edge + far_edge) / 2)))
    camera = world.robots[0].camera
    v, _ = _pixel_rays(camera)
    below_horizon = camera.pantilt[1] + np.arctan(v)
    # Where each ray meets the strip's top face, `top` above the floor.
    floor_distance = (EYE_Z - top) / np.tan(below_horizon)
    expected = np.nonzero((floor_distance >= near_edge) & (floor_distance <= far_edge))[0]
    frame = _render(world)
    centre = frame.rgba[:, camera.resolution[0] // 2]
    assert list(np.nonzero(_is(centre, (1.0, 1.0, 0.0)))[0]) == list(expected)
    # Depth is along the optical axis: distance to the floor point times cos(off-axis).
    row = expected[0]
    assert frame.depth[row, camera.resolution[0] // 2] == pytest.approx(
        math.hypot(floor_distance[row], EYE_Z - top) * math.cos(math.atan(v[row])), rel=1e-5)


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
    # Over the wall the floor ends with the world's extent: Stage's clear colour.
    assert _is(centre[v < (EYE_Z - wall_height) / (distance + thickness)], BACKGROUND).all()
    assert frame.depth[face, camera.resolution[0] // 2] == pytest.approx(distance)
    assert frame.depth[on_top, camera.resolution[0] // 2] == pytest.approx(
        (EYE_Z - wall_height) / v[on_top])
    assert np.isinf(frame.depth[v < 0, camera.resolution[0] // 2]).all()


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
