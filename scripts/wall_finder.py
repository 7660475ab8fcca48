#!/usr/bin/env python3
"""The find_wall service node."""
import _signal; _signal.signal(_signal.SIGINT, _signal.SIG_DFL)  # noqa: E702 (shared/signals.py)
import sys

from wall_follower.nodes.course.wall_finder import main

if __name__ == '__main__':
    sys.exit(main())
