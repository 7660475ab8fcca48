"""`rosrun wall_follower map_png MAP.yaml WORLD OUT.png`: a saved map beside its world.

A PNG of a saved map (map_server's YAML) over a world's bitmap and its
true walls. The map is placed in the world at the robot's start pose in
the world file (where the mapper's map frame begins). WORLD is a .world
file, or the name of a world in the package's worlds/.

    rosrun wall_follower map_png ~/arena.yaml arena out.png
"""
import argparse
import os
import re
import sys

from wall_follower.evaluation.outputs import output_problem
from wall_follower.evaluation.pictures.map_plot import plot_map_and_world
from wall_follower.evaluation.scoring.course import CourseMap
from wall_follower.mapping.mapfile import load_map
from wall_follower.sim.stage_interface import world_path
from wall_follower.sim.worldfile import WorldFileError


def bitmap_of(world):
    """The first floorplan bitmap a .world file names, as a path."""
    with open(world) as stream:
        found = re.search(r'^\s*bitmap\s+"([^"]+)"', stream.read(), re.MULTILINE)
    if not found:
        raise ValueError('%s names no bitmap' % world)
    return os.path.join(os.path.dirname(os.path.abspath(world)), found.group(1))


def main(argv=None):
    parser = argparse.ArgumentParser(prog='map_png', description=__doc__.splitlines()[0])
    parser.add_argument('map_yaml', help='the saved map: NAME.yaml')
    parser.add_argument('world', help='a .world file, or the name of one in worlds/')
    parser.add_argument('png', help='output file')
    args = parser.parse_args(argv)
    world = args.world if args.world.endswith('.world') else world_path(args.world)
    problem = output_problem(args.png)
    if not os.path.isfile(world):
        problem = 'no world %s (neither a .world file nor a world of worlds/)' % args.world
    if problem:
        sys.stderr.write('map_png: %s\n' % problem)
        return 1
    try:
        saved = load_map(args.map_yaml)
        bitmap = bitmap_of(world)
        course = CourseMap(world)
        plot_map_and_world(saved, bitmap, args.png, os.path.basename(args.map_yaml),
                           course.robot.pose, course.edges)
    except (IOError, OSError, ValueError, WorldFileError) as err:
        sys.stderr.write('map_png: %s\n' % err)
        return 1
    print('wrote %s' % args.png)
    return 0
