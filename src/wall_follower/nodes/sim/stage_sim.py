"""stage_sim: a Stage-compatible simulator node, standing in for stageros.

    stage_sim [-g] [--simulator builtin|stage|auto] WORLD

Offers what stageros 1.8 offers, under the same relative names: publishes
base_scan (frame base_laser_link), odom and base_pose_ground_truth (frame
odom, empty child frame), /clock and tf odom -> base_footprint -> base_link
-> base_laser_link, once per world step; for a robot with a camera, and only
while image or depth has a subscriber, image (rgba8), depth (32FC1),
camera_info and tf base_link -> camera (frame camera), once per step too; subscribes cmd_vel; serves
reset_positions. Several robots get stageros' names: robot_0/base_scan,
robot_0/base_link, ... Beyond stageros it publishes `stalled` (std_msgs/Bool),
holds ~speedup headless, and subscribes cmd_pose (geometry_msgs/Pose: a
teleport with no collision check, as stage_ros' add_pose_sub branch). -g
(headless) is accepted for compatibility: this simulator has no GUI anyway.

--simulator stage or auto may hand the process over to the real stageros
(exec, so that roslaunch keeps watching the same process), by the rule of
wall_follower.sim.simulator_choice: real stageros only with its window (no
-g), since headless it cannot be paced; auto falls back to this simulator,
stage refuses with a clear error.

Private parameters: the table in wall_follower.params.sim.stage_sim, read once
at start. The world file's `speedup` is ignored, as stageros -g ignores it.
Services beyond stageros, named as Gazebo's: pause_physics and unpause_physics
(std_srvs/Empty) stop and resume the world steps; nothing is published while paused.

/use_sim_time must be true before any node starts, which is the launch
file's job; like stageros, this node sets it if nobody did, too late for the
nodes already running; unlike stageros, it puts back what was there (or
deletes it) when it exits, so that nodes started later on the same master
are not left waiting for a /clock that no longer comes.

A world whose robots cannot start where they are put (none at all, one
inside a wall or outside the map: sim.start_check) is refused with an error
naming the world file and the robot, and exit status 1. What a world file
asks and gets otherwise than it likely meant (a camera capped at the
window's size as real Stage caps it, a camera no robot carries, a robot's
second camera, a pantilt beyond a half or a quarter turn) is logged as a
warning at start, each naming its file and line.
"""
import argparse
import math
import os
import signal
import sys
import threading
import time
import warnings

import rospkg
import rospy
import tf2_ros
from geometry_msgs.msg import Pose, TransformStamped, Twist
from nav_msgs.msg import Odometry
from rosgraph_msgs.msg import Clock
from roslib.packages import find_node
from sensor_msgs.msg import CameraInfo, Image, LaserScan
from std_msgs.msg import Bool
from std_srvs.srv import Empty, EmptyResponse

from wall_follower.nodes.shared.connections import keep_connected
from wall_follower.nodes.shared.messages import yaw_of
from wall_follower.nodes.shared.parameters import NodeParameters
from wall_follower.params.sim.stage_sim import TABLE
from wall_follower.rotation import quaternion_of_yaw
from wall_follower.sim import compiled_camera, compiled_raytrace
from wall_follower.sim.camera import camera_intrinsics, camera_mount
from wall_follower.sim.engine import Simulation
from wall_follower.sim.simulator_choice import BUILTIN, SIMULATORS, STAGE, choose_simulator
from wall_follower.sim.stage_interface import parse_pose, quit_report, robot_prefix
from wall_follower.sim.start_check import start_problems
from wall_follower.sim.step_pacer import StepPacer
from wall_follower.sim.worldfile import WorldFileError, load_world


def readings_publisher(name, data_class):
    """A publisher of a step's readings that has written them to every subscriber's
    socket when publish() returns.

    rospy's queued publishers (queue_size set) hand each message to a thread per
    connection, and the stepping loop can starve those threads: a step's /clock then
    went out before its scan, and a controller woken by the clock acted on a scan
    several steps old (the lockstep, which waits only for a command, let the world
    step on it). Written in the stepping thread, before /clock is queued, every
    reading is on the wire ahead of its step's clock, and none is dropped however fast
    the world steps. A subscriber that stops reading holds the world only once its
    socket's buffers (megabytes: hundreds of steps) are full.
    """
    with warnings.catch_warnings():
        # rospy warns of synchronous publishing, which is the point here
        warnings.simplefilter('ignore', SyntaxWarning)
        return rospy.Publisher(name, data_class, queue_size=None)


def stamp_of(seconds):
    """rospy.Time of a simulated time, exact to the microsecond (the engine's
    unit), so that every topic of one step carries the identical stamp."""
    micros = int(round(seconds * 1e6))
    return rospy.Time(micros // 1000000, (micros % 1000000) * 1000)


class RobotTopics(object):
    """One robot's publishers and frame names, with stageros' prefix."""

    def __init__(self, prefix, spec):
        self.prefix = prefix
        self.odom_frame = prefix + 'odom'
        self.footprint_frame = prefix + 'base_footprint'
        self.base_frame = prefix + 'base_link'
        self.laser_frame = prefix + 'base_laser_link'
        self.camera = CameraTopics(prefix, spec) if spec.camera is not None else None
        self.scan = readings_publisher(prefix + 'base_scan', LaserScan)
        self.odom = readings_publisher(prefix + 'odom', Odometry)
        self.truth = readings_publisher(prefix + 'base_pose_ground_truth', Odometry)
        self.stalled = readings_publisher(prefix + 'stalled', Bool)

    def scan_msg(self, stamp, scan):
        msg = LaserScan()
        msg.header.stamp = stamp
        msg.header.frame_id = self.laser_frame
        msg.angle_min = scan.angle_min
        msg.angle_max = scan.angle_max
        msg.angle_increment = scan.angle_increment
        msg.range_min = scan.range_min
        msg.range_max = scan.range_max
        msg.ranges = scan.ranges.tolist()
        msg.intensities = scan.intensities.tolist()
        return msg

    def odometry_msg(self, stamp, odometry):
        """stageros fills both odom and ground truth this way: frame odom,
        no child frame, zero covariances."""
        msg = Odometry()
        msg.header.stamp = stamp
        msg.header.frame_id = self.odom_frame
        msg.pose.pose.position.x = odometry.x
        msg.pose.pose.position.y = odometry.y
        msg.pose.pose.orientation.z, msg.pose.pose.orientation.w = quaternion_of_yaw(odometry.yaw)
        msg.twist.twist.linear.x = odometry.vx
        msg.twist.twist.linear.y = odometry.vy
        msg.twist.twist.angular.z = odometry.wz
        return msg

    def publish(self, stamp, robot, with_tf):
        """One step's topics of this robot, each if subscribed; returns its transforms
        (none without `with_tf`). The camera's subscribers are read once, so that a
        subscriber leaving mid-step cannot part an image from its camera_info and tf."""
        if robot.scan is not None and self.scan.get_num_connections():
            self.scan.publish(self.scan_msg(stamp, robot.scan))
        if self.odom.get_num_connections():
            self.odom.publish(self.odometry_msg(stamp, robot.odom))
        if self.truth.get_num_connections():
            self.truth.publish(self.odometry_msg(stamp, robot.ground_truth))
        if self.stalled.get_num_connections():
            self.stalled.publish(Bool(robot.stalled))
        wanted = CameraTopics.NONE
        if robot.image is not None and self.camera is not None:
            wanted = self.camera.subscribed()
            if any(wanted):
                self.camera.publish(stamp, robot.image, wanted)
        return self.transforms(stamp, robot, any(wanted)) if with_tf else []

    def transforms(self, stamp, robot, with_camera):
        odom = robot.odom
        laser = robot.laser
        chain = [(self.odom_frame, self.footprint_frame, odom.x, odom.y, 0.0,
                  (0.0, 0.0) + quaternion_of_yaw(odom.yaw)),
                 (self.footprint_frame, self.base_frame, 0.0, 0.0, 0.0, (0.0, 0.0, 0.0, 1.0))]
        if laser is not None:
            chain.append((self.base_frame, self.laser_frame, laser.x, laser.y, laser.z,
                          (0.0, 0.0) + quaternion_of_yaw(laser.yaw)))
        if with_camera:
            mount = self.camera.mount
            chain.append((self.base_frame, self.camera.frame, mount.x, mount.y, mount.z,
                          mount.rotation))
        transforms = []
        for parent, child, x, y, z, rotation in chain:
            transform = TransformStamped()
            transform.header.stamp = stamp
            transform.header.frame_id = parent
            transform.child_frame_id = child
            transform.transform.translation.x = x
            transform.transform.translation.y = y
            transform.transform.translation.z = z
            quaternion = transform.transform.rotation
            quaternion.x, quaternion.y, quaternion.z, quaternion.w = rotation
            transforms.append(transform)
        return transforms


class StartRefused(Exception):
    """The world's robots cannot start where they are put; problems: a sentence each."""

    def __init__(self, problems):
        Exception.__init__(self, '; '.join(problems))
        self.problems = problems


class CameraTopics(object):
    """A robot's camera topics, as stageros names them for one camera per robot: image,
    depth and camera_info in frame `camera` (with the robot's prefix)."""

    # subscribed() of a camera nobody watches.
    NONE = (False, False)

    def __init__(self, prefix, spec):
        self.frame = prefix + 'camera'
        self.mount = camera_mount(spec)
        self.image = rospy.Publisher(prefix + 'image', Image, queue_size=10)
        self.depth = rospy.Publisher(prefix + 'depth', Image, queue_size=10)
        self.info = rospy.Publisher(prefix + 'camera_info', CameraInfo, queue_size=10)
        self.info_msg = self._info(spec.camera)

    def subscribed(self):
        """Whether image and depth have a subscriber now, as a pair: stageros renders
        and publishes only while one of them has."""
        return self.image.get_num_connections() > 0, self.depth.get_num_connections() > 0

    def _info(self, camera):
        fx, fy, cx, cy = camera_intrinsics(camera)
        msg = CameraInfo()
        msg.header.frame_id = self.frame
        msg.width, msg.height = camera.resolution
        msg.D = [0.0] * 4
        msg.K = [fx, 0.0, cx, 0.0, fy, cy, 0.0, 0.0, 1.0]
        msg.R = [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0]
        msg.P = [fx, 0.0, cx, 0.0, 0.0, fy, cy, 0.0, 0.0, 0.0, 1.0, 0.0]
        return msg

    def publish(self, stamp, frame, subscribed):
        """One step's image and depth (each if `subscribed` says so) and camera_info."""
        height, width = frame.depth.shape
        with_image, with_depth = subscribed
        if with_image:
            self.image.publish(self._image(stamp, width, height, 'rgba8', 4, frame.rgba))
        if with_depth:
            self.depth.publish(self._image(stamp, width, height, '32FC1', 4, frame.depth))
        self.info_msg.header.stamp = stamp
        self.info.publish(self.info_msg)

    def _image(self, stamp, width, height, encoding, bytes_per_pixel, pixels):
        msg = Image()
        msg.header.stamp = stamp
        msg.header.frame_id = self.frame
        msg.width, msg.height = width, height
        msg.encoding = encoding
        msg.is_bigendian = int(sys.byteorder == 'big')
        msg.step = width * bytes_per_pixel
        msg.data = pixels.tobytes()
        return msg


class StageSimNode(object):
    """Steps a Simulation at the paced rate and speaks stageros' ROS interface.

    The main thread owns the loop; cmd_vel and reset_positions arrive on
    rospy's threads and reach the simulation under one lock.
    """

    # Wall seconds between checks for a stop request while paused.
    PAUSE_POLL = 0.1

    def __init__(self, world, params, quit_time, paused):
        poses = {}
        start = parse_pose(params['pose'])
        if start is not None:
            poses[0] = start
        self._sim = Simulation(world, laser_profile=params['laser_profile'],
                               seed=params['seed'], poses=poses,
                               watchdog_timeout=params['base_watchdog_timeout'])
        problems = start_problems(world, self._sim.grid,
                                  [robot.start_pose for robot in self._sim.robots])
        if problems:
            raise StartRefused(problems)
        self._quit_time = quit_time
        self._lock = threading.Lock()
        count = len(self._sim.robots)
        speedup = params['speedup']
        period = self._sim.dt / speedup if speedup > 0 else 0.0
        self._pacer = StepPacer(period, robot_count=count, lockstep=bool(params['lockstep']),
                                grace=params['lockstep_grace'],
                                timeout=params['lockstep_timeout'],
                                patience=params['late_command_share'] * period)
        self._robots = [RobotTopics(robot_prefix(index, count), robot.spec)
                        for index, robot in enumerate(self._sim.robots)]
        self._clock = rospy.Publisher('/clock', Clock, queue_size=10)
        self._tf = tf2_ros.TransformBroadcaster()
        self._command_subs = []
        for index, topics in enumerate(self._robots):
            self._command_subs.append(rospy.Subscriber(
                topics.prefix + 'cmd_vel', Twist, self._on_cmd_vel, index, queue_size=1))
            self._command_subs.append(rospy.Subscriber(
                topics.prefix + 'cmd_pose', Pose, self._on_cmd_pose, index, queue_size=1))
        keep_connected(self._command_subs)
        self._running = threading.Event()
        if not paused:
            self._running.set()
        self._services = [
            rospy.Service('reset_positions', Empty, self._on_reset),
            rospy.Service('pause_physics', Empty, self._on_pause),
            rospy.Service('unpause_physics', Empty, self._on_unpause),
        ]
        rospy.on_shutdown(self._pacer.stop)

    def request_stop(self, _signal=None, _frame=None):
        """SIGINT/SIGTERM handler. rospy's own handler shuts rospy down right
        where the signal lands, which deadlocks when that is inside a
        publish; this one only asks the loop to end, and main() then shuts
        rospy down from a clean state."""
        self._pacer.request_stop()

    def _on_cmd_vel(self, msg, index):
        arrived = self._pacer.now()   # before a step under way lets it in
        with self._lock:
            self._sim.set_command(index, msg.linear.x, msg.angular.z)
        self._pacer.command_arrived(index, arrived)

    def _on_cmd_pose(self, msg, index):
        yaw = yaw_of(msg.orientation)
        with self._lock:
            self._sim.teleport(index, (msg.position.x, msg.position.y, yaw))
        rospy.loginfo('cmd_pose: robot %d teleported to (%.3f, %.3f, %.1f deg)', index,
                      msg.position.x, msg.position.y, math.degrees(yaw))

    def _on_reset(self, _request):
        with self._lock:
            self._sim.reset()
        rospy.loginfo('reset_positions: robots back at their start poses')
        return EmptyResponse()

    @property
    def running(self):
        return self._running.is_set()

    def _on_pause(self, _request):
        self._running.clear()
        rospy.loginfo('pause_physics: world steps stopped')
        return EmptyResponse()

    def _on_unpause(self, _request):
        self._running.set()
        rospy.loginfo('unpause_physics: world steps resumed')
        return EmptyResponse()

    def run(self):
        """Steps until shutdown or quit_time."""
        first_step = None
        while not rospy.is_shutdown() and not self._pacer.stopped:
            if not self._running.wait(self.PAUSE_POLL):
                continue
            with self._lock:
                driven = self._sim.driven()
            if not self._pacer.wait_turn(driven):
                return
            with_scans = any(topics.scan.get_num_connections() for topics in self._robots)
            with_images = any(topics.camera is not None and any(topics.camera.subscribed())
                              for topics in self._robots)
            if first_step is None:
                first_step = time.time()
            with self._lock:
                # Taken with the step, under the lock the commands come in by: a command
                # that came during the wait drives this step, one that comes later the next.
                idle = self._pacer.lockstep and not any(self._sim.driven())
                frame = self._sim.step(with_scans=with_scans, with_images=with_images, idle=idle)
            self._pacer.readings_out()
            try:
                self._publish(frame)
            except rospy.ROSException:
                if rospy.is_shutdown():   # shut down from outside (rosnode kill) mid-publish
                    return
                raise
            if 0.0 < self._quit_time <= frame.stamp + 1e-9:
                rospy.loginfo(quit_report(frame.stamp, time.time() - first_step))
                return

    def _publish(self, frame):
        """All topics of one step, /clock last as stageros does, so that a
        controller woken by the clock already has this step's scan."""
        stamp = stamp_of(frame.stamp)
        transforms = []
        with_tf = self._tf.pub_tf.get_num_connections() > 0
        for topics, robot in zip(self._robots, frame.robots):
            transforms.extend(topics.publish(stamp, robot, with_tf))
        if with_tf:
            self._tf.sendTransform(transforms)
        self._clock.publish(Clock(clock=stamp))


def parse_args(argv):
    parser = argparse.ArgumentParser(
        prog='stage_sim', description='Stage-compatible simulator with the stageros interface.')
    parser.add_argument('-g', dest='headless', action='store_true',
                        help='headless, as stageros -g (this simulator has no window anyway)')
    parser.add_argument('--simulator', choices=SIMULATORS, default=BUILTIN,
                        help='builtin: this simulator; stage: real stageros (needs stage_ros and '
                        'no -g); auto: real stageros when stage_ros is installed and -g is not '
                        'given, else this simulator')
    parser.add_argument('world', help='Stage .world file')
    return parser.parse_args(argv)


def find_stageros():
    """Path of the real stageros executable, or None when stage_ros is not installed."""
    try:
        found = find_node('stage_ros', 'stageros')
    except rospkg.ResourceNotFound:
        return None
    return found[0] if found else None


def exec_stageros(path, argv, world):
    """Replaces this process by stageros, with its window, and the same remappings."""
    remaps = [arg for arg in argv[1:] if ':=' in arg]
    args = [path, world] + remaps
    sys.stderr.write('stage_sim: running real Stage: %s\n' % ' '.join(args))
    sys.stdout.flush()
    sys.stderr.flush()
    os.execv(path, args)


def main(argv=None):
    argv = list(sys.argv if argv is None else argv)
    args = parse_args(rospy.myargv(argv)[1:])
    stageros = find_stageros() if args.simulator != BUILTIN else None
    choice = choose_simulator(args.simulator, not args.headless, stageros is not None)
    if choice.error:
        sys.stderr.write('stage_sim: error: %s\n' % choice.error)
        return 1
    if choice.note:
        # On stderr, which roslaunch shows even for a node whose output is a log file.
        sys.stderr.write('stage_sim: %s\n' % choice.note)
    if choice.simulator == STAGE:
        exec_stageros(stageros, argv, args.world)
    try:
        world = load_world(args.world)
    except WorldFileError as error:
        sys.stderr.write('stage_sim: error: %s\n' % error)
        return 1
    if not compiled_raytrace.available():
        sys.stderr.write('stage_sim: error: %s\n' % compiled_raytrace.MISSING)
        return 1
    if any(robot.camera is not None for robot in world.robots) and \
            not compiled_camera.available():
        sys.stderr.write('stage_sim: error: %s\n' % compiled_camera.MISSING)
        return 1
    try:
        return run_node(world, argv)
    except KeyboardInterrupt:   # Ctrl-C before our handler is in place
        return 0


def run_node(world, argv):
    """Runs the simulator node on a loaded world; returns the exit status."""
    # disable_rostime: the node is the source of /clock and has no use for
    # reading it back; that self-subscription cost 90% of a free-running step.
    rospy.init_node('stage_sim', argv=argv, disable_signals=True, disable_rostime=True)
    params = NodeParameters(TABLE).snapshot()
    try:
        node = StageSimNode(world, params,
                            params['quit_time'] if params['quit_time'] >= 0.0 else world.quit_time,
                            params['paused'] or bool(world.paused))
    except StartRefused as refused:
        for problem in refused.problems:
            rospy.logerr('stage_sim: cannot start: %s', problem)
        return 1
    except ValueError as error:
        rospy.logerr('~%s', error)
        return 1
    signal.signal(signal.SIGINT, node.request_stop)
    signal.signal(signal.SIGTERM, node.request_stop)
    found = rospy.get_param('/use_sim_time', None)
    if not found:
        rospy.set_param('/use_sim_time', True)
        rospy.logwarn('/use_sim_time was not set: set it now, as stageros does; nodes that '
                      'started before keep wall time (set it in the launch file)')
    rospy.loginfo('world %s: %d robot(s), %d obstacle model(s), resolution %g m, step %g s; '
                  'speedup %s, laser %s%s', world.path, len(world.robots), len(world.obstacles),
                  world.resolution, world.interval_sim,
                  params['speedup'] if params['speedup'] > 0 else 'unlimited',
                  params['laser_profile'], ', lockstep' if params['lockstep'] else '')
    if not node.running:
        rospy.loginfo('paused: call unpause_physics to start the world')
    for warning in world.warnings:
        rospy.logwarn('stage_sim: %s', warning)
    if world.unknown_keywords:
        rospy.logdebug('world keywords skipped: %s', ', '.join(world.unknown_keywords))
    try:
        node.run()
    finally:
        if not found:
            put_back_sim_time(found)
    rospy.signal_shutdown('simulation ended')
    return 0


def put_back_sim_time(found):
    """Undo this node's setting of /use_sim_time: found is what was there (None: nothing).

    At the end of a roslaunch the master may already be gone: then there is
    nothing left to undo.
    """
    try:
        if found is None:
            rospy.delete_param('/use_sim_time')
        else:
            rospy.set_param('/use_sim_time', found)
    except (KeyError, OSError, rospy.ROSException):
        return
    rospy.loginfo('/use_sim_time put back as it was (%s)',
                  'not set' if found is None else repr(found))


if __name__ == '__main__':
    sys.exit(main())
