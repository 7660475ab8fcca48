/*
 * The built-in simulator's camera: one ray per pixel against the floor and the
 * world's models, loaded by wall_follower/sim/compiled_camera.py through ctypes.
 *
 * What is drawn, and why, is in wall_follower/sim/camera.py, which prepares the
 * rays and the tables here. Each model ("solid") is its outline edges extruded
 * from zmin to zmax: its top is the even-odd interior of the edges (looked up
 * in a filled raster when it has many edges), its sides the edges themselves
 * (for a flat solid with a raster: the boundaries between its filled and empty
 * cells, met by walking the cells along the ray). A pixel takes the colour of the nearest hit whose depth (the ray parameter:
 * rays have a forward component of 1) lies in [near, far).
 */
#include <math.h>
#include <stdint.h>

/* A raster cell's bits: inside the solid's outline; a neighbour (of the eight) is not of
 * the same kind (compiled_camera.RASTER_FILLED, RASTER_BORDER). */
#define RASTER_FILLED 1
#define RASTER_BORDER 2

struct camera_scene {
    int64_t solid_count;
    const double *edges;          /* x1 y1 x2 y2 of every edge of every solid */
    const int64_t *edge_start;    /* solid s owns edges [edge_start[s], edge_start[s + 1]) */
    const double *zspan;          /* zmin zmax per solid */
    const double *bounds;         /* xmin ymin xmax ymax per solid */
    const uint8_t *colors;        /* r g b per solid */
    const uint8_t *walk_sides;    /* 1: find side hits by walking the raster (flat solids),
                                     0: by testing every edge */
    const uint8_t *convex;        /* 1: the edges are one convex polygon */
    const uint8_t *raster;        /* the rasters, row-major, one after the other: per cell
                                     RASTER_FILLED and RASTER_BORDER bits */
    const int64_t *raster_start;  /* per solid: offset into raster, or -1 (crossing test) */
    const int64_t *raster_shape;  /* rows cols per solid */
    const double *raster_origin;  /* x y of each raster's first cell corner */
    double raster_cell;
};

struct camera_view {
    int64_t width, height;        /* pixels */
    const double *u, *v;          /* per column, per row: the pixel centre's offsets right
                                     and down from the optical axis, in focal lengths */
    double basis[9];              /* world forward, right and down of the camera (x y z each):
                                     a pixel's ray is forward + u right + v down */
    double eye[3];
    double near_clip, far_clip;
    double floor_bounds[4];       /* xmin ymin xmax ymax of the white floor */
    uint8_t floor_color[3];
    uint8_t background[3];
    uint8_t *rgba;                /* out: count x 4 */
    float *depth;                 /* out: count, +inf where nothing was drawn */
};

/* The raster byte of solid s's cell at (x, y): RASTER_FILLED, RASTER_BORDER bits; 0 off
 * the raster. */
static uint8_t raster_code(const struct camera_scene *scene, int64_t s, double x, double y)
{
    double col = floor((x - scene->raster_origin[2 * s]) / scene->raster_cell);
    double row = floor((y - scene->raster_origin[2 * s + 1]) / scene->raster_cell);
    int64_t rows = scene->raster_shape[2 * s], cols = scene->raster_shape[2 * s + 1];
    if (row < 0 || col < 0 || row >= (double)rows || col >= (double)cols)
        return 0;
    return scene->raster[scene->raster_start[s] + (int64_t)row * cols + (int64_t)col];
}

static int inside(const struct camera_scene *scene, int64_t s, double x, double y)
{
    if (scene->raster_start[s] >= 0)
        return raster_code(scene, s, x, y) & RASTER_FILLED;
    int odd = 0;
    for (int64_t e = scene->edge_start[s]; e < scene->edge_start[s + 1]; ++e) {
        const double *edge = scene->edges + 4 * e;
        if (edge[1] == edge[3])
            continue;
        if ((edge[1] <= y) != (edge[3] <= y)) {
            double cross = edge[0] + (y - edge[1]) * (edge[2] - edge[0]) / (edge[3] - edge[1]);
            if (x < cross)
                odd = !odd;
        }
    }
    return odd;
}

static double box_distance(const double *box, double x, double y)
{
    double nx = x < box[0] ? box[0] : (x > box[2] ? box[2] : x);
    double ny = y < box[1] ? box[1] : (y > box[3] ? box[3] : y);
    return hypot(nx - x, ny - y);
}

/* The depth at which a ray first crosses a side face of raster solid s: a boundary
 * between a filled and an empty cell, met while the ray is within the solid's z-span,
 * at a depth in [near, limit); INFINITY if there is none. The cells are walked in the
 * ray's order (Amanatides and Woo). A flat solid's z-span is a few millimetres of the
 * ray, seldom more than a cell: there a start cell whose neighbours are all of its own
 * kind (no RASTER_BORDER bit) ends the search at once. */
static double raster_side(const struct camera_scene *scene, int64_t s, const double *eye,
                          const double *ray, double near, double limit)
{
    const double zmin = scene->zspan[2 * s], zmax = scene->zspan[2 * s + 1];
    double from = 0.0, to = limit;
    if (ray[2] == 0.0) {
        if (eye[2] < zmin || eye[2] > zmax)
            return INFINITY;
    } else {
        const double t1 = (zmin - eye[2]) / ray[2], t2 = (zmax - eye[2]) / ray[2];
        from = fmax(from, fmin(t1, t2));
        to = fmin(to, fmax(t1, t2));
    }
    if (from >= to)
        return INFINITY;
    const double cell = scene->raster_cell;
    const double ox = scene->raster_origin[2 * s], oy = scene->raster_origin[2 * s + 1];
    const int64_t rows = scene->raster_shape[2 * s], cols = scene->raster_shape[2 * s + 1];
    const uint8_t *mask = scene->raster + scene->raster_start[s];
    const int short_span = (to - from) * fabs(ray[0]) < cell && (to - from) * fabs(ray[1]) < cell;
    int from_outside = 0;   /* the span starts where the ray enters the raster's box */
    if (!short_span) {
        /* Only the part of the ray over the raster's box can cross a side. */
        const double *box = scene->bounds + 4 * s;
        for (int axis = 0; axis < 2; ++axis) {
            if (ray[axis] == 0.0) {
                if (eye[axis] < box[axis] || eye[axis] > box[axis + 2])
                    return INFINITY;
                continue;
            }
            const double t1 = (box[axis] - eye[axis]) / ray[axis];
            const double t2 = (box[axis + 2] - eye[axis]) / ray[axis];
            if (fmin(t1, t2) > from) {
                from = fmin(t1, t2);
                from_outside = 1;
            }
            to = fmin(to, fmax(t1, t2));
        }
        if (from >= to)
            return INFINITY;
    }
    int64_t col = (int64_t)floor((eye[0] + from * ray[0] - ox) / cell);
    int64_t row = (int64_t)floor((eye[1] + from * ray[1] - oy) / cell);
    int in_range = row >= 0 && col >= 0 && row < rows && col < cols;
    const uint8_t start = in_range ? mask[row * cols + col] : 0;
    if (short_span && in_range && !(start & RASTER_BORDER))
        return INFINITY;
    int filled = start & RASTER_FILLED;
    /* Entering the box into a filled cell is crossing a side, on the box's edge. */
    if (filled && from_outside && from >= near)
        return from;
    const int64_t step_col = ray[0] > 0.0 ? 1 : -1, step_row = ray[1] > 0.0 ? 1 : -1;
    double next_col = ray[0] == 0.0 ? INFINITY :
        ((double)(col + (ray[0] > 0.0)) * cell + ox - eye[0]) / ray[0];
    double next_row = ray[1] == 0.0 ? INFINITY :
        ((double)(row + (ray[1] > 0.0)) * cell + oy - eye[1]) / ray[1];
    const double col_span = ray[0] == 0.0 ? INFINITY : cell / fabs(ray[0]);
    const double row_span = ray[1] == 0.0 ? INFINITY : cell / fabs(ray[1]);
    for (;;) {
        double t;
        if (next_col < next_row) {
            t = next_col;
            next_col += col_span;
            col += step_col;
        } else {
            t = next_row;
            next_row += row_span;
            row += step_row;
        }
        if (t >= to)
            return INFINITY;
        in_range = row >= 0 && col >= 0 && row < rows && col < cols;
        const int now = in_range && (mask[row * cols + col] & RASTER_FILLED);
        if (now != filled && t >= near)
            return t;
        filled = now;
    }
}

/* The nearest hit on one scene's solids closer than *best; updates *best and *color.
 * horizontal: the length of the ray's x, y. */
static void shade(const struct camera_scene *scene, const struct camera_view *view,
                  const uint8_t *hidden_sides, const double *reach, const double *ray,
                  double horizontal, double *best, const uint8_t **color)
{
    const double ex = view->eye[0], ey = view->eye[1], ez = view->eye[2];
    const double dx = ray[0], dy = ray[1], dz = ray[2];
    for (int64_t s = 0; s < scene->solid_count; ++s) {
        if (reach[s] >= view->far_clip || reach[s] > *best * horizontal)
            continue;
        const double zmin = scene->zspan[2 * s], zmax = scene->zspan[2 * s + 1];
        if (ez > zmax) {
            /* From above, a ray meets nothing of the solid before its top's plane: going up,
             * nothing at all; through the top, nothing nearer. */
            if (dz >= 0.0)
                continue;
            const double t = (zmax - ez) / dz;
            if (t >= *best || t >= view->far_clip)
                continue;
            if (t >= view->near_clip) {
                const double x = ex + t * dx, y = ey + t * dy;
                if (scene->walk_sides[s]) {
                    /* Over a cell whose neighbours are all empty, a ray that stays within a
                     * cell's reach over the solid's height meets no side either. */
                    const uint8_t code = raster_code(scene, s, x, y);
                    const double span = (zmax - zmin) / -dz;
                    if (code & RASTER_FILLED) {
                        *best = t;
                        *color = scene->colors + 3 * s;
                        continue;
                    }
                    if (!(code & RASTER_BORDER) && span * fabs(dx) < scene->raster_cell &&
                        span * fabs(dy) < scene->raster_cell)
                        continue;
                } else if (inside(scene, s, x, y)) {
                    *best = t;
                    *color = scene->colors + 3 * s;
                    continue;
                }
            }
        } else if (ez <= zmin && dz <= 0.0) {
            /* From level with its base or below, only a ray going up meets a solid. */
            continue;
        } else if (dz != 0.0) {
            const double t = (zmax - ez) / dz;
            if (t >= view->near_clip && t < view->far_clip && t < *best &&
                inside(scene, s, ex + t * dx, ey + t * dy)) {
                *best = t;
                *color = scene->colors + 3 * s;
            }
        }
        if (hidden_sides[s])
            continue;
        if (scene->walk_sides[s]) {
            const double limit = *best < view->far_clip ? *best : view->far_clip;
            const double t = raster_side(scene, s, view->eye, ray, view->near_clip, limit);
            if (t < limit) {
                *best = t;
                *color = scene->colors + 3 * s;
            }
            continue;
        }
        for (int64_t e = scene->edge_start[s]; e < scene->edge_start[s + 1]; ++e) {
            const double *edge = scene->edges + 4 * e;
            const double sx = edge[2] - edge[0], sy = edge[3] - edge[1];
            const double det = sx * dy - sy * dx;
            if (det == 0.0)
                continue;
            const double wx = edge[0] - ex, wy = edge[1] - ey;
            const double t = (sx * wy - sy * wx) / det;
            if (t < view->near_clip || t >= view->far_clip || t >= *best)
                continue;
            const double along = (dx * wy - dy * wx) / det;
            if (along < 0.0 || along > 1.0)
                continue;
            const double z = ez + t * dz;
            if (z < zmin || z > zmax)
                continue;
            *best = t;
            *color = scene->colors + 3 * s;
        }
    }
}

/* Per-frame facts of a scene: each solid's distance from the eye in xy, and whether its
 * sides are hidden: the solid is convex, the eye is over its top and so far above it
 * that every ray reaching a side passes through the top first, beyond the near clip
 * (nearer, the top is clipped away and the sides seen from inside show through, as in
 * OpenGL). Over a concave solid (a line's bend) a ray may leave the top's outline and
 * meet a side of another part of it.
 * steepest: the largest |z| of a pixel ray. */
static void prepare(const struct camera_scene *scene, const struct camera_view *view,
                    double steepest, double *reach, uint8_t *hidden_sides)
{
    for (int64_t s = 0; s < scene->solid_count; ++s) {
        reach[s] = box_distance(scene->bounds + 4 * s, view->eye[0], view->eye[1]);
        hidden_sides[s] = scene->convex[s] &&
            view->eye[2] - scene->zspan[2 * s + 1] >= view->near_clip * steepest &&
            reach[s] == 0.0 && inside(scene, s, view->eye[0], view->eye[1]);
    }
}

/* The largest |z| of the pixel rays: z is linear in u and v, so it is at a corner. */
static double steepest_ray(const struct camera_view *view)
{
    const double *b = view->basis;
    double most = 0.0;
    for (int corner = 0; corner < 4; ++corner) {
        double u = view->u[corner & 1 ? view->width - 1 : 0];
        double v = view->v[corner & 2 ? view->height - 1 : 0];
        double z = fabs(b[2] + u * b[5] + v * b[8]);
        if (z > most)
            most = z;
    }
    return most;
}

/* Renders `view` over `scene_count` scenes; reach and hidden_sides are scratch space
 * of one entry per solid of all the scenes. */
void camera_render(const struct camera_scene *scenes, int64_t scene_count,
                   const struct camera_view *view, double *reach, uint8_t *hidden_sides)
{
    int64_t offset = 0;
    const double steepest = steepest_ray(view);
    for (int64_t k = 0; k < scene_count; ++k) {
        prepare(scenes + k, view, steepest, reach + offset, hidden_sides + offset);
        offset += scenes[k].solid_count;
    }
    const double ex = view->eye[0], ey = view->eye[1], ez = view->eye[2];
    const double *fb = view->floor_bounds, *b = view->basis;
    for (int64_t p = 0; p < view->width * view->height; ++p) {
        const double u = view->u[p % view->width], v = view->v[p / view->width];
        const double ray[3] = {b[0] + u * b[3] + v * b[6], b[1] + u * b[4] + v * b[7],
                               b[2] + u * b[5] + v * b[8]};
        const double horizontal = sqrt(ray[0] * ray[0] + ray[1] * ray[1]);
        double best = INFINITY;
        const uint8_t *color = view->background;
        if (ray[2] < 0.0) {
            double t = -ez / ray[2];
            double x = ex + t * ray[0], y = ey + t * ray[1];
            if (t >= view->near_clip && t < view->far_clip &&
                x >= fb[0] && x <= fb[2] && y >= fb[1] && y <= fb[3]) {
                best = t;
                color = view->floor_color;
            }
        }
        offset = 0;
        for (int64_t k = 0; k < scene_count; ++k) {
            shade(scenes + k, view, hidden_sides + offset, reach + offset, ray, horizontal,
                  &best, &color);
            offset += scenes[k].solid_count;
        }
        uint8_t *out = view->rgba + 4 * p;
        out[0] = color[0];
        out[1] = color[1];
        out[2] = color[2];
        out[3] = 255;
        view->depth[p] = (float)best;
    }
}
