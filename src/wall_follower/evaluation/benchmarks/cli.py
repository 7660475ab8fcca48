"""Command line of `rosrun wall_follower benchmark`: one table per measured part.

Benchmarks print figures rather than assert them, so that the speed and
quality targets are measured on the machine at hand instead of being timed
inside the test suite.
"""
import argparse
import importlib
import sys

PARTS = {
    'sim': 'simulator speed: free run, held speed-up with a controller, raytrace',
    'follow': 'wall following: time in band, RMS error, clearance, lap time',
    'find': 'find_wall: time to align, final distance and heading errors',
    'wander': 'lab exercise wander: share of the free floor visited in 5 simulated minutes',
    'mapping': 'mapping a lap with drifting odometry: map precision, recall, pose errors, CPU',
    'camera': 'the simulator\'s camera: frames per second at 320x240 and 640x480',
    'arm': 'robot arm: planning time and success on random reachable points, motion time',
    'line': 'camera line following: lap time, speed, cross-track RMS and max, against the lab',
}


def main(argv=None):
    parser = argparse.ArgumentParser(
        prog='benchmark', description=__doc__.splitlines()[0],
        epilog='parts: ' + '; '.join('%s = %s' % item for item in PARTS.items()))
    parser.add_argument('part', nargs='?', default='all', choices=sorted(PARTS) + ['all'])
    args, rest = parser.parse_known_args(argv)
    parts = sorted(PARTS) if args.part == 'all' else [args.part]
    status = 0
    for part in parts:
        print('\n## %s: %s\n' % (part, PARTS[part]))
        sys.stdout.flush()
        module = importlib.import_module('wall_follower.evaluation.benchmarks.' + part)
        status = module.main(rest) or status
    return status


if __name__ == '__main__':
    sys.exit(main())
