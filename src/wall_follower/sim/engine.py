"""One Stage world update at a time, with stageros' outputs, free of ROS.

What one `step()` does, in Stage's order (measured on real Stage 4.3 +
stage_ros 1.8, see the stage-reference README):

1. every robot's laser is raytraced, and its camera (if asked for) rendered,
   at the pose it has *before* this update;
2. the command in force becomes the velocity (clamped to velocity_bounds), and
   odometry reports the pose before the move with that velocity as its twist
   (with localization "odom": Stage's dead reckoning of that velocity instead);
3. each robot takes one Euler step; a step whose body outline, drawn into
   Stage's cells, would share a cell with an obstacle (or whose footprint would
   overlap another robot's) is rejected: the robot keeps its last free pose and
   is stalled;
4. ground truth is the new pose, its twist the world-frame finite difference
   from the last published ground truth;
5. the clock advances by interval_sim, then the watchdog zeroes the command of
   a robot whose last command is timeout or more old: a command given after
   update T therefore drives the updates T+dt and T+2dt and no more.

Time is kept in integer microseconds, as Stage does, so the watchdog's
comparison is exact.
"""
import math
from collections import namedtuple

import numpy as np

from .camera import CameraRenderer, CameraScene
from .grid import OccupancyGrid, footprint_cells, footprint_collides, footprint_corners, \
    footprints_overlap
from .kinematics import clamp_velocity, diff_drive_step, normalize_angle
from .laser_profiles import PROFILES, angle_noise, beam_layout, reach, report
from .raytrace import stage_beam_angles, stage_ranges

__all__ = ['Simulation', 'Frame', 'RobotFrame', 'Scan', 'Odometry', 'LaserMount', 'RobotState',
           'DEFAULT_ODOM_ERROR_LIMITS']

Scan = namedtuple('Scan', ['angle_min', 'angle_max', 'angle_increment', 'range_min',
                           'range_max', 'ranges', 'intensities', 'profile'])
# Pose in the world; twist: odometry in the robot frame (vx, vy, wz), ground truth in the
# world frame.
Odometry = namedtuple('Odometry', ['x', 'y', 'yaw', 'vx', 'vy', 'wz'])
# base_link -> base_laser_link, as stageros publishes it (z = body height + ranger z).
LaserMount = namedtuple('LaserMount', ['x', 'y', 'z', 'yaw'])
# image: a camera.CameraFrame, or None (no camera, or not asked for).
RobotFrame = namedtuple('RobotFrame', ['name', 'scan', 'odom', 'ground_truth', 'stalled',
                                       'laser', 'image'])
Frame = namedtuple('Frame', ['stamp', 'robots'])

# A body drawn in the grid is hit by other robots' lasers with Stage's default return.
_ROBOT_RANGER_RETURN = 1.0
# Stage 4.3's default odometry scale errors (x, y, yaw) lie within +- these:
# half its INTEGRATION_ERROR_MAX_X, _Y and _A (0.03, 0.03, 0.05).
DEFAULT_ODOM_ERROR_LIMITS = (0.015, 0.015, 0.025)
# Updates in a row, each after a command to stand, that make a robot held still (driven()).
HOLDING_STEPS = 2
# Beside the seed, the key of the noise stream of a step on which nobody drives (step()).
IDLE_STREAM = 1


class RobotState(object):
    """A robot's live state: pose, the command in force and what the last update did."""

    def __init__(self, name, spec, start_pose):
        self.name = name
        self.spec = spec
        self.start_pose = tuple(start_pose)
        self.pose = self.start_pose
        self.command = (0.0, 0.0)
        self.velocity = (0.0, 0.0)
        self.last_command_us = 0   # sim time of the last command
        self.held_steps = 0        # updates in a row before each of which it was told to stand
        self.stalled = False
        self.published_pose = None   # ground truth at the last update, for its twist
        self.odom_pose = (0.0, 0.0, 0.0)   # dead reckoning for localization "odom"
        self.odom_error = (0.0, 0.0, 0.0)


class Simulation(object):
    """A Stage world advanced one `interval_sim` per `step()`.

    world: a worldfile.World. laser_profile: one of laser_profiles.PROFILES.
    seed: for laser noise and drawn odometry errors. poses: optional {robot
    index: (x, y, yaw)} start poses that replace the world file's.
    watchdog_timeout: seconds of sim time (stageros' ~base_watchdog_timeout);
    0 disables it.
    """

    def __init__(self, world, laser_profile='stage', seed=0, poses=None, watchdog_timeout=0.2):
        if laser_profile not in PROFILES:
            raise ValueError('unknown laser profile %r (known: %s)'
                             % (laser_profile, ', '.join(PROFILES)))
        self.world = world
        self.laser_profile = laser_profile
        self.grid = OccupancyGrid.from_world(world)
        self.dt = world.interval_sim
        self._dt_us = int(round(world.interval_sim * 1e6))
        self._watchdog_us = int(round(watchdog_timeout * 1e6))
        self._seed = seed
        self.rng = np.random.RandomState(seed)
        self._time_us = 0
        poses = poses or {}
        self.robots = []
        for index, spec in enumerate(world.robots):
            start = poses.get(index, spec.pose)
            start = (float(start[0]), float(start[1]), normalize_angle(float(start[2])))
            robot = RobotState(spec.name, spec, start)
            robot.odom_error = spec.odom_error or _random_odom_error(self.rng)
            self.robots.append(robot)
        self._cameras = None   # CameraRenderer per robot (None: no camera), built on first use

    @property
    def time(self):
        """Simulated seconds since the start (the stamp of the last update)."""
        return self._time_us / 1e6

    def set_command(self, index, v, w):
        """Command robot `index` (as a cmd_vel would); it drives from the next update."""
        robot = self.robots[index]
        robot.command = (float(v), float(w))
        robot.last_command_us = self._time_us

    def driven(self):
        """Per robot, whether a controller is driving it: it is commanded to move, or a
        controller holds it still, telling it to stand before each of the last
        HOLDING_STEPS updates.

        A simulator in lockstep waits for the next command of these. A robot
        held still is driven as much as a moving one: a controller whose next
        command, to move off, comes late would otherwise find the world
        stepped on without it, and its timing shifted by the load. A last stop,
        sent once (or a few times at once) by a controller that then goes
        quiet, is not holding: waiting for a command that never comes would
        cost every such end a whole lockstep time-out.
        """
        return [robot.command != (0.0, 0.0) or robot.held_steps >= HOLDING_STEPS
                for robot in self.robots]

    def reset(self):
        """Back to the start poses with zero commands (stageros' reset_positions).

        As in stageros, only the true pose is set back: "odom" dead reckoning
        goes on from where it was, as a real robot's odometry would if it
        were carried back.
        """
        for robot in self.robots:
            robot.pose = robot.start_pose
            robot.command = (0.0, 0.0)
            robot.velocity = (0.0, 0.0)
            robot.stalled = False

    def teleport(self, index, pose):
        """Put a robot at pose (x, y, yaw) at once, with no collision check.

        As Stage's SetPose (stage_ros's cmd_pose): for tests and demos that
        need many start poses in one run. The command is kept.
        """
        robot = self.robots[index]
        robot.pose = (float(pose[0]), float(pose[1]), normalize_angle(float(pose[2])))
        robot.stalled = False

    def step(self, with_scans=True, with_images=False, idle=False):
        """Advance one world update and return its Frame (scans None if not with_scans,
        camera images None unless with_images).

        idle: nobody drives (see driven()), as a simulator in lockstep tells
        it. The scans then draw their noise from a stream of their own,
        begun afresh at every such step, and the run's stream is left where
        it was. Such steps are paced by the wall clock, and how many of
        them pass before a controller starts depends on the machine; the
        run's stream, drawn from only while someone drives, meets a lap
        with the same noise however many passed.
        """
        for robot in self.robots:
            # Commanded since the last update (it bore this time stamp), to stand.
            held = robot.last_command_us == self._time_us and robot.command == (0.0, 0.0)
            robot.held_steps = robot.held_steps + 1 if held else 0
        rng = np.random.RandomState((self._seed, IDLE_STREAM)) if idle else self.rng
        scans = [self._scan(i, rng) if with_scans else None for i in range(len(self.robots))]
        images = [self.camera_image(i) if with_images else None
                  for i in range(len(self.robots))]
        odoms = []
        for robot in self.robots:
            v, w = clamp_velocity(robot.command[0], robot.command[1], robot.spec.velocity_bounds)
            robot.velocity = (v, w)
            if robot.spec.localization == 'odom':
                robot.odom_pose = _dead_reckoning(robot.odom_pose, v, w, self.dt,
                                                  robot.odom_error)
                x, y, yaw = robot.odom_pose
            else:
                x, y, yaw = robot.pose
            odoms.append(Odometry(x, y, yaw, v, 0.0, w))
        for index, robot in enumerate(self.robots):
            self._move(index, robot)
        self._time_us += self._dt_us
        frames = []
        for robot, scan, odom, image in zip(self.robots, scans, odoms, images):
            frames.append(RobotFrame(robot.name, scan, odom, self._ground_truth(robot),
                                     robot.stalled, laser_mount(robot.spec), image))
        for robot in self.robots:
            if self._watchdog_us > 0 and self._time_us - robot.last_command_us >= self._watchdog_us:
                robot.command = (0.0, 0.0)
        return Frame(self.time, frames)

    def _move(self, index, robot):
        v, w = robot.velocity
        if v == 0.0 and w == 0.0:
            return  # Stage does not move (nor touch the stall flag) at zero velocity
        new_pose = diff_drive_step(robot.pose, v, w, self.dt)
        if self._blocked(index, new_pose):
            robot.stalled = True
        else:
            robot.pose = new_pose
            robot.stalled = False

    def _blocked(self, index, pose):
        spec = self.robots[index].spec
        if footprint_collides(self.grid, spec, pose):
            return True
        if len(self.robots) > 1:
            corners = footprint_corners(spec, pose)
            for other_index, other in enumerate(self.robots):
                if other_index != index and \
                        footprints_overlap(corners, footprint_corners(other.spec, other.pose)):
                    return True
        return False

    def _ground_truth(self, robot):
        x, y, yaw = robot.pose
        previous = robot.published_pose
        robot.published_pose = robot.pose
        if previous is None:
            return Odometry(x, y, yaw, 0.0, 0.0, 0.0)
        return Odometry(x, y, yaw, (x - previous[0]) / self.dt, (y - previous[1]) / self.dt,
                        normalize_angle(yaw - previous[2]) / self.dt)

    def camera_image(self, index):
        """The CameraFrame robot `index`'s camera sees now (None: it has no camera)."""
        if self._cameras is None:
            scene = CameraScene(self.world)
            self._cameras = [CameraRenderer(scene, robot.spec.camera)
                             if robot.spec.camera is not None else None
                             for robot in self.robots]
        renderer = self._cameras[index]
        if renderer is None:
            return None
        return renderer.render(self.robots[index].pose,
                               [(robot.spec, robot.pose) for robot in self.robots])

    def laser_origin(self, index):
        """World (x, y, yaw) of robot `index`'s beams (ranger pose, then sensor pose)."""
        x, y, ranger_yaw = self._ranger_origin(index)
        return x, y, normalize_angle(ranger_yaw + self.robots[index].spec.ranger.sensor_pose[3])

    def _ranger_origin(self, index):
        """Beam origin (x, y) and the ranger model's world yaw, in Stage's arithmetic."""
        robot = self.robots[index]
        ranger = robot.spec.ranger
        x, y, yaw = robot.pose
        ranger_x, ranger_y, _, ranger_yaw = ranger.pose
        cosa, sina = math.cos(yaw), math.sin(yaw)
        rx = x + ranger_x * cosa - ranger_y * sina
        ry = y + ranger_x * sina + ranger_y * cosa
        ra = normalize_angle(yaw + ranger_yaw)
        sensor_x, sensor_y = ranger.sensor_pose[0], ranger.sensor_pose[1]
        cosr, sinr = math.cos(ra), math.sin(ra)
        return rx + sensor_x * cosr - sensor_y * sinr, ry + sensor_x * sinr + sensor_y * cosr, ra

    def _scan(self, index, rng):
        """Robot index's Scan, its noise drawn from rng (a numpy RandomState)."""
        robot = self.robots[index]
        ranger = robot.spec.ranger
        if ranger is None:
            return None
        x, y, ranger_yaw = self._ranger_origin(index)
        layout = beam_layout(self.laser_profile, ranger, rng)
        limits = reach(self.laser_profile, ranger)
        # Stage sweeps from the normalised first-beam angle in float32 steps.
        first = normalize_angle(ranger_yaw + (ranger.sensor_pose[3] + layout.angle_min))
        angles = stage_beam_angles(first, layout.angle_increment, layout.count)
        if ranger.noise[2] > 0.0:
            angles = angles + angle_noise(ranger, layout, rng)
        own = [footprint_cells(robot.spec, robot.pose, self.grid.ppm)]
        others = []
        for other_index, other in enumerate(self.robots):
            if other_index != index:
                xs, ys = footprint_cells(other.spec, other.pose, self.grid.ppm)
                others.append((xs, ys, _ROBOT_RANGER_RETURN))
        ranges, intensities = stage_ranges(self.grid, x, y, angles, limits.max,
                                           height=ranger.sensor_height, robot_cells=own,
                                           other_cells=others)
        hit = ranges < limits.max
        ranges, intensities = report(self.laser_profile, ranges, intensities, hit, ranger, rng)
        return Scan(layout.angle_min, layout.angle_max, layout.angle_increment,
                    limits.published_min, limits.published_max, ranges, intensities,
                    self.laser_profile)


def laser_mount(spec):
    """base_link -> base_laser_link of a robot, as stageros publishes it (None: no ranger)."""
    if spec.ranger is None:
        return None
    x, y, z, yaw = spec.ranger.pose
    return LaserMount(x, y, spec.size[2] + z, yaw)


def _random_odom_error(rng):
    """Stage's default odometry scale errors: each uniform within +-DEFAULT_ODOM_ERROR_LIMITS.

    Drawn once per robot, as Stage does for each position model without odom_error.
    Real Stage seeds its draw from the clock, so every run differs
    (test/data/stage_reference/stage_odometry.json); here it comes from the
    simulation's seed, so that a run can be repeated.
    """
    return tuple(rng.uniform(-limit, limit) for limit in DEFAULT_ODOM_ERROR_LIMITS)


def _dead_reckoning(pose, v, w, dt, error):
    """Stage's "odom" localization: turn first, then advance along the new heading."""
    x, y, yaw = pose
    yaw = normalize_angle(yaw + (w * dt) * (1.0 + error[2]))
    dx = (v * dt) * (1.0 + error[0])
    return x + dx * math.cos(yaw), y + dx * math.sin(yaw), yaw
