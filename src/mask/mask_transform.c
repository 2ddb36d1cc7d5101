/* tether — rotated and scaled copies of a mask (nearest pixel), so that a
 * turning or growing sprite can be tested pixel by pixel. */
#include "mask_internal.h"

#include <math.h>

tt_mask *tt_mask_scaled(const tt_mask *m, int w, int h)
{
    const char *fn = "tt_mask_scaled";
    if (tt__mask_check(fn, "mask", m) != TT_OK || tt__mask_check_size(fn, w, h) != TT_OK) return NULL;
    tt_mask *out = tt__mask_alloc(fn, w, h);
    if (!out) return NULL;
    for (int y = 0; y < h; y++) {
        int sy = (int)(((int64_t)y * m->h) / h); /* the source pixel whose span holds this centre's row */
        for (int x = 0; x < w; x++)
            if (tt__mask_bit(m, (int)(((int64_t)x * m->w) / w), sy)) tt__mask_put(out, x, y, true);
    }
    return out;
}

/* Rounded to a multiple of 2^-20 so that the sine and cosine of the same
 * angle give the same box and pixels on every libm worth the name. */
static double snap(double v)
{
    return nearbyint(v * 1048576.0) / 1048576.0;
}

tt_mask *tt_mask_rotated(const tt_mask *m, double angle)
{
    const char *fn = "tt_mask_rotated";
    if (tt__mask_check(fn, "mask", m) != TT_OK) return NULL;
    if (!(fabs(angle) <= 1e6)) {
        tt__mask_fail(TT_EINVAL, "%s: angle %g not finite within 1e6 rad", fn, angle);
        return NULL;
    }
    double c = snap(cos(angle)), s = snap(sin(angle));
    /* on screen y goes down: counter-clockwise as seen is (x, y) → (x c + y s, −x s + y c) */
    double hw = m->w / 2.0, hh = m->h / 2.0;
    double ew = fabs(c) * hw + fabs(s) * hh, eh = fabs(s) * hw + fabs(c) * hh;
    int w = (int)ceil(2 * ew - 1e-9), h = (int)ceil(2 * eh - 1e-9);
    if (w < 1) w = 1;
    if (h < 1) h = 1;
    if (tt__mask_check_size(fn, w, h) != TT_OK) return NULL;
    tt_mask *out = tt__mask_alloc(fn, w, h);
    if (!out) return NULL;
    for (int y = 0; y < h; y++) {
        double py = y + 0.5 - h / 2.0;
        for (int x = 0; x < w; x++) {
            double px = x + 0.5 - w / 2.0;
            /* the inverse turn takes this pixel's centre back into m */
            double sx = px * c - py * s + hw, sy = px * s + py * c + hh;
            if (sx < 0 || sy < 0 || sx >= m->w || sy >= m->h) continue;
            if (tt__mask_bit(m, (int)sx, (int)sy)) tt__mask_put(out, x, y, true);
        }
    }
    return out;
}
