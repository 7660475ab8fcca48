#!/usr/bin/env python3
"""The wall following node: find_wall, then record_odom, then follow the right wall."""
import _signal; _signal.signal(_signal.SIGINT, _signal.SIG_DFL)  # noqa: E702 (shared/signals.py)
import sys

from wall_follower.nodes.course.wall_following import main

if __name__ == '__main__':
    sys.exit(main())
