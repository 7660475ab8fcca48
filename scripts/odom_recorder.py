#!/usr/bin/env python3
"""The record_odom action server node."""
import _signal; _signal.signal(_signal.SIGINT, _signal.SIG_DFL)  # noqa: E702 (shared/signals.py)
import sys

from wall_follower.nodes.course.odom_recorder import main

if __name__ == '__main__':
    sys.exit(main())
