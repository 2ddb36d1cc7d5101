/* tether — masks of RGBA images: by alpha threshold or by colour. */
#include "mask_internal.h"

static tt_result check_rgba(const char *fn, const uint8_t *rgba, int w, int h, size_t stride)
{
    if (!rgba) return tt__mask_fail(TT_EINVAL, "%s: pixels are NULL", fn);
    tt_result r = tt__mask_check_size(fn, w, h);
    if (r != TT_OK) return r;
    if (stride < (size_t)w * 4) return tt__mask_fail(TT_EINVAL, "%s: stride %zu below 4·width = %d", fn, stride, 4 * w);
    return TT_OK;
}

tt_mask *tt_mask_from_rgba(const uint8_t *rgba, int w, int h, size_t stride, int threshold)
{
    const char *fn = "tt_mask_from_rgba";
    if (check_rgba(fn, rgba, w, h, stride) != TT_OK) return NULL;
    if (threshold < 0 || threshold > 254) {
        tt__mask_fail(TT_EINVAL, "%s: threshold %d outside 0…254", fn, threshold);
        return NULL;
    }
    tt_mask *m = tt__mask_alloc(fn, w, h);
    if (!m) return NULL;
    for (int y = 0; y < h; y++) {
        const uint8_t *p = rgba + (size_t)y * stride;
        uint64_t *row = tt__mask_row(m, y);
        for (int x = 0; x < w; x++)
            if (p[4 * x + 3] > threshold) row[x >> 6] |= (uint64_t)1 << (x & 63);
    }
    return m;
}

static int absdiff(int a, int b)
{
    return a > b ? a - b : b - a;
}

tt_mask *tt_mask_from_color(const uint8_t *rgba, int w, int h, size_t stride, const uint8_t key[3], int tolerance,
                            bool invert)
{
    const char *fn = "tt_mask_from_color";
    if (check_rgba(fn, rgba, w, h, stride) != TT_OK) return NULL;
    if (!key || tolerance < 0 || tolerance > 255) {
        tt__mask_fail(TT_EINVAL, key ? "%s: tolerance %d outside 0…255" : "%s: key is NULL", fn, tolerance);
        return NULL;
    }
    tt_mask *m = tt__mask_alloc(fn, w, h);
    if (!m) return NULL;
    for (int y = 0; y < h; y++) {
        const uint8_t *p = rgba + (size_t)y * stride;
        for (int x = 0; x < w; x++, p += 4) {
            bool match = absdiff(p[0], key[0]) <= tolerance && absdiff(p[1], key[1]) <= tolerance &&
                         absdiff(p[2], key[2]) <= tolerance;
            if (match != invert) tt__mask_put(m, x, y, true);
        }
    }
    return m;
}
