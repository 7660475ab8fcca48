"""Mapping a lap of every world with drifting odometry (its _odom variant).

The loop the nodes of mapping.launch run, in pure Python and simulated
time: the simulator steps, the finder and then the follower answer each
scan from the world's start pose at once (as in mapping.test, where
find_wall turns the robot from the first step: a mapper cannot count on a
scan at rest to start its map), and the mapper takes every scan with the
odometry of its stamp, until the true path has closed its lap; then the
robot stands for a second and the map is saved in map_server's format,
read back and scored against the world (evaluation/scoring/map_quality.py). Each
world is mapped twice: with scan matching, and from raw odometry alone, the
map a mapper without matching would make. CPU time is the mapper's alone,
per scan: a 10 Hz laser leaves it 100 ms.

--generated N maps N generated rooms of --seed instead (see mapping_generated).
"""
import argparse
import math
import os
import shutil
import tempfile
import time

import numpy as np

from wall_follower.control.course.finder import WallFinder
from wall_follower.control.following.follower import WallFollower
from wall_follower.control.motion import clamp
from wall_follower.control.sensing.scan import ScanView
from wall_follower.evaluation.benchmarks import mapping_generated
from wall_follower.evaluation.launching import WORLDS, shipped_world
from wall_follower.evaluation.scoring.course import CourseMap, RunScore
from wall_follower.evaluation.scoring.map_quality import map_quality
from wall_follower.evaluation.tables import fmt, print_table
from wall_follower.mapping.mapfile import load_map, save_map
from wall_follower.mapping.poses import between
from wall_follower.mapping.slam import Mapper
from wall_follower.rotation import wrap_angle
from wall_follower.sim.engine import Simulation
from wall_follower.sim.worldfile import load_world

WORLD_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, os.pardir,
                         os.pardir, os.pardir, 'worlds')
# Simulated seconds the robot stands after the lap before the map is saved.
STAND = 1.0
# The course's worlds, and rooms of angled walls with a pillar (octagon, 60/120-degree corners).
MAPPING_WORLDS = WORLDS + ('octagon', 'parallelogram')


def map_a_lap(world_path, scan_matching=True, map_name=None, time_limit=240.0):
    """One lap mapped; a dict of the run's figures (poses relative to the start)."""
    world = load_world(world_path)
    simulation = Simulation(world)
    course = CourseMap(world_path)
    score = RunScore(course)
    ranger = world.robots[0].ranger
    mapper = Mapper((ranger.pose[0], ranger.pose[1], ranger.pose[3]),
                    scan_matching=scan_matching)
    controller = WallFinder(laser_x=ranger.pose[0])
    controller.start()
    start = simulation.robots[0].start_pose
    path, cpu, slowest, stand_until = [start], 0.0, 0.0, None
    while simulation.time < time_limit:
        robot = simulation.step().robots[0]
        truth = robot.ground_truth
        scan = robot.scan
        angles = scan.angle_min + scan.angle_increment * np.arange(len(scan.ranges))
        started = time.process_time()
        pose = mapper.add_scan(scan.ranges, angles, scan.range_min, scan.range_max,
                               (robot.odom.x, robot.odom.y, robot.odom.yaw))
        spent = time.process_time() - started
        cpu += spent
        slowest = max(slowest, spent)
        path.append((truth.x, truth.y, truth.yaw))
        if stand_until is None:
            if isinstance(controller, WallFinder) and controller.done:
                controller = WallFollower()
            if isinstance(controller, WallFollower):
                score.add_pose(simulation.time, path[-1])
            if score.lap.closed:
                stand_until = simulation.time + STAND
            command = clamp(controller.update(ScanView(scan.ranges, scan.angle_min,
                                                       scan.angle_increment, scan.range_min,
                                                       scan.range_max)))
            simulation.set_command(0, *command)
        elif simulation.time >= stand_until:
            break
    values, origin = mapper.occupancy_map()
    directory = None
    if map_name is None:
        directory = tempfile.mkdtemp(prefix='benchmark-map-')
        map_name = os.path.join(directory, 'map')
    save_map(map_name, values, mapper.grid.resolution, origin)
    quality = map_quality(load_map(map_name + '.yaml'), world_path, start, path,
                          mapper.config['max_range'])
    if directory:
        shutil.rmtree(directory)
    true = between(start, path[-1])
    odom = (robot.odom.x, robot.odom.y, robot.odom.yaw)

    def error(estimate):
        return (math.hypot(estimate[0] - true[0], estimate[1] - true[1]),
                abs(math.degrees(wrap_angle(estimate[2] - true[2]))))

    return {'precision': quality.precision, 'recall': quality.recall,
            'worst_distance': quality.worst_distance,
            'pose_error': error(pose), 'odom_error': error(odom),
            'cpu_ms': 1000.0 * cpu / max(mapper.scans, 1), 'cpu_max_ms': 1000.0 * slowest,
            'scans': mapper.scans,
            'lap_closed': score.lap.closed, 'time': simulation.time}


def main(argv=None):
    parser = argparse.ArgumentParser(prog='benchmark mapping', description=__doc__)
    parser.add_argument('--worlds', nargs='+', default=list(MAPPING_WORLDS),
                        type=shipped_world('_odom'))
    parser.add_argument('--maps', default='',
                        help='keep the maps (with scan matching) here as WORLD_odom.pgm/.yaml')
    parser.add_argument('--generated', type=int, metavar='N',
                        help='map N generated rooms with drifting odometry instead')
    parser.add_argument('--seed', type=int, default=1, help="with --generated: the rooms' seed")
    parser.add_argument('--out', default='',
                        help='with --generated: keep the worlds and maps here')
    args = parser.parse_args(argv)
    if args.generated:
        return mapping_generated.run(args.generated, args.seed, args.out,
                                     os.path.join(WORLD_DIR, 'burger.inc'), map_a_lap)
    rows = []
    for name in args.worlds:
        path = os.path.join(WORLD_DIR, name + '_odom.world')
        keep = os.path.join(args.maps, name + '_odom') if args.maps else None
        matched = map_a_lap(path, True, keep)
        raw = map_a_lap(path, False)
        rows.append([name + '_odom', 'yes' if matched['lap_closed'] else 'NO',
                     fmt(100 * matched['precision'], '.1f'), fmt(100 * matched['recall'], '.1f'),
                     fmt(100 * matched['worst_distance'], '.1f'),
                     fmt(100 * matched['pose_error'][0], '.1f'),
                     fmt(matched['pose_error'][1], '.2f'),
                     fmt(100 * matched['odom_error'][0], '.1f'),
                     fmt(matched['odom_error'][1], '.2f'),
                     fmt(100 * raw['precision'], '.1f'), fmt(100 * raw['recall'], '.1f'),
                     fmt(matched['cpu_ms'], '.1f'), fmt(matched['cpu_max_ms'], '.1f'),
                     fmt(raw['cpu_ms'], '.1f')])
    print_table(['world', 'lap', 'precision %', 'recall %', 'worst cell cm', 'mapper cm',
                 'mapper deg', 'odom cm', 'odom deg', 'odom-only precision %', 'odom-only recall %',
                 'CPU ms/scan', 'slowest scan ms', 'odom-only CPU ms/scan'], rows)
    print('\nfinal pose errors after the lap and a second standing, against ground truth;')
    print('goals: precision and recall >= 99 %, no occupied cell more than 10 cm from a true '
          'wall, mapper within 3 cm and 1 deg, CPU per scan well under 100 ms (10 Hz on one '
          'core)')
    return 0
