/* tether — measures of a pile of equal circles, the same for every engine:
 * height, and overlap as a fraction of a radius (deepest, and the mean over
 * the pairs that overlap at all), and the contacts per circle (pairs within
 * 1 % of a radius of touching: what a resting engine keeps apart by its
 * slop or margin still touches). The height is the fill level: the median
 * over columns one diameter wide of the highest circle top in each, so one
 * circle rolling on top of the pile does not move it. */
#include "scene.h"

#include <math.h>
#include <stdlib.h>

static int by_x(const void *p, const void *q)
{
    const double a = *(const double *)p, b = *(const double *)q;
    return (a > b) - (a < b);
}

static int by_value(const void *p, const void *q)
{
    const double a = *(const double *)p, b = *(const double *)q;
    return (a > b) - (a < b);
}

/* xy sorted by x: the median of the columns' highest tops. */
static double fill_level(const double *xy, uint32_t n, double r)
{
    if (n == 0) return 0;
    const double x0 = xy[0], width = xy[2 * (n - 1)] - x0;
    const uint32_t cols = (uint32_t)(width / (2 * r)) + 1;
    double *top = malloc(cols * sizeof *top);
    if (!top) return NAN;
    for (uint32_t c = 0; c < cols; c++) top[c] = -INFINITY;
    for (uint32_t i = 0; i < n; i++) {
        uint32_t c = (uint32_t)((xy[2 * i] - x0) / (2 * r));
        if (c >= cols) c = cols - 1;
        top[c] = fmax(top[c], xy[2 * i + 1] + r);
    }
    uint32_t k = 0; /* columns no circle fell in are left out */
    for (uint32_t c = 0; c < cols; c++)
        if (top[c] > -INFINITY) top[k++] = top[c];
    qsort(top, k, sizeof *top, by_value);
    const double h = k % 2 ? top[k / 2] : 0.5 * (top[k / 2 - 1] + top[k / 2]);
    free(top);
    return h;
}

void ts_pile_measure(double *xy, uint32_t n, double r, ts_pile *out)
{
    if (!out) return;
    *out = (ts_pile){NAN, NAN, NAN, 0, NAN};
    if ((!xy && n) || !(r > 0)) return;
    /* sorted by x, a circle's neighbours within reach follow it: no grid needed */
    qsort(xy, n, 2 * sizeof *xy, by_x);
    const double reach = 2.01 * r;
    double deepest = 0, sum = 0;
    uint32_t pairs = 0, touching = 0;
    for (uint32_t i = 0; i < n; i++) {
        for (uint32_t j = i + 1; j < n && xy[2 * j] - xy[2 * i] < reach; j++) {
            const double dx = xy[2 * j] - xy[2 * i], dy = xy[2 * j + 1] - xy[2 * i + 1], d2 = dx * dx + dy * dy;
            if (d2 < reach * reach) touching++;
            if (d2 >= 4 * r * r) continue;
            const double depth = 2 * r - sqrt(d2);
            deepest = fmax(deepest, depth);
            sum += depth;
            pairs++;
        }
    }
    out->height = fill_level(xy, n, r);
    out->max_overlap = deepest / r;
    out->mean_overlap = pairs ? sum / pairs / r : 0;
    out->overlapping = pairs;
    out->contacts = n ? 2.0 * touching / n : 0;
}
