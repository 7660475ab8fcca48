"""Stage's colour names, as (r, g, b) in [0, 1].

Stage looks a model's `color` up in X11's rgb.txt. Debian and Ubuntu ship
that table (package x11-common), and it is read from there when it exists;
a few common names are built in so that the simulator still knows them on a
machine without it. `grayN` / `greyN` (N in 0..100) follow X11's formula.
"""
import functools
import os
import re

__all__ = ['color_by_name', 'RGB_FILES']

RGB_FILES = ('/usr/share/X11/rgb.txt', '/etc/X11/rgb.txt')

_BUILT_IN = {
    'black': (0, 0, 0), 'white': (255, 255, 255), 'red': (255, 0, 0), 'green': (0, 255, 0),
    'blue': (0, 0, 255), 'yellow': (255, 255, 0), 'cyan': (0, 255, 255),
    'magenta': (255, 0, 255), 'orange': (255, 165, 0), 'gray': (190, 190, 190),
    'grey': (190, 190, 190), 'dark gray': (169, 169, 169), 'light gray': (211, 211, 211),
    'navy': (0, 0, 128), 'brown': (165, 42, 42), 'gold': (255, 215, 0),
}
_GRAY_RE = re.compile(r'^gr[ae]y(\d{1,3})$')


@functools.lru_cache(maxsize=1)
def _table():
    table = dict((name, rgb) for name, rgb in _BUILT_IN.items())
    for path in RGB_FILES:
        if not os.path.isfile(path):
            continue
        with open(path) as stream:
            for line in stream:
                fields = line.split(None, 3)
                if len(fields) == 4 and all(field.isdigit() for field in fields[:3]):
                    table[fields[3].strip().lower()] = tuple(int(f) for f in fields[:3])
        break
    return table


def color_by_name(name):
    """(r, g, b) in [0, 1] of an X11 colour name; KeyError if it is unknown."""
    key = name.strip().lower()
    gray = _GRAY_RE.match(key)
    if gray and int(gray.group(1)) <= 100:
        level = int(int(gray.group(1)) * 255 / 100.0 + 0.5) / 255.0
        return (level, level, level)
    rgb = _table()[key]
    return tuple(value / 255.0 for value in rgb)
