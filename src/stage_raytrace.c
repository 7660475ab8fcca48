/*
 * Stage's laser raytrace, one beam after another, stepped cell by cell.
 *
 * The simulator's only raytrace (src/wall_follower/sim/raytrace.py's docstring
 * says what Stage does to a beam and why); it loads this library through
 * ctypes (wall_follower/sim/compiled_raytrace.py), whose Structures mirror the
 * two structs below field for field. test/unit/stage_raytrace_oracle.py is
 * this loop transliterated into scalar Python, the oracle the tests hold it to:
 * change the two together.
 *
 * Positions are doubles in cell units, moved by +-1 per cell step and by the
 * crossings of each flight as running sums, as in Stage, so that rounding
 * happens where Stage's does. Build without -ffast-math and with
 * -ffp-contract=off: a fused multiply-add would round differently.
 */
#include <math.h>
#include <stdint.h>

#define REGION_BITS 5
#define REGION_WIDTH (1 << REGION_BITS)

/* The grid's lookup tables (compiled_raytrace.GridTables); outside them nothing is visible
   and no region is populated. */
struct grid_tables {
  const uint8_t *visible;   /* per cell, rows of `width` cells from cell (cx0, cy0) */
  const double *returns;    /* intensity of a visible cell, same layout */
  int64_t width, height, cx0, cy0;
  const uint8_t *populated; /* per region, rows of `region_cols` from region (rx0, ry0) */
  int64_t region_cols, region_rows, rx0, ry0;
  double ppm;               /* cells per metre */
};

/* The beams of one scan (compiled_raytrace.Beams), and where their readings go. */
struct beams {
  int64_t count;
  const double *cosa, *sina, *tana; /* direction (tana = sina / cosa, 0 rad already nudged) */
  const int64_t *ax, *ay;           /* the cells to range_max along x and along y */
  double range_max;                 /* metres */
  double *ranges, *intensities;     /* out, per beam */
};

/* Region of a truncated cell coordinate: floor division, also below zero. */
static int64_t region_of(int64_t cell)
{
  return cell >= 0 ? cell / REGION_WIDTH : -((-cell + REGION_WIDTH - 1) / REGION_WIDTH);
}

static int populated(const struct grid_tables *t, int64_t rx, int64_t ry)
{
  rx -= t->rx0;
  ry -= t->ry0;
  if (rx < 0 || ry < 0 || rx >= t->region_cols || ry >= t->region_rows)
    return 0;
  return t->populated[ry * t->region_cols + rx];
}

/* Index of a visible cell in `visible` / `returns`, or -1. */
static int64_t visible_cell(const struct grid_tables *t, int64_t x, int64_t y)
{
  x -= t->cx0;
  y -= t->cy0;
  if (x < 0 || y < 0 || x >= t->width || y >= t->height)
    return -1;
  return t->visible[y * t->width + x] ? y * t->width + x : -1;
}

/* A region border ahead of a flying beam along one axis. */
struct crossing {
  double x, y;         /* where the beam crosses it */
  double hop_x, hop_y; /* how that point moves on to the next border along the axis */
  double hop_length;   /* Manhattan length of such a hop */
  double distance;     /* Manhattan distance still to fly to it */
};

static struct crossing first_crossing(double gx, double gy, double dx, double dy, double hop_x,
                                      double hop_y)
{
  const struct crossing c = {gx + dx, gy + dy, hop_x, hop_y, fabs(hop_x) + fabs(hop_y),
                             fabs(dx) + fabs(dy)};
  return c;
}

/*
 * Fly to the border `taken`, paying its distance from the budget (truncated,
 * as Stage's integer budget is), and move it on to the next border along its
 * axis; the other border comes that much nearer.
 */
static void fly_to(struct crossing *taken, struct crossing *other, double *gx, double *gy,
                   int64_t *budget)
{
  *gx = taken->x;
  *gy = taken->y;
  *budget = (int64_t)((double)*budget - taken->distance);
  taken->x += taken->hop_x;
  taken->y += taken->hop_y;
  other->distance -= taken->distance;
  taken->distance = taken->hop_length;
}

/*
 * One beam from (startx, starty) in cell units. cosa, sina, tana: its
 * direction (tana = sina / cosa, the beam at exactly 0 rad already nudged);
 * ax, ay: the cells to range_max along x and y. Writes the range in cells
 * travelled along the major axis (over its direction cosine) and the hit
 * cell's intensity; returns 0 when the beam hits nothing within its budget.
 */
static int trace_beam(const struct grid_tables *t, double startx, double starty,
                      double cosa, double sina, double tana, int64_t ax, int64_t ay,
                      double *range, double *intensity)
{
  const int64_t sx = cosa < 0.0 ? -1 : 1;
  const int64_t sy = sina < 0.0 ? -1 : 1;
  const double region_x = (double)(sx * REGION_WIDTH), region_y = (double)(sy * REGION_WIDTH);
  double gx = startx, gy = starty;
  /* The cell path's error term: step along x while it is negative. */
  int64_t error = ay - ax;
  int64_t budget = ax + ay;
  struct crossing along_x = {0}, along_y = {0};
  int crossings_stale = 1;

  while (budget > 0) {
    const int64_t ix = (int64_t)gx; /* truncated, as Stage's int conversion */
    const int64_t iy = (int64_t)gy;
    const int64_t rx = region_of(ix), ry = region_of(iy);
    if (populated(t, rx, ry)) {
      /* Walk the region cell by cell, from the cell of the position. */
      int64_t cx = ix, cy = iy;
      crossings_stale = 1;
      while (region_of(cx) == rx && region_of(cy) == ry && budget > 0) {
        const int64_t cell = visible_cell(t, cx, cy);
        if (cell >= 0) {
          *range = ax > ay ? fabs((gx - startx) / cosa) : fabs((gy - starty) / sina);
          *intensity = t->returns[cell];
          return 1;
        }
        if (error < 0) {
          gx += (double)sx;
          error += 2 * ay;
          cx += sx;
        } else {
          gy += (double)sy;
          error -= 2 * ax;
          cy += sy;
        }
        --budget;
      }
      continue;
    }
    /* Fly over the empty region to the nearer of the next x and y border crossings. */
    if (crossings_stale) {
      const double left = (double)(rx * REGION_WIDTH), bottom = (double)(ry * REGION_WIDTH);
      const double dx = sx < 0 ? left - gx - 1.0 : left + REGION_WIDTH - gx;
      const double dy = sy < 0 ? bottom - gy - 1.0 : bottom + REGION_WIDTH - gy;
      along_x = first_crossing(gx, gy, dx, dx * tana, region_x, region_x * tana);
      along_y = first_crossing(gx, gy, dy / tana, dy, region_y / tana, region_y);
      crossings_stale = 0;
    }
    if (along_x.distance < along_y.distance)
      fly_to(&along_x, &along_y, &gx, &gy, &budget);
    else
      fly_to(&along_y, &along_x, &gx, &gy, &budget);
  }
  return 0;
}

/*
 * All beams of a scan from (x, y), in metres. Fills in every beam's range, in metres
 * (range_max exactly, intensity 0, for a beam that hits nothing), and intensity.
 */
void stage_raytrace(const struct grid_tables *t, const struct beams *b, double x, double y)
{
  const double startx = x * t->ppm, starty = y * t->ppm;
  int64_t beam;
  for (beam = 0; beam < b->count; ++beam) {
    double cells = 0.0, intensity = 0.0;
    if (trace_beam(t, startx, starty, b->cosa[beam], b->sina[beam], b->tana[beam], b->ax[beam],
                   b->ay[beam], &cells, &intensity)) {
      b->ranges[beam] = cells / t->ppm;
      b->intensities[beam] = intensity;
    } else {
      b->ranges[beam] = b->range_max;
      b->intensities[beam] = 0.0;
    }
  }
}
