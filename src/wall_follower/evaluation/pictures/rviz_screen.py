"""rviz on a virtual screen: a launch with rviz under Xvfb, and screenshots of it.

For tools/rviz_screenshot.py and the rviz picture check. Xvfb picks a free
display itself (-displayfd), each launch gets a ROS master of its own on a
free port, and everything started here is stopped as a group, so that
nothing is left behind on a machine others share. Needs Xvfb (xvfb) and
ImageMagick's `import` (imagemagick); `missing_tools()` says which are absent.
"""
import os
import shutil
import subprocess

import numpy as np
from PIL import Image

from wall_follower.evaluation.launching import ProcessGroup, free_port, master_environment

SCREEN = (1280, 800)   # pixels: the configs' window (1080 x 760) fits
STOP_WAIT = 15.0       # wall seconds for a launch to end on SIGINT before it is killed
TOOLS = {'Xvfb': 'xvfb', 'import': 'imagemagick', 'rviz': 'rviz'}


def missing_tools():
    """The Debian packages of the programs this needs that are not on PATH."""
    return sorted({package for program, package in TOOLS.items()
                   if shutil.which(program) is None})


class VirtualScreen(object):
    """An Xvfb display for as long as the `with` block lasts."""

    def __init__(self, size=SCREEN):
        self.size = size
        self.display = None
        self._server = None

    def __enter__(self):
        read, write = os.pipe()
        self._server = subprocess.Popen(
            ['Xvfb', '-displayfd', str(write), '-screen', '0', '%dx%dx24' % self.size,
             '-nolisten', 'tcp'], pass_fds=(write,), stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL)
        os.close(write)
        with os.fdopen(read) as stream:
            number = stream.readline().strip()
        if not number:
            self._server.kill()
            self._server.wait()
            raise RuntimeError('Xvfb did not start')
        self.display = ':' + number
        return self

    def __exit__(self, *_exc):
        self._server.terminate()
        self._server.wait()

    def screenshot(self, path):
        """Save the whole screen as an image file; its pixels as an (H, W, 3) uint8 array."""
        subprocess.run(['import', '-display', self.display, '-window', 'root', path],
                       check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        return np.asarray(Image.open(path).convert('RGB'))


class Launch(object):
    """`roslaunch wall_follower LAUNCH ARGS` on a master of its own, drawing on screen."""

    def __init__(self, screen, launch_file, args, log):
        port = free_port()
        self._group = ProcessGroup(grace=STOP_WAIT)
        self.process = self._group.start(
            ['roslaunch', '-p', str(port), 'wall_follower', launch_file] + list(args),
            master_environment(port, dict(os.environ, DISPLAY=screen.display)), log)

    def running(self):
        return self.process.poll() is None

    def stop(self):
        """End the launch and all it started, as Ctrl-C would; killed if it does not end."""
        self._group.stop()
