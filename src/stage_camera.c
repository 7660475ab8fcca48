/*
 * The built-in simulator's camera: one ray per pixel against the floor and the
 * world's models, loaded by wall_follower/sim/compiled_camera.py through ctypes.
 *
 * What is drawn, and why, is in wall_follower/sim/camera.py, which prepares the
 * rays and the tables here. Each model ("solid") is its outline edges extruded
 * from zmin to zmax: its top is the even-odd interior of the edges (looked up
 * in a filled raster when it has many edges), its sides the edges themselves.
 * A pixel takes the colour of the nearest hit whose depth (the ray parameter:
 * rays have a forward component of 1) lies in [near, far).
 */
#include <math.h>
#include <stdint.h>

struct camera_scene {
    int64_t solid_count;
    const double *edges;          /* x1 y1 x2 y2 of every edge of every solid */
    const int64_t *edge_start;    /* solid s owns edges [edge_start[s], edge_start[s + 1]) */
    const double *zspan;          /* zmin zmax per solid */
    const double *bounds;         /* xmin ymin xmax ymax per solid */
    const uint8_t *colors;        /* r g b per solid */
    const uint8_t *sides;         /* 1: draw the solid's sides */
    const uint8_t *raster;        /* the filled rasters, row-major, one after the other */
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

static int inside(const struct camera_scene *scene, int64_t s, double x, double y)
{
    if (scene->raster_start[s] >= 0) {
        double col = floor((x - scene->raster_origin[2 * s]) / scene->raster_cell);
        double row = floor((y - scene->raster_origin[2 * s + 1]) / scene->raster_cell);
        int64_t rows = scene->raster_shape[2 * s], cols = scene->raster_shape[2 * s + 1];
        if (row < 0 || col < 0 || row >= (double)rows || col >= (double)cols)
            return 0;
        return scene->raster[scene->raster_start[s] + (int64_t)row * cols + (int64_t)col];
    }
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

/* The nearest hit on one scene's solids closer than *best; updates *best and *color. */
static void shade(const struct camera_scene *scene, const struct camera_view *view,
                  const uint8_t *hidden_sides, const double *reach, const double *ray,
                  double *best, const uint8_t **color)
{
    const double ex = view->eye[0], ey = view->eye[1], ez = view->eye[2];
    const double dx = ray[0], dy = ray[1], dz = ray[2];
    const double horizontal = hypot(dx, dy);
    for (int64_t s = 0; s < scene->solid_count; ++s) {
        if (reach[s] >= view->far_clip || reach[s] > *best * horizontal)
            continue;
        const double zmin = scene->zspan[2 * s], zmax = scene->zspan[2 * s + 1];
        if (dz != 0.0) {
            double t = (zmax - ez) / dz;
            if (t >= view->near_clip && t < view->far_clip && t < *best &&
                inside(scene, s, ex + t * dx, ey + t * dy)) {
                *best = t;
                *color = scene->colors + 3 * s;
            }
        }
        if (!scene->sides[s] || hidden_sides[s])
            continue;
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
 * sides are hidden: the eye is over the solid's top and so far above it that every ray
 * reaching a side passes through the top first, beyond the near clip (nearer, the top
 * is clipped away and the sides seen from inside show through, as in OpenGL).
 * steepest: the largest |z| of a pixel ray. */
static void prepare(const struct camera_scene *scene, const struct camera_view *view,
                    double steepest, double *reach, uint8_t *hidden_sides)
{
    for (int64_t s = 0; s < scene->solid_count; ++s) {
        reach[s] = box_distance(scene->bounds + 4 * s, view->eye[0], view->eye[1]);
        hidden_sides[s] = view->eye[2] - scene->zspan[2 * s + 1] >= view->near_clip * steepest &&
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
            shade(scenes + k, view, hidden_sides + offset, reach + offset, ray, &best, &color);
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
