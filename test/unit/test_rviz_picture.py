"""Reading rviz screenshots: the walls found where the view puts them, displays in error."""
import numpy as np

from wall_follower.evaluation.pictures.rviz_picture import (BACKGROUND, ERROR_TEXT,
                                                            error_text_pixels, expected_corner,
                                                            material_colours, material_share,
                                                            render_panel, wall_template,
                                                            walls_drawn)

RESOLUTION = 0.05
SCALE = 40.0            # pixels per metre: 2 per cell
PANEL = (20, 220, 100, 400)   # top, bottom, left, right of the render panel on the screen


def room():
    """A 2 m x 1.5 m walled room (rows bottom-up, 100 = wall) with a pillar near a corner."""
    values = np.zeros((30, 40), dtype=np.int8)
    values[0, :] = values[-1, :] = values[:, 0] = values[:, -1] = 100
    values[3:6, 3:5] = 100
    return values


def screen(template=None, corner=None):
    """A screenshot: a grey Displays panel, the render panel, walls drawn black at corner."""
    rgb = np.full((240, 420, 3), 200, dtype=np.uint8)
    top, bottom, left, right = PANEL
    rgb[top:bottom, left:right] = BACKGROUND
    if template is not None:
        row, col = corner
        rgb[row:row + template.shape[0], col:col + template.shape[1]][template] = (14, 14, 14)
    return rgb


def test_template_is_the_map_at_scale_top_row_first():
    template = wall_template(room(), RESOLUTION, SCALE)
    assert template.shape == (60, 80)
    assert template[0].all() and template[-1].all()
    # The pillar sits near the bottom-left corner of the map, so near the template's bottom.
    assert template[-12:-6, 6:10].all() and not template[6:12, 6:10].any()


def test_walls_found_where_the_view_puts_them():
    template = wall_template(room(), RESOLUTION, SCALE)
    origin, focal = (-1.0, -0.5), (0.0, 0.0)
    corner = expected_corner(PANEL, origin, template.shape, SCALE, focal)
    assert corner == (120.0 + 20.0 - 60.0, 250.0 - 40.0)
    rgb = screen(template, (int(corner[0]), int(corner[1])))
    assert render_panel(rgb) == PANEL
    share, found = walls_drawn(rgb, template)
    assert share == 1.0 and found == (80, 210)


def test_walls_elsewhere_are_found_off_their_place():
    template = wall_template(room(), RESOLUTION, SCALE)
    share, found = walls_drawn(screen(template, (100, 250)), template)
    assert share == 1.0
    assert found != expected_corner(PANEL, (-1.0, -0.5), template.shape, SCALE)


def test_no_walls_drawn_no_share():
    template = wall_template(room(), RESOLUTION, SCALE)
    assert walls_drawn(screen(), template)[0] == 0.0


def test_error_red_counts_left_of_the_render_panel_only():
    rgb = screen()
    assert error_text_pixels(rgb) == 0
    rgb[50:55, 10:40] = ERROR_TEXT
    assert error_text_pixels(rgb) == 150
    rgb[50:55, 150:200] = ERROR_TEXT   # a red scan in the render panel is no error
    assert error_text_pixels(rgb) == 150


ARM_URDF = """<robot name="arm">
  <material name="grey"><color rgba="0.6 0.6 0.6 1.0"/></material>
  <material name="orange"><color rgba="0.95 0.55 0.1 1.0"/></material>
  <link name="base"><visual><geometry><box size="1 1 1"/></geometry>
    <material name="blue"><color rgba="0.2 0.35 0.8 1"/></material></visual></link>
</robot>"""
ORANGE = (0.95, 0.55, 0.1)
BLUE = (0.2, 0.35, 0.8)


def test_material_colours_are_the_coloured_ones_not_grey():
    assert material_colours(ARM_URDF) == [ORANGE, BLUE]


def test_a_shaded_link_counts_in_its_materials_hue():
    rgb = screen()
    top, bottom, left, right = PANEL
    rgb[top:top + 60, left:left + 30] = (121, 70, 13)       # the orange link, in shadow
    rgb[top:top + 60, left + 30:left + 60] = (242, 140, 26)   # lit
    area = (bottom - top) * (right - left)
    assert abs(material_share(rgb, [ORANGE, BLUE]) - 3600.0 / area) < 1e-9


def test_no_robot_drawn_no_share():
    rgb = screen()
    top, bottom, left, right = PANEL
    rgb[top + 10:top + 12, left:right] = (160, 160, 164)    # the grid
    rgb[top + 50:top + 60, left:left + 40] = (255, 0, 0)    # a red axis of the TF display
    rgb[top + 70:top + 80, left:left + 40] = (0, 0, 255)    # a blue one
    assert material_share(rgb, [ORANGE, BLUE]) == 0.0
    assert material_share(screen(), []) == 0.0
