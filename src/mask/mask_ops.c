/* tether — drawing into masks: one mask ORed into (draw) or cleared out of
 * (erase) another at an offset, and circles, rectangles and polygons
 * filled in or cut out. */
#include "mask_internal.h"

#include <math.h>
#include <stdlib.h>

/* dst's words OR (erase false) or AND NOT (erase true) src's placed at (dx, dy). */
static tt_result combine(const char *fn, tt_mask *dst, const tt_mask *src, int dx, int dy, bool erase)
{
    tt__mask_shift s;
    if (!dst || !src) return tt__mask_fail(TT_EINVAL, "%s: %s is NULL", fn, dst ? "src" : "dst");
    tt_result r = tt__mask_check_offset(fn, dx, dy);
    if (r != TT_OK) return r;
    if (!tt__mask_shift_of(&s, dst, src, dx, dy)) return TT_OK;
    /* src may be dst: read each of src's rows before writing it */
    uint64_t *tmp = NULL;
    if (src == dst && !(tmp = malloc((size_t)src->stride * sizeof *tmp)))
        return tt__mask_fail(TT_ENOMEM, "%s: out of memory", fn);
    int y0 = s.y0, y1 = s.y1, step = 1;
    if (src == dst && dy > 0) { y0 = s.y1 - 1; y1 = s.y0 - 1; step = -1; } /* rows read before they are written */
    for (int y = y0; y != y1; y += step) {
        uint64_t *d = tt__mask_row(dst, y);
        const uint64_t *b = tt__mask_row(src, y - dy);
        if (tmp) {
            for (int k = 0; k < src->stride; k++) tmp[k] = b[k];
            b = tmp;
        }
        for (int k = s.k0; k <= s.k1; k++) {
            uint64_t v = tt__mask_bword(b, src->stride, &s, k);
            d[k] = erase ? d[k] & ~v : d[k] | v;
        }
    }
    free(tmp);
    tt__mask_clear_tail(dst);
    return TT_OK;
}

tt_result tt_mask_draw(tt_mask *dst, const tt_mask *src, int dx, int dy)
{
    return combine("tt_mask_draw", dst, src, dx, dy, false);
}

tt_result tt_mask_erase(tt_mask *dst, const tt_mask *src, int dx, int dy)
{
    return combine("tt_mask_erase", dst, src, dx, dy, true);
}

/* Sets or clears pixels x0…x1 (inclusive, inside the mask) of row y, a word at a time. */
static void fill_span(tt_mask *m, int y, int x0, int x1, bool value)
{
    uint64_t *row = tt__mask_row(m, y);
    for (int k = x0 >> 6; k <= x1 >> 6; k++) {
        int lo = k * 64 > x0 ? 0 : x0 & 63, hi = k * 64 + 63 < x1 ? 63 : x1 & 63;
        uint64_t bits = (hi == 63 ? ~(uint64_t)0 : (((uint64_t)1 << (hi + 1)) - 1)) & ~(((uint64_t)1 << lo) - 1);
        row[k] = value ? row[k] | bits : row[k] & ~bits;
    }
}

tt_result tt_mask_fill_rect(tt_mask *m, int x, int y, int w, int h, bool value)
{
    if (!m) return tt__mask_fail(TT_EINVAL, "tt_mask_fill_rect: mask is NULL");
    /* no abs(): abs(INT_MIN) is INT_MIN, which passed */
    if (w < 0 || h < 0 || w > TT_MASK_MAX_OFFSET || h > TT_MASK_MAX_OFFSET || x < -TT_MASK_MAX_OFFSET ||
        x > TT_MASK_MAX_OFFSET || y < -TT_MASK_MAX_OFFSET || y > TT_MASK_MAX_OFFSET)
        return tt__mask_fail(TT_EINVAL, "tt_mask_fill_rect: rect (%d, %d, %d, %d) has a negative size or lies beyond ±%d",
                             x, y, w, h, TT_MASK_MAX_OFFSET);
    int x0 = x < 0 ? 0 : x, y0 = y < 0 ? 0 : y, x1 = x + w > m->w ? m->w : x + w, y1 = y + h > m->h ? m->h : y + h;
    for (int r = y0; r < y1 && x0 < x1; r++) fill_span(m, r, x0, x1 - 1, value);
    return TT_OK;
}

static bool bad_coord(double v)
{
    return !(fabs(v) <= 1e6); /* NaN fails too */
}

tt_result tt_mask_fill_circle(tt_mask *m, double cx, double cy, double r, bool value)
{
    if (!m) return tt__mask_fail(TT_EINVAL, "tt_mask_fill_circle: mask is NULL");
    if (bad_coord(cx) || bad_coord(cy) || bad_coord(r) || r < 0)
        return tt__mask_fail(TT_EINVAL, "tt_mask_fill_circle: centre (%g, %g) or radius %g not finite within 1e6 (radius ≥ 0)",
                             cx, cy, r);
    for (int y = 0; y < m->h; y++) {
        double ey = y + 0.5 - cy, half2 = r * r - ey * ey;
        if (half2 < 0) continue;
        double half = sqrt(half2);
        /* pixel x is inside when |x + 0.5 − cx| ≤ half */
        double lo = ceil(cx - half - 0.5), hi = floor(cx + half - 0.5);
        if (lo < 0) lo = 0;
        if (hi > m->w - 1) hi = m->w - 1;
        if (lo <= hi) fill_span(m, y, (int)lo, (int)hi, value);
    }
    return TT_OK;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Even-odd scanline fill at pixel centres; xs has room for n crossings. */
static void polygon_rows(tt_mask *m, const tt_vec2 *p, uint32_t n, double *xs, bool value)
{
    for (int y = 0; y < m->h; y++) {
        double cy = y + 0.5;
        uint32_t c = 0;
        for (uint32_t i = 0, j = n - 1; i < n; j = i++) {
            if ((p[i].y > cy) == (p[j].y > cy)) continue;
            xs[c++] = p[j].x + (cy - p[j].y) * (p[i].x - p[j].x) / (p[i].y - p[j].y);
        }
        qsort(xs, c, sizeof *xs, cmp_double);
        for (uint32_t k = 0; k + 1 < c; k += 2) {
            double lo = ceil(xs[k] - 0.5), hi = ceil(xs[k + 1] - 0.5) - 1; /* centres in [xs[k], xs[k+1]) */
            if (lo < 0) lo = 0;
            if (hi > m->w - 1) hi = m->w - 1;
            if (lo <= hi) fill_span(m, y, (int)lo, (int)hi, value);
        }
    }
}

tt_result tt_mask_fill_polygon(tt_mask *m, const tt_vec2 *points, uint32_t n, bool value)
{
    if (!m || !points) return tt__mask_fail(TT_EINVAL, "tt_mask_fill_polygon: %s is NULL", m ? "points" : "mask");
    if (n < 3 || n > 1000000) return tt__mask_fail(TT_EINVAL, "tt_mask_fill_polygon: %u points, expected 3…1000000", n);
    for (uint32_t i = 0; i < n; i++)
        if (bad_coord(points[i].x) || bad_coord(points[i].y))
            return tt__mask_fail(TT_EINVAL, "tt_mask_fill_polygon: point %u (%g, %g) not finite within 1e6", i,
                                 points[i].x, points[i].y);
    double *xs = malloc(n * sizeof *xs);
    if (!xs) return tt__mask_fail(TT_ENOMEM, "tt_mask_fill_polygon: out of memory");
    polygon_rows(m, points, n, xs, value);
    free(xs);
    return TT_OK;
}
