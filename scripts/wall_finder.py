#!/usr/bin/env python3
"""The find_wall service node."""
import sys

from wall_follower.nodes.wall_finder import main

if __name__ == '__main__':
    sys.exit(main())
