#!/usr/bin/env python3
"""Regenerates the floorplan bitmaps of worlds/ from their geometry.

The geometry below is the single source of truth for each map: a free-space
outline in world metres (counter-clockwise), drawn at 0.02 m per pixel with
everything outside it black, and round pillars inside it, black too. The
image is the free-space bounding box plus a 0.10 m wall on every side, so
its black pixels reach all four edges; Stage then scales the whole image to
the floorplan `size` (image pixels x 0.02) and centres it on the floorplan
`pose` (the bounding-box centre), which puts every wall exactly where the
outline says. The .world headers quote these
numbers; change both together.

Pixels are decided in integer centimetres (pixel centres are odd, vertices
even), so the pixels are exact and the files reproducible:

    /usr/bin/python3 tools/make_world_bitmaps.py          # rewrite worlds/*.png
    /usr/bin/python3 tools/make_world_bitmaps.py --check  # exit 1 if any pixel differs
"""
import argparse
import os
import sys

import numpy as np
from PIL import Image

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, 'src'))
from wall_follower.evaluation.worlds.floorplan import png_bytes, render  # noqa: E402

# name -> free-space outline, (x, y) in metres, counter-clockwise.
OUTLINES = {
    # 3.0 x 2.4 m rectangle centred on the origin.
    'room': [(-1.5, -1.2), (1.5, -1.2), (1.5, 1.2), (-1.5, 1.2)],
    # 3.5 x 3.0 m bounding box: an L (top-right 1.0 x 1.0 m block removed,
    # convex corner at (0.75, 0.5)), a 45-degree chamfer at the bottom left
    # and a 1.0 m wide, 0.6 m deep nook in the left wall.
    'arena': [(-0.55, -1.5), (1.75, -1.5), (1.75, 0.5), (0.75, 0.5),
              (0.75, 1.5), (-1.15, 1.5), (-1.15, 0.8), (-1.75, 0.8),
              (-1.75, -0.2), (-1.15, -0.2), (-1.15, -0.9)],
    # 4.0 x 3.0 m room with a 0.4 x 0.6 m pillar down from the top wall and a
    # 0.6 x 0.4 m pillar in from the right wall (the box is a separate model).
    'obstacles': [(-2.0, -1.5), (2.0, -1.5), (2.0, -0.2), (1.4, -0.2),
                  (1.4, 0.2), (2.0, 0.2), (2.0, 1.5), (0.2, 1.5), (0.2, 0.9),
                  (-0.2, 0.9), (-0.2, 1.5), (-2.0, 1.5)],
    # Mapping on angled walls: an octagon 3.0 m across its flats (walls at
    # x, y = +-1.5), its four slanted walls at 45 degrees; the square pillar
    # inside it is a model of octagon.world.
    'octagon': [(-0.62, -1.5), (0.62, -1.5), (1.5, -0.62), (1.5, 0.62), (0.62, 1.5),
                (-0.62, 1.5), (-1.5, 0.62), (-1.5, -0.62)],
    # Mapping on walls that meet at 60 and 120 degrees: a parallelogram, 3.0 m
    # along its walls at y = +-1.09, its other two walls rising 2.18 m over
    # 1.26 m (60 degrees to the first); the pillar is a model of the world.
    'parallelogram': [(-2.13, -1.09), (0.87, -1.09), (2.13, 1.09), (-0.87, 1.09)],
    # Like ROBOTIS's turtlebot3_world, for the lab exercises: a hexagon 5.0 m
    # corner to corner (4.32 m flat to flat) round a 3 x 3 grid of pillars.
    'pillars': [(-2.5, 0.0), (-1.24, -2.16), (1.24, -2.16), (2.5, 0.0), (1.24, 2.16),
                (-1.24, 2.16)],
}

# name -> round pillars standing in the free space, (x, y, radius) in metres.
PILLARS = {
    'pillars': [(x, y, 0.15) for x in (-1.1, 0.0, 1.1) for y in (-1.1, 0.0, 1.1)],
}


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    parser.add_argument('--check', action='store_true',
                        help='compare with the committed PNGs instead of writing them')
    parser.add_argument('--worlds', default=os.path.join(
        os.path.dirname(os.path.abspath(__file__)), os.pardir, 'worlds'))
    args = parser.parse_args(argv)
    stale = []
    for name, outline in sorted(OUTLINES.items()):
        image, size, centre = render(outline, PILLARS.get(name, ()))
        path = os.path.join(args.worlds, name + '.png')
        print('%s.png: %dx%d px, floorplan size [%.3f %.3f], pose [%.3f %.3f]'
              % (name, image.width, image.height, size[0], size[1], centre[0], centre[1]))
        if args.check:
            # pixels, not bytes: another PIL or zlib may compress differently
            if not np.array_equal(np.asarray(Image.open(path).convert('L')), np.asarray(image)):
                stale.append(path)
        else:
            with open(path, 'wb') as out:
                out.write(png_bytes(image))
    for path in stale:
        print('differs from its geometry: %s' % path, file=sys.stderr)
    return 1 if stale else 0


if __name__ == '__main__':
    sys.exit(main())
