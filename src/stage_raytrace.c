/*
 * Stage's laser raytrace, one beam after another, as a C loop.
 *
 * The same model of Stage's beam as src/wall_follower/sim/raytrace.py (read
 * its docstring for what Stage does and why), stepped cell by cell instead
 * of in closed form: numpy pays per call, so it needs about a thousand calls
 * per scan whatever the number of beams, while this loop pays per cell
 * visited. The simulator loads this library through ctypes
 * (wall_follower/sim/compiled_raytrace.py) and falls back on numpy without it.
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

/* The grid's lookup tables, as laid out by raytrace.py's _GridTables. */
struct grid_tables {
  const uint8_t *visible;   /* per cell, rows of `width` cells from cell (cx0, cy0) */
  const double *returns;    /* intensity of a visible cell, same layout */
  int64_t width, height, cx0, cy0;
  const uint8_t *populated; /* per region, rows of `region_cols` from region (rx0, ry0) */
  int64_t region_cols, region_rows, rx0, ry0;
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
  /* Flights: a region along x (along y) moves the crossing by these. */
  const double xhop_x = (double)(sx * REGION_WIDTH);
  const double xhop_y = (double)(sx * REGION_WIDTH) * tana;
  const double yhop_x = (double)(sy * REGION_WIDTH) / tana;
  const double yhop_y = (double)(sy * REGION_WIDTH);
  const double xhop_length = fabs(xhop_x) + fabs(xhop_y);
  const double yhop_length = fabs(yhop_x) + fabs(yhop_y);
  double gx = startx, gy = starty;
  /* The cell path's error term: step along x while it is negative. */
  int64_t error = ay - ax;
  int64_t budget = ax + ay;
  double xcross_x = 0.0, xcross_y = 0.0, ycross_x = 0.0, ycross_y = 0.0;
  double to_xcross = 0.0, to_ycross = 0.0;
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
      const double rise = dx * tana, run = dy / tana;
      crossings_stale = 0;
      xcross_x = gx + dx;
      xcross_y = gy + rise;
      ycross_x = gx + run;
      ycross_y = gy + dy;
      to_xcross = fabs(dx) + fabs(rise);
      to_ycross = fabs(run) + fabs(dy);
    }
    if (to_xcross < to_ycross) {
      gx = xcross_x;
      gy = xcross_y;
      budget = (int64_t)((double)budget - to_xcross);
      xcross_x += xhop_x;
      xcross_y += xhop_y;
      to_ycross -= to_xcross;
      to_xcross = xhop_length;
    } else {
      gx = ycross_x;
      gy = ycross_y;
      budget = (int64_t)((double)budget - to_ycross);
      ycross_x += yhop_x;
      ycross_y += yhop_y;
      to_xcross -= to_ycross;
      to_ycross = yhop_length;
    }
  }
  return 0;
}

/*
 * All beams of a scan. ranges and intensities are filled in for every beam:
 * in metres (range_max exactly, intensity 0, for a beam that hits nothing).
 */
void stage_raytrace(const uint8_t *visible, const double *returns, int64_t width, int64_t height,
                    int64_t cx0, int64_t cy0, const uint8_t *populated_regions,
                    int64_t region_cols, int64_t region_rows, int64_t rx0, int64_t ry0,
                    double ppm, double startx, double starty, int64_t count, const double *cosa,
                    const double *sina, const double *tana, const int64_t *ax, const int64_t *ay,
                    double range_max, double *ranges, double *intensities)
{
  const struct grid_tables t = {visible, returns, width, height, cx0, cy0,
                                populated_regions, region_cols, region_rows, rx0, ry0};
  int64_t beam;
  for (beam = 0; beam < count; ++beam) {
    double cells = 0.0, intensity = 0.0;
    if (trace_beam(&t, startx, starty, cosa[beam], sina[beam], tana[beam], ax[beam], ay[beam],
                   &cells, &intensity)) {
      ranges[beam] = cells / ppm;
      intensities[beam] = intensity;
    } else {
      ranges[beam] = range_max;
      intensities[beam] = 0.0;
    }
  }
}
