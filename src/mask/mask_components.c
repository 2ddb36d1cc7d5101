/* tether — connected components (8-connected, as pygame's), pygame's
 * border-pixel outline, and convolve ("where does this sprite fit"). */
#include "mask_internal.h"

#include <stdlib.h>

/* Labels every set pixel with its component's number (1, 2, … in the order
 * of their first pixel, row by row); clear pixels get 0. Flood fill with an
 * explicit stack: a large component would recurse as deep as it is big.
 * Returns the number of components, or −1 when memory runs out. */
static int64_t label(const tt_mask *m, uint32_t *lab)
{
    size_t cap = 1024, top = 0;
    uint32_t *st = malloc(cap * 2 * sizeof *st), next = 0;
    if (!st) return -1;
    for (int y = 0; y < m->h; y++)
        for (int x = 0; x < m->w; x++) {
            if (!tt__mask_bit(m, x, y) || lab[(size_t)y * m->w + x]) continue;
            lab[(size_t)y * m->w + x] = ++next;
            st[0] = (uint32_t)x;
            st[1] = (uint32_t)y;
            top = 1;
            while (top) {
                top--;
                int cx = (int)st[2 * top], cy = (int)st[2 * top + 1];
                for (int ny = cy - 1; ny <= cy + 1; ny++)
                    for (int nx = cx - 1; nx <= cx + 1; nx++) {
                        if (nx < 0 || ny < 0 || nx >= m->w || ny >= m->h) continue;
                        size_t i = (size_t)ny * m->w + nx;
                        if (lab[i] || !tt__mask_bit(m, nx, ny)) continue;
                        lab[i] = next;
                        if (top == cap) {
                            uint32_t *s2 = realloc(st, cap * 4 * sizeof *st);
                            if (!s2) { free(st); return -1; }
                            st = s2;
                            cap *= 2;
                        }
                        st[2 * top] = (uint32_t)nx;
                        st[2 * top + 1] = (uint32_t)ny;
                        top++;
                    }
            }
        }
    free(st);
    return next;
}

/* The labels of m (free them), or NULL with a message. */
static uint32_t *labels_of(const char *fn, const tt_mask *m, int64_t *n)
{
    uint32_t *lab = calloc((size_t)m->w * (size_t)m->h, sizeof *lab);
    if (lab && (*n = label(m, lab)) >= 0) return lab;
    free(lab);
    tt__mask_fail(TT_ENOMEM, "%s: out of memory", fn);
    return NULL;
}

int64_t tt_mask_component_count(const tt_mask *m)
{
    int64_t n = -1;
    if (tt__mask_check("tt_mask_component_count", "mask", m) != TT_OK) return -1;
    free(labels_of("tt_mask_component_count", m, &n));
    return n;
}

/* The label with the most pixels (the lowest among equals), 0 when none. */
static uint32_t largest(const uint32_t *lab, size_t npx, int64_t n)
{
    int64_t *size = calloc((size_t)n + 1, sizeof *size);
    uint32_t best = 0;
    if (!size) return 0;
    for (size_t i = 0; i < npx; i++) size[lab[i]]++;
    for (int64_t k = 1; k <= n; k++)
        if (!best || size[k] > size[best]) best = (uint32_t)k;
    free(size);
    return best;
}

tt_mask *tt_mask_component(const tt_mask *m, int x, int y)
{
    const char *fn = "tt_mask_component";
    if (tt__mask_check(fn, "mask", m) != TT_OK) return NULL;
    bool pick_largest = x == -1 && y == -1;
    if (!pick_largest && (x < 0 || y < 0 || x >= m->w || y >= m->h)) {
        tt__mask_fail(TT_EINVAL, "%s: pixel (%d, %d) outside the %d x %d mask (−1, −1: the largest)", fn, x, y, m->w, m->h);
        return NULL;
    }
    int64_t n;
    uint32_t *lab = labels_of(fn, m, &n);
    tt_mask *out = lab ? tt__mask_alloc(fn, m->w, m->h) : NULL;
    if (out) {
        size_t npx = (size_t)m->w * (size_t)m->h;
        uint32_t want = pick_largest ? largest(lab, npx, n) : lab[(size_t)y * m->w + x];
        for (size_t i = 0; want && i < npx; i++)
            if (lab[i] == want) tt__mask_put(out, (int)(i % (size_t)m->w), (int)(i / (size_t)m->w), true);
    }
    free(lab);
    return out;
}

tt_result tt_mask_component_rects(const tt_mask *m, tt_mask_rect *out, uint32_t cap, uint32_t *count)
{
    const char *fn = "tt_mask_component_rects";
    if (!m || !count || (!out && cap)) return tt__mask_fail(TT_EINVAL, "%s: %s is NULL", fn, !m ? "mask" : !count ? "count" : "out");
    int64_t n;
    uint32_t *lab = labels_of(fn, m, &n);
    if (!lab) return TT_ENOMEM;
    *count = (uint32_t)n;
    for (uint32_t k = 0; k < cap && k < (uint32_t)n; k++) out[k] = (tt_mask_rect){ m->w, m->h, -1, -1 };
    for (int y = 0; y < m->h; y++)
        for (int x = 0; x < m->w; x++) {
            uint32_t l = lab[(size_t)y * m->w + x];
            if (!l || l > cap) continue;
            tt_mask_rect *r = &out[l - 1]; /* w, h hold the right and bottom pixel until the end */
            if (x < r->x) r->x = x;
            if (y < r->y) r->y = y;
            if (x > r->w) r->w = x;
            if (y > r->h) r->h = y;
        }
    for (uint32_t k = 0; k < cap && k < (uint32_t)n; k++) {
        out[k].w = out[k].w - out[k].x + 1;
        out[k].h = out[k].h - out[k].y + 1;
    }
    free(lab);
    return TT_OK;
}

/* The 8 neighbours clockwise on screen from the east. */
static const int NX[8] = { 1, 1, 0, -1, -1, -1, 0, 1 }, NY[8] = { 0, 1, 1, 1, 0, -1, -1, -1 };

static int at(const tt_mask *m, int x, int y)
{
    return x >= 0 && y >= 0 && x < m->w && y < m->h && tt__mask_bit(m, x, y);
}

/* From pixel (x, y), entered coming from direction back, the next border
 * pixel clockwise: returns its direction, or −1 for a lone pixel. */
static int next_dir(const tt_mask *m, int x, int y, int back)
{
    for (int i = 1; i <= 8; i++) {
        int d = (back + i) & 7;
        if (at(m, x + NX[d], y + NY[d])) return d;
    }
    return -1;
}

tt_result tt_mask_outline(const tt_mask *m, int *xy, uint32_t cap, uint32_t *count)
{
    if (!m || !count || (!xy && cap))
        return tt__mask_fail(TT_EINVAL, "tt_mask_outline: %s is NULL", !m ? "mask" : !count ? "count" : "xy");
    *count = 0;
    int sx = -1, sy = -1;
    for (int y = 0; y < m->h && sx < 0; y++)
        for (int x = 0; x < m->w; x++)
            if (tt__mask_bit(m, x, y)) { sx = x; sy = y; break; }
    if (sx < 0) return TT_OK;
    /* Moore-neighbour tracing: the first pixel's upper and left neighbours are
     * clear, so the search starts from the west; the walk ends when it would
     * leave the first pixel the way it first left it. */
    int x = sx, y = sy, d = next_dir(m, x, y, 4), d0 = d;
    uint64_t n = 0, limit = 4 * (uint64_t)m->w * (uint64_t)m->h + 8;
    do {
        if (n < cap) { xy[2 * n] = x; xy[2 * n + 1] = y; }
        n++;
        if (d < 0) break;
        x += NX[d];
        y += NY[d];
        d = next_dir(m, x, y, (d + 4) & 7); /* sweep clockwise from the pixel we came from */
    } while (!(x == sx && y == sy && d == d0) && n < limit);
    *count = (uint32_t)n;
    return TT_OK;
}

/* A dilation: every set pixel (bx, by) of B puts a copy of A at
 * (wb − 1 − bx, hb − 1 − by), a word at a time. Its cost is count(B) rows
 * of A, hence the documented limit. */
tt_mask *tt_mask_convolve(const tt_mask *a, const tt_mask *b)
{
    const char *fn = "tt_mask_convolve";
    if (tt__mask_check(fn, "a", a) != TT_OK || tt__mask_check(fn, "b", b) != TT_OK) return NULL;
    int w = a->w + b->w - 1, h = a->h + b->h - 1;
    if (tt__mask_check_size(fn, w, h) != TT_OK) return NULL;
    double work = (double)tt_mask_count(b) * a->h * (a->stride + 1);
    if (work > TT_MASK_MAX_CONVOLVE) {
        tt__mask_fail(TT_EINVAL, "%s: %.3g word operations (set pixels of b × rows × words of a), more than %g", fn,
                      work, (double)TT_MASK_MAX_CONVOLVE);
        return NULL;
    }
    tt_mask *out = tt__mask_alloc(fn, w, h);
    if (!out) return NULL;
    for (int by = 0; by < b->h; by++)
        for (int k = 0; k < b->stride; k++)
            for (uint64_t bits = tt__mask_row(b, by)[k]; bits; bits &= bits - 1) {
                int bx = k * 64 + __builtin_ctzll(bits);
                tt_mask_draw(out, a, b->w - 1 - bx, b->h - 1 - by);
            }
    tt__mask_ok();
    return out;
}
