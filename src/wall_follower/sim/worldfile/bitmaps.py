"""Obstacle outlines as real Stage makes them: a bitmap's black pixels merged into runs, a
model's blocks scaled to its `size`, and `boundary 1`'s four walls."""
import numpy as np


# Black pixels: Stage treats a pixel as free when its first channel is above 127.
_BITMAP_THRESHOLD = 127


def polygon_edges(points):
    """Directed edges of the closed polygon through `points` ((N, 2) -> (N, 2, 2))."""
    points = np.asarray(points, dtype=float)
    return np.stack([points, np.roll(points, -1, axis=0)], axis=1)


def boundary_blocks(blocks, size):
    """Stage's `boundary 1`: four thin walls along the (scaled) bounding box."""
    edges, _ = fit_to_size(blocks, size)
    flat = edges.reshape(-1, 2)
    xmin, ymin = flat.min(axis=0)
    xmax, ymax = flat.max(axis=0)
    eps = 0.01
    sx, sy = xmax - xmin, ymax - ymin

    def rect(x, y, dx, dy):
        corners = [[x, y], [x + dx, y], [x + dx, y + dy], [x, y + dy]]
        return (polygon_edges(corners), 0.0, size[2])
    return [rect(xmin, ymin, eps, sy), rect(xmin, ymin, sx, eps),
            rect(xmin, ymax - eps, sx, eps), rect(xmax - eps, ymin, eps, sy)]


def fit_to_size(blocks, size):
    """Scale and centre blocks so their joint bounding box fills `size` (Stage CalcSize).

    Returns all edges as one (M, 2, 2) array and the model's (zmin, zmax).
    """
    eps = np.finfo(float).eps
    edges = np.concatenate([b[0] for b in blocks])
    flat = edges.reshape(-1, 2)
    bmin = flat.min(axis=0)
    bmax = flat.max(axis=0)
    extent = np.where(np.abs(bmax - bmin) >= eps, bmax - bmin, eps)
    offset = bmin + extent / 2.0
    zmin = min(b[1] for b in blocks)
    zmax = max(b[2] for b in blocks)
    zextent = zmax - zmin if abs(zmax - zmin) >= eps else eps
    scaled = np.empty_like(edges)
    scaled[..., 0] = (edges[..., 0] - offset[0]) * (size[0] / extent[0])
    scaled[..., 1] = (edges[..., 1] - offset[1]) * (size[1] / extent[1])
    return scaled, (zmin * (size[2] / zextent), zmax * (size[2] / zextent))


def black_pixels(path):
    from PIL import Image
    with Image.open(path) as image:
        image.load()
        if image.mode in ('RGBA', 'LA', 'P'):
            image = image.convert('RGBA')
        bands = image.split()
        first = np.asarray(bands[0], dtype=np.uint8)
        if image.mode == 'RGBA':
            # Fully transparent pixels count as white, like a blank canvas.
            alpha = np.asarray(bands[3], dtype=np.uint8)
            return (first <= _BITMAP_THRESHOLD) & (alpha > 0)
        return first <= _BITMAP_THRESHOLD


def bitmap_edges(black):
    """Directed black/white boundary edges of a boolean image, in Stage's bitmap frame.

    Pixel (row r, column c) spans x in [c, c+1] and y in [-(r+1), -r]: image row 0 is the
    top (+y) edge. Each edge is one maximal straight run of boundary, directed the way
    Stage's image tracing walks a black pixel's sides (top +x, right -y, bottom -x,
    left +y), because Stage's line rasteriser gives different cells in either direction.
    """
    black = np.asarray(black, dtype=bool)
    padded = np.pad(black, 1, mode='constant', constant_values=False)
    inner = padded[1:-1, 1:-1]
    runs = []
    runs += _runs(inner & ~padded[:-2, 1:-1], horizontal=True, forward=True, offset=0)
    runs += _runs(inner & ~padded[2:, 1:-1], horizontal=True, forward=False, offset=1)
    runs += _runs(inner & ~padded[1:-1, 2:], horizontal=False, forward=True, offset=1)
    runs += _runs(inner & ~padded[1:-1, :-2], horizontal=False, forward=False, offset=0)
    return np.array(runs, dtype=float).reshape(-1, 2, 2)


def _runs(mask, horizontal, forward, offset):
    """Maximal runs of True in `mask` along rows (horizontal) or columns, as directed segments."""
    if not horizontal:
        mask = mask.T
    out = []
    padded = np.zeros((mask.shape[0], mask.shape[1] + 2), dtype=np.int8)
    padded[:, 1:-1] = mask
    diff = np.diff(padded, axis=1)
    starts = np.argwhere(diff == 1)
    ends = np.argwhere(diff == -1)
    for (line, a), (_, b) in zip(starts, ends):
        # the run covers pixels a .. b-1 along the line; its edge spans a .. b
        lo, hi = float(a), float(b)
        first, last = (lo, hi) if forward else (hi, lo)
        if horizontal:
            y = -float(line + offset)
            out.append([[first, y], [last, y]])
        else:
            x = float(line + offset)
            out.append([[x, -first], [x, -last]])
    return out
