"""What a screenshot of rviz shows: the world's walls where they belong, no display in error.

Used by the rviz picture check (test/rostest/check_rviz.py) on screenshots
taken under Xvfb. A top-down orthographic view (every shipped config's)
draws the map at `scale` pixels per metre, x to the right and y up; where
the render panel sits on the screen depends on the window's layout, so the
walls are looked for at every offset (by FFT cross-correlation): the share
of the world's wall pixels drawn dark at the best offset says that they are
drawn (the scan drawn over them hides some), and that offset, against the
one the view's focal point puts them at, whether they are where they
belong. rviz writes the name of a display in error in one red (ERROR_TEXT)
in its Displays panel, left of the render panel.

A view with no map (the arm's) is judged by its robot instead: the share
of the render panel drawn in the hues of the robot's coloured URDF
materials (shading changes a lit surface's brightness, not its hue; the
grid, the background and grey materials have no hue to match).
"""
import xml.etree.ElementTree as ElementTree

import numpy as np
from matplotlib.colors import rgb_to_hsv

ERROR_TEXT = (192, 32, 32)     # rviz's colour of a display's name and status in error
COLOUR_SLACK = 12              # per channel, for anti-aliased text
DARK = 40                      # a drawn wall (black map cell): every channel below this
BACKGROUND = (48, 48, 48)      # the configs' render background
PANEL_SHARE = 0.5              # a render-panel column: at least this share of background
MIN_SATURATION = 0.4           # a coloured material, and a pixel drawn in its colour
HUE_SLACK = 0.025              # of the hue circle (9 degrees), for a pixel of a material's hue


def wall_template(values, resolution, scale):
    """Boolean image (rows top-down) of the occupied cells (value 100) of a map
    (values: rows bottom-up, as map_server's) drawn at `scale` pixels per metre."""
    rows, cols = values.shape
    height = int(np.ceil(rows * resolution * scale))
    width = int(np.ceil(cols * resolution * scale))
    cell_rows = np.minimum(((height - 0.5 - np.arange(height)) / scale / resolution).astype(int),
                           rows - 1)
    cell_cols = np.minimum(((np.arange(width) + 0.5) / scale / resolution).astype(int), cols - 1)
    return values[np.ix_(cell_rows, cell_cols)] == 100


def dark_pixels(rgb):
    """Pixels of an (H, W, 3) image dark enough to be a drawn wall."""
    return np.all(rgb < DARK, axis=2)


def walls_drawn(rgb, template):
    """(share, (row, col)): the largest share of the template's wall pixels found
    dark in rviz's render panel of the screenshot rgb, with the template's
    top-left corner at (row, col) of the screenshot; share 0.0 when there is
    no render panel or the template does not fit in it."""
    found = render_panel(rgb)
    if found is None:
        return 0.0, (0, 0)
    top, bottom, left, right = found
    dark = dark_pixels(rgb[top:bottom, left:right]).astype(float)
    mask = template.astype(float)
    height, width = dark.shape
    if mask.shape[0] > height or mask.shape[1] > width or not mask.any():
        return 0.0, (top, left)
    # Correlation by FFT; wrap-around offsets (the template past the panel's edge) excluded.
    spectrum = np.fft.rfft2(dark) * np.conj(np.fft.rfft2(mask, s=dark.shape))
    counts = np.fft.irfft2(spectrum, s=dark.shape)
    valid = counts[:height - mask.shape[0] + 1, :width - mask.shape[1] + 1]
    row, col = np.unravel_index(int(np.argmax(valid)), valid.shape)
    return float(valid[row, col] / mask.sum()), (top + int(row), left + int(col))


def render_panel(rgb):
    """(top, bottom, left, right): the rows and columns (bottom and right excluded) of
    rviz's render panel, where most pixels have the background colour; None without one."""
    background = np.all(rgb == np.array(BACKGROUND), axis=2)
    columns = np.flatnonzero(background.mean(axis=0) >= PANEL_SHARE)
    if not columns.size:
        return None
    left, right = int(columns[0]), int(columns[-1]) + 1
    rows = np.flatnonzero(background[:, left:right].mean(axis=1) >= PANEL_SHARE)
    return int(rows[0]), int(rows[-1]) + 1, left, right


def expected_corner(panel, origin, shape, scale, focal=(0.0, 0.0)):
    """(row, col) on the screen of the top-left corner of a map's wall template of
    `shape`, whose cell (0, 0) has its corner at `origin` (x, y) in the fixed frame,
    in a render panel (top, bottom, left, right) centred on `focal` (x, y) of the
    fixed frame at `scale` pixels per metre."""
    top, bottom, left, right = panel
    col = (left + right) / 2.0 + (origin[0] - focal[0]) * scale
    bottom_row = (top + bottom) / 2.0 - (origin[1] - focal[1]) * scale
    return bottom_row - shape[0], col


def error_text_pixels(rgb):
    """How many pixels left of the render panel have rviz's colour of a display in error."""
    found = render_panel(rgb)
    panel = rgb[:, :found[2] if found else rgb.shape[1]].astype(int)
    return int(np.all(np.abs(panel - np.array(ERROR_TEXT)) <= COLOUR_SLACK, axis=2).sum())


def material_colours(urdf_text):
    """(r, g, b) in 0..1 of the URDF's materials coloured enough (MIN_SATURATION)
    that the robot's pixels can be told from grey by their hue."""
    colours = []
    for colour in ElementTree.fromstring(urdf_text).iter('color'):
        rgb = [float(value) for value in colour.get('rgba').split()[:3]]
        if rgb_to_hsv(np.array(rgb))[1] >= MIN_SATURATION:
            colours.append(tuple(rgb))
    return colours


def material_share(rgb, colours):
    """The share of rviz's render panel of the screenshot rgb whose pixels have the hue
    of one of `colours` (within HUE_SLACK) and at least MIN_SATURATION; 0.0 with no
    render panel or no colours."""
    found = render_panel(rgb)
    if found is None or not colours:
        return 0.0
    top, bottom, left, right = found
    hsv = rgb_to_hsv(rgb[top:bottom, left:right] / 255.0)
    drawn = np.zeros(hsv.shape[:2], dtype=bool)
    for colour in colours:
        hue = rgb_to_hsv(np.array(colour, dtype=float))[0]
        apart = np.abs(hsv[..., 0] - hue)
        drawn |= (np.minimum(apart, 1.0 - apart) <= HUE_SLACK) & (hsv[..., 1] >= MIN_SATURATION)
    return float(drawn.mean())
