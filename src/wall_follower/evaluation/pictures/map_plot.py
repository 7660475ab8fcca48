"""A picture of a saved map beside the world's bitmap it was made in."""
import matplotlib

matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402
from matplotlib.transforms import Affine2D  # noqa: E402
from PIL import Image  # noqa: E402

# Grey levels as map_server's images have them: free white, occupied black, unknown grey.
_SHADES = {0: 254, 100: 0, -1: 205}


def plot_map_and_world(saved_map, bitmap_path, filename, title='', start_pose=None,
                       edges=None):
    """Save a PNG: the saved map left, the world's bitmap right.

    With the robot's true start_pose (x, y, yaw), the map is drawn in the
    world frame (the mapper's map frame starts at the robot's start pose),
    with the world's exact obstacle edges over it in red where given.
    """
    data = saved_map.data
    image = np.full(data.shape, _SHADES[-1], dtype=np.uint8)
    image[data == 0] = _SHADES[0]
    image[data == 100] = _SHADES[100]
    rows, cols = data.shape
    x0, y0 = saved_map.origin[:2]
    extent = (x0, x0 + cols * saved_map.resolution, y0, y0 + rows * saved_map.resolution)
    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 5.5))
    shown = left.imshow(image, cmap='gray', vmin=0, vmax=255, origin='lower', extent=extent,
                        interpolation='nearest')
    frame = 'map frame'
    if start_pose is not None:
        x, y, yaw = start_pose
        shown.set_transform(Affine2D().rotate(yaw).translate(x, y) + left.transData)
        corners = np.array([[extent[0], extent[2]], [extent[1], extent[2]],
                            [extent[1], extent[3]], [extent[0], extent[3]]])
        c, s = np.cos(yaw), np.sin(yaw)
        world = np.column_stack((x + c * corners[:, 0] - s * corners[:, 1],
                                 y + s * corners[:, 0] + c * corners[:, 1]))
        left.set_xlim(world[:, 0].min(), world[:, 0].max())
        left.set_ylim(world[:, 1].min(), world[:, 1].max())
        frame = 'world frame'
    if edges is not None and start_pose is not None:
        left.add_collection(LineCollection(edges, colors='tab:red', linewidths=0.8))
    left.set_aspect('equal')
    left.set_title('saved map (%.3f m cells)%s' % (
        saved_map.resolution, ', true walls in red' if edges is not None else ''))
    left.set_xlabel('x [m], ' + frame)
    left.set_ylabel('y [m]')
    right.imshow(np.asarray(Image.open(bitmap_path).convert('L')), cmap='gray',
                 interpolation='nearest')
    right.set_title('world bitmap')
    right.set_axis_off()
    if title:
        fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(filename, dpi=110)
    plt.close(fig)
