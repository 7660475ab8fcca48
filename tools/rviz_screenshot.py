#!/usr/bin/env python3
"""Run a launch of wall_follower with rviz on a virtual screen (Xvfb) and save a screenshot.

    /usr/bin/python3 tools/rviz_screenshot.py OUT.png main.launch sim:=true world:=arena
    /usr/bin/python3 tools/rviz_screenshot.py --after 40 /tmp/mapping.png mapping.launch \
        sim:=true map_file:=/tmp/map

The launch gets rviz:=true and a ROS master of its own on a free port; the
screenshot is taken `--after` wall seconds after it starts, then the launch
is stopped. Needs the workspace built and sourced (tools/workspace.sh),
and rviz, xvfb and imagemagick installed.
"""
import argparse
import os
import sys
import tempfile
import time

from wall_follower.evaluation.pictures.rviz_screen import Launch, VirtualScreen, missing_tools


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument('out', help='image file to write (PNG)')
    parser.add_argument('launch', help="a launch file of wall_follower's launch/")
    parser.add_argument('args', nargs='*', help='its arguments, NAME:=VALUE')
    parser.add_argument('--after', type=float, default=25.0,
                        help='wall seconds from the start to the screenshot (default 25)')
    options = parser.parse_args()
    missing = missing_tools()
    if missing:
        sys.stderr.write('rviz_screenshot: not installed: %s (apt-get install %s)\n'
                         % (', '.join(missing), ' '.join(missing)))
        return 1
    with VirtualScreen() as screen, tempfile.NamedTemporaryFile('w+', suffix='.log') as log:
        launch = Launch(screen, options.launch, options.args + ['rviz:=true'], log)
        try:
            deadline = time.monotonic() + options.after
            while launch.running() and time.monotonic() < deadline:
                time.sleep(0.5)
            if not launch.running():
                log.seek(0)
                sys.stderr.write(log.read()[-3000:])
                sys.stderr.write('rviz_screenshot: the launch ended early (its output is above)\n')
                return 1
            screen.screenshot(os.path.abspath(options.out))
        finally:
            launch.stop()
    print(os.path.abspath(options.out))
    return 0


if __name__ == '__main__':
    sys.exit(main())
