#!/usr/bin/env python3
"""The find_wall service node."""
from wall_follower.nodes.wall_finder import main

if __name__ == '__main__':
    main()
