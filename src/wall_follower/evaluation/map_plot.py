"""A picture of a saved map beside the world's bitmap it was made in."""
import matplotlib

matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402  (the backend must be chosen first)
import numpy as np  # noqa: E402
from PIL import Image  # noqa: E402

# Grey levels as map_server's images have them: free white, occupied black, unknown grey.
_SHADES = {0: 254, 100: 0, -1: 205}


def plot_map_and_world(saved_map, bitmap_path, filename, title=''):
    """Save a PNG: the saved map (its own frame, metres) left, the world's bitmap right."""
    data = saved_map.data
    image = np.full(data.shape, _SHADES[-1], dtype=np.uint8)
    image[data == 0] = _SHADES[0]
    image[data == 100] = _SHADES[100]
    rows, cols = data.shape
    x0, y0 = saved_map.origin[:2]
    extent = (x0, x0 + cols * saved_map.resolution, y0, y0 + rows * saved_map.resolution)
    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 5.5))
    left.imshow(image, cmap='gray', vmin=0, vmax=255, origin='lower', extent=extent,
                interpolation='nearest')
    left.set_title('saved map (%.3f m cells)' % saved_map.resolution)
    left.set_xlabel('x [m], map frame')
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
