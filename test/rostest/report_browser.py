"""A grading's pages as a real browser shows them: headless Chromium's DOM (after the page's
script has run) and its screenshot, and what the checks read from them.

Chromium runs as root here, so without its sandbox, with a fresh profile each time, no
network services and no GPU (Debian's `chromium`; `--dump-dom` and `--screenshot` need
no driver). Every process it starts is ended with it (launching.ProcessGroup).
"""
import os
import shutil
import subprocess
import tempfile
from html.parser import HTMLParser

import cv2
import numpy as np
from PIL import Image
from scipy import ndimage

from wall_follower.evaluation.launching import ProcessGroup

FLAGS = ['--headless', '--no-sandbox', '--disable-gpu', '--no-first-run',
         '--disable-background-networking', '--disable-component-update', '--disable-sync',
         '--hide-scrollbars', '--force-device-scale-factor=1', '--force-color-profile=srgb',
         '--virtual-time-budget=1000']
WALL_LIMIT = 90.0
# The verdict cells' backgrounds (page.STYLE: td.pass, td.fail, td.na).
COLOURS = {'pass': (0xd4, 0xf0, 0xd4), 'fail': (0xf6, 0xcc, 0xcc), 'na': (0xee, 0xee, 0xee)}
# A verdict cell is at least this many pixels of its colour (a word and a border around).
LEAST_CELL = 400
BLUR = 1.5


def chromium():
    """The browser's command; AssertionError when it is not installed (the tests need it:
    tools/run-tests installs Debian's chromium)."""
    path = shutil.which('chromium')
    assert path, 'no chromium on PATH (apt-get install chromium)'
    return path


def _run(words, url):
    """Run chromium with words on url; its standard output."""
    profile = tempfile.mkdtemp(prefix='report-browser-')
    try:
        with ProcessGroup(grace=2.0) as group, tempfile.TemporaryFile() as out:
            process = group.start([chromium()] + FLAGS + ['--user-data-dir=' + profile] + words
                                  + [url], log=out, errors=subprocess.DEVNULL)
            process.wait(timeout=WALL_LIMIT)
            out.seek(0)
            return out.read().decode('utf-8', 'replace')
    finally:
        shutil.rmtree(profile, ignore_errors=True)


def url_of(path, fragment=''):
    return 'file://' + os.path.abspath(path) + (('#' + fragment) if fragment else '')


def dom(path, fragment=''):
    """The page's DOM as the browser holds it once loaded and scripted."""
    return Page(_run(['--dump-dom'], url_of(path, fragment)))


def screenshot(path, size=(1500, 1300), fragment=''):
    """The page as the browser draws it in a window of size (width, height): RGB array."""
    descriptor, shot = tempfile.mkstemp(suffix='.png')
    os.close(descriptor)
    try:
        _run(['--screenshot=' + shot, '--window-size=%d,%d' % size], url_of(path, fragment))
        with Image.open(shot) as image:
            return np.asarray(image.convert('RGB'))
    finally:
        os.unlink(shot)


class Page(HTMLParser):
    """What the checks read from a dumped DOM: the table's rows in order, with their data-*
    attributes, whether hidden, their verdict cells (criterion: class), their pictures, the
    'plot not found' notes and the count of rows shown."""

    def __init__(self, text):
        HTMLParser.__init__(self)
        self.text = text
        self.rows = []
        self.missing = []
        self.shown = None
        self.links = []
        self._in = None
        self.feed(text)

    def handle_starttag(self, tag, attrs):
        attrs = dict(attrs)
        if tag == 'tr' and attrs.get('class') in ('case', 'student'):
            self.rows.append({'data': {k[5:]: v for k, v in attrs.items()
                                       if k.startswith('data-')},
                              'hidden': 'hidden' in attrs, 'verdicts': {}, 'images': []})
        elif tag == 'td' and 'data-criterion' in attrs and self.rows:
            self.rows[-1]['verdicts'][attrs['data-criterion']] = attrs.get('class')
        elif tag == 'img' and self.rows:
            self.rows[-1]['images'].append(attrs.get('src'))
        elif tag == 'a' and self.rows:
            self.links.append(attrs.get('href'))
        elif tag == 'span' and attrs.get('class') == 'missing':
            self._in = 'missing'
        elif tag == 'span' and attrs.get('id') == 'shown':
            self._in = 'shown'

    def handle_data(self, data):
        if self._in == 'missing':
            self.missing.append(data)
        elif self._in == 'shown':
            self.shown = data
        self._in = None

    def visible(self):
        return [row for row in self.rows if not row['hidden']]


def cells_of_colour(shot, colour):
    """The regions of exactly colour (4-connected), at least LEAST_CELL pixels each, top to
    bottom then left to right: (top, left, pixels)."""
    mask = np.all(shot == np.array(colour, dtype=shot.dtype), axis=2)
    labels, count = ndimage.label(mask)
    found = []
    for index, region in enumerate(ndimage.find_objects(labels), 1):
        pixels = int(np.sum(labels[region] == index))
        if pixels >= LEAST_CELL:
            found.append((region[0].start, region[1].start, pixels))
    return sorted(found)


def _soft(rgb):
    """Grey, slightly blurred: what is left of a picture whatever filter scaled it."""
    grey = cv2.cvtColor(np.ascontiguousarray(rgb, dtype=np.uint8), cv2.COLOR_RGB2GRAY)
    return cv2.GaussianBlur(grey.astype(np.float32), (0, 0), BLUR)


def find_picture(shot, picture, width):
    """(score, (left, top)) of the best match of the PNG picture, shown `width` px wide, in
    the screenshot (score: normalised correlation, 1 for the same pixels). The browser's
    scaling filter is not PIL's: both are compared grey and blurred by BLUR pixels."""
    with Image.open(picture) as image:
        image = image.convert('RGB')
        height = int(round(image.height * width / float(image.width)))
        small = np.asarray(image.resize((width, height), Image.BILINEAR))
    result = cv2.matchTemplate(_soft(shot), _soft(small), cv2.TM_CCOEFF_NORMED)
    _, score, _, where = cv2.minMaxLoc(result)
    return score, where
