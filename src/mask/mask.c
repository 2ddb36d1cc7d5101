/* tether — masks: making, copying, freeing, single pixels, whole-mask
 * operations (count, clear, fill, invert, bounding rect, centroid), and the
 * error message every mask call leaves. */
#include "mask_internal.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* One message per thread: masks have no owner object (unlike a world) to
 * keep it in, and two threads each working on their own masks must not
 * read each other's reasons. */
static _Thread_local char last_error[256];

const char *tt_mask_last_error(void)
{
    return last_error;
}

tt_result tt__mask_fail(tt_result code, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(last_error, sizeof last_error, fmt, ap);
    va_end(ap);
    return code;
}

void tt__mask_ok(void)
{
    last_error[0] = '\0';
}

tt_result tt__mask_check_size(const char *fn, int w, int h)
{
    if (w < 1 || h < 1 || w > TT_MASK_MAX_SIDE || h > TT_MASK_MAX_SIDE)
        return tt__mask_fail(TT_EINVAL, "%s: size %d x %d outside 1…%d", fn, w, h, TT_MASK_MAX_SIDE);
    return TT_OK;
}

tt_result tt__mask_check(const char *fn, const char *name, const tt_mask *m)
{
    if (!m) return tt__mask_fail(TT_EINVAL, "%s: %s is NULL", fn, name);
    return TT_OK;
}

tt_result tt__mask_check_offset(const char *fn, int dx, int dy)
{
    if (dx < -TT_MASK_MAX_OFFSET || dx > TT_MASK_MAX_OFFSET || dy < -TT_MASK_MAX_OFFSET || dy > TT_MASK_MAX_OFFSET)
        return tt__mask_fail(TT_EINVAL, "%s: offset (%d, %d) beyond ±%d", fn, dx, dy, TT_MASK_MAX_OFFSET);
    return TT_OK;
}

/* The struct and its bits in one block: one allocation per mask, which is
 * what a mask made per call (an overlap mask) costs. Sizes are checked by
 * the callers (≤ TT_MASK_MAX_SIDE), so nothing here overflows. */
#define HEAD ((sizeof(tt_mask) + 63) / 64 * 64)

static size_t block_size(int w, int h)
{
    return HEAD + (size_t)((w + 63) >> 6) * (size_t)h * sizeof(uint64_t);
}

static tt_mask *lay_out(unsigned char *block, int w, int h)
{
    tt_mask *m = (tt_mask *)block;
    m->w = w;
    m->h = h;
    m->stride = (w + 63) >> 6;
    m->bits = (uint64_t *)(block + HEAD);
    return m;
}

static tt_mask *alloc_block(const char *fn, int w, int h, bool zero)
{
    unsigned char *block = zero ? calloc(1, block_size(w, h)) : malloc(block_size(w, h));
    if (!block) {
        tt__mask_fail(TT_ENOMEM, "%s: out of memory for a %d x %d mask", fn, w, h);
        return NULL;
    }
    tt__mask_ok();
    return lay_out(block, w, h);
}

size_t tt_mask_footprint(int w, int h)
{
    if (tt__mask_check_size("tt_mask_footprint", w, h) != TT_OK) return 0;
    return block_size(w, h);
}

tt_mask *tt_mask_init(void *mem, size_t size, int w, int h)
{
    const char *fn = "tt_mask_init";
    if (tt__mask_check_size(fn, w, h) != TT_OK) return NULL;
    if (!mem || size < block_size(w, h) || ((uintptr_t)mem & 7u)) {
        tt__mask_fail(TT_EINVAL, "%s: %s", fn, !mem ? "mem is NULL" : size < block_size(w, h) ? "size below tt_mask_footprint" : "mem not aligned to 8 bytes");
        return NULL;
    }
    tt_mask *m = lay_out(mem, w, h);
    memset(m->bits, 0, block_size(w, h) - HEAD);
    tt__mask_ok();
    return m;
}

tt_result tt_mask_copy_into(tt_mask *dst, const tt_mask *src)
{
    if (!dst || !src) return tt__mask_fail(TT_EINVAL, "tt_mask_copy_into: %s is NULL", dst ? "src" : "dst");
    if (dst->w != src->w || dst->h != src->h)
        return tt__mask_fail(TT_EINVAL, "tt_mask_copy_into: sizes differ (%d x %d, %d x %d)", dst->w, dst->h, src->w, src->h);
    if (dst != src) memcpy(dst->bits, src->bits, (size_t)src->stride * (size_t)src->h * sizeof *src->bits);
    return TT_OK;
}

tt_mask *tt__mask_alloc(const char *fn, int w, int h)
{
    return alloc_block(fn, w, h, true);
}

tt_mask *tt__mask_alloc_raw(const char *fn, int w, int h)
{
    return alloc_block(fn, w, h, false);
}

void tt__mask_clear_tail(tt_mask *m)
{
    if ((m->w & 63) == 0) return;
    uint64_t keep = ((uint64_t)1 << (m->w & 63)) - 1;
    for (int y = 0; y < m->h; y++) tt__mask_row(m, y)[m->stride - 1] &= keep;
}

tt_mask *tt_mask_create(int w, int h, bool filled)
{
    if (tt__mask_check_size("tt_mask_create", w, h) != TT_OK) return NULL;
    tt_mask *m = tt__mask_alloc("tt_mask_create", w, h);
    if (m && filled) tt_mask_fill(m);
    return m;
}

void tt_mask_destroy(tt_mask *m)
{
    free(m); /* the bits are in the same block */
}

tt_mask *tt_mask_copy(const tt_mask *m)
{
    if (tt__mask_check("tt_mask_copy", "mask", m) != TT_OK) return NULL;
    tt_mask *c = tt__mask_alloc("tt_mask_copy", m->w, m->h);
    if (c) memcpy(c->bits, m->bits, (size_t)m->stride * (size_t)m->h * sizeof *m->bits);
    return c;
}

tt_result tt_mask_size(const tt_mask *m, int *w, int *h)
{
    if (!m) return tt__mask_fail(TT_EINVAL, "tt_mask_size: mask is NULL");
    if (w) *w = m->w;
    if (h) *h = m->h;
    return TT_OK;
}

/* Checks m and that (x, y) is inside it. */
static tt_result check_pixel(const char *fn, const tt_mask *m, int x, int y)
{
    if (!m) return tt__mask_fail(TT_EINVAL, "%s: mask is NULL", fn);
    if (x < 0 || y < 0 || x >= m->w || y >= m->h)
        return tt__mask_fail(TT_EINVAL, "%s: pixel (%d, %d) outside the %d x %d mask", fn, x, y, m->w, m->h);
    return TT_OK;
}

int tt_mask_get(const tt_mask *m, int x, int y)
{
    if (check_pixel("tt_mask_get", m, x, y) != TT_OK) return -1;
    return tt__mask_bit(m, x, y);
}

tt_result tt_mask_set(tt_mask *m, int x, int y, bool value)
{
    tt_result r = check_pixel("tt_mask_set", m, x, y);
    if (r == TT_OK) tt__mask_put(m, x, y, value);
    return r;
}

int64_t tt_mask_count(const tt_mask *m)
{
    if (!m) return 0;
    int64_t n = 0;
    size_t words = (size_t)m->stride * (size_t)m->h;
    for (size_t i = 0; i < words; i++) n += __builtin_popcountll(m->bits[i]);
    return n;
}

tt_result tt_mask_clear(tt_mask *m)
{
    if (!m) return tt__mask_fail(TT_EINVAL, "tt_mask_clear: mask is NULL");
    memset(m->bits, 0, (size_t)m->stride * (size_t)m->h * sizeof *m->bits);
    return TT_OK;
}

tt_result tt_mask_fill(tt_mask *m)
{
    if (!m) return tt__mask_fail(TT_EINVAL, "tt_mask_fill: mask is NULL");
    memset(m->bits, 0xff, (size_t)m->stride * (size_t)m->h * sizeof *m->bits);
    tt__mask_clear_tail(m);
    return TT_OK;
}

tt_result tt_mask_invert(tt_mask *m)
{
    if (!m) return tt__mask_fail(TT_EINVAL, "tt_mask_invert: mask is NULL");
    size_t words = (size_t)m->stride * (size_t)m->h;
    for (size_t i = 0; i < words; i++) m->bits[i] = ~m->bits[i];
    tt__mask_clear_tail(m);
    return TT_OK;
}

tt_result tt_mask_bounding_rect(const tt_mask *m, tt_mask_rect *out)
{
    if (!m || !out) return tt__mask_fail(TT_EINVAL, "tt_mask_bounding_rect: %s is NULL", m ? "out" : "mask");
    int x0 = m->w, x1 = -1, y0 = m->h, y1 = -1;
    for (int y = 0; y < m->h; y++) {
        const uint64_t *row = tt__mask_row(m, y);
        for (int k = 0; k < m->stride; k++) {
            if (!row[k]) continue;
            int lo = k * 64 + __builtin_ctzll(row[k]), hi = k * 64 + 63 - __builtin_clzll(row[k]);
            if (lo < x0) x0 = lo;
            if (hi > x1) x1 = hi;
            if (y < y0) y0 = y;
            y1 = y;
        }
    }
    *out = x1 < 0 ? (tt_mask_rect){ 0, 0, 0, 0 } : (tt_mask_rect){ x0, y0, x1 - x0 + 1, y1 - y0 + 1 };
    return TT_OK;
}

tt_result tt_mask_centroid(const tt_mask *m, tt_vec2 *out)
{
    if (!m || !out) return tt__mask_fail(TT_EINVAL, "tt_mask_centroid: %s is NULL", m ? "out" : "mask");
    int64_t n = 0, sx = 0, sy = 0;
    for (int y = 0; y < m->h; y++) {
        const uint64_t *row = tt__mask_row(m, y);
        for (int k = 0; k < m->stride; k++) {
            for (uint64_t b = row[k]; b; b &= b - 1) sx += k * 64 + __builtin_ctzll(b);
            int c = __builtin_popcountll(row[k]);
            n += c;
            sy += (int64_t)c * y;
        }
    }
    *out = n ? (tt_vec2){ (double)sx / (double)n, (double)sy / (double)n } : (tt_vec2){ 0, 0 };
    return TT_OK;
}
