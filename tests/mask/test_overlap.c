/* Overlap, first point, area and overlap mask against a plain per-pixel
 * reference, on thousands of random pairs (sizes 1…200 and widths up to 513,
 * widths around the 64-bit word, offsets across word boundaries and wholly
 * outside); draw
 * and erase likewise; the push-out normal on known shapes. */
#include "test.h"
#include "tether.h"

#include <stdlib.h>
#include <string.h>

/* xorshift64*: the same pairs on every machine */
static uint64_t rng = 0x9E3779B97F4A7C15u;
static uint32_t rnd(uint32_t n)
{
    rng ^= rng >> 12;
    rng ^= rng << 25;
    rng ^= rng >> 27;
    return (uint32_t)((rng * 0x2545F4914F6CDD1Du) >> 33) % n;
}

/* A mask and its plain copy, one byte per pixel, at density per 1000. */
typedef struct pair_mask {
    tt_mask *m;
    unsigned char *px;
    int w, h;
} pair_mask;

static int pick_side(void)
{
    static const int special[] = { 1, 2, 63, 64, 65, 127, 128, 129, 200 };
    return rnd(3) == 0 ? special[rnd(9)] : 1 + (int)rnd(rnd(4) == 0 ? 200 : 80);
}

static pair_mask make(void)
{
    pair_mask p;
    /* wide ones too: rows of five words and more take the four-words-at-a-time loop */
    p.w = rnd(6) == 0 ? (int[]){ 256, 257, 319, 320, 321, 513 }[rnd(6)] : pick_side();
    p.h = pick_side();
    p.m = tt_mask_create(p.w, p.h, false);
    p.px = calloc((size_t)p.w * p.h, 1);
    uint32_t density = (uint32_t[]){ 2, 30, 500, 970, 1000 }[rnd(5)];
    for (int y = 0; y < p.h; y++)
        for (int x = 0; x < p.w; x++)
            if (rnd(1000) < density) {
                p.px[y * p.w + x] = 1;
                tt_mask_set(p.m, x, y, true);
            }
    return p;
}

static void drop(pair_mask *p)
{
    tt_mask_destroy(p->m);
    free(p->px);
}

static int ref_at(const pair_mask *p, int x, int y)
{
    return x >= 0 && y >= 0 && x < p->w && y < p->h && p->px[y * p->w + x];
}

/* An offset: near the word boundaries of A, around its edges, or far outside. */
static int pick_offset(int wa, int wb)
{
    switch (rnd(5)) {
    case 0: return (int)rnd(5) * 64 - 128 + (int)rnd(3) - 1;
    case 1: return wa - 1 + (int)rnd(3) - 1;          /* B's left column on A's last, or just past it */
    case 2: return -wb + (int)rnd(3);                 /* B's right column on A's first, or just before it */
    case 3: return rnd(2) ? 1000000 + (int)rnd(100) : -1000000 - (int)rnd(100);
    default: return (int)rnd((uint32_t)(wa + wb + 1)) - wb;
    }
}

TEST(mask_overlap_matches_per_pixel_reference)
{
    for (int it = 0; it < 3000; it++) {
        pair_mask a = make(), b = make();
        int dx = pick_offset(a.w, b.w), dy = pick_offset(a.h, b.h);
        int64_t area = 0;
        int fx = -1, fy = -1;
        tt_mask *om = tt_mask_overlap_mask(a.m, b.m, dx, dy);
        ENSURE(om != NULL);
        bool same = true;
        for (int y = 0; y < a.h; y++)
            for (int x = 0; x < a.w; x++) {
                int v = ref_at(&a, x, y) && ref_at(&b, x - dx, y - dy);
                if (v && fy < 0) { fx = x; fy = y; }
                area += v;
                if (tt_mask_get(om, x, y) != v) same = false;
            }
        int x = -7, y = -7;
        bool hit = tt_mask_overlap(a.m, b.m, dx, dy, &x, &y);
        int64_t got = tt_mask_overlap_area(a.m, b.m, dx, dy);
        if (!same || hit != (fy >= 0) || (hit && (x != fx || y != fy)) || got != area || tt_mask_count(om) != area)
            tt_test_fail(__FILE__, __LINE__, "pair %d: A %dx%d, B %dx%d at (%d, %d): hit %d (%d, %d) area %lld mask %s;"
                         " reference %d (%d, %d) area %lld", it, a.w, a.h, b.w, b.h, dx, dy, hit, x, y, (long long)got,
                         same ? "same" : "differs", fy >= 0, fx, fy, (long long)area);
        tt_mask_destroy(om);
        drop(&a);
        drop(&b);
        if (!same || got != area) return;
    }
}

TEST(mask_draw_and_erase_match_per_pixel_reference)
{
    for (int it = 0; it < 600; it++) {
        pair_mask a = make(), b = make();
        int dx = pick_offset(a.w, b.w), dy = pick_offset(a.h, b.h);
        bool erase = rnd(2);
        ENSURE_OK(erase ? tt_mask_erase(a.m, b.m, dx, dy) : tt_mask_draw(a.m, b.m, dx, dy));
        for (int y = 0; y < a.h; y++)
            for (int x = 0; x < a.w; x++) {
                int in = ref_at(&b, x - dx, y - dy), v = erase ? ref_at(&a, x, y) && !in : ref_at(&a, x, y) || in;
                if (tt_mask_get(a.m, x, y) != v) {
                    tt_test_fail(__FILE__, __LINE__, "pair %d %s: pixel (%d, %d) is %d, reference %d", it,
                                 erase ? "erase" : "draw", x, y, tt_mask_get(a.m, x, y), v);
                    return;
                }
            }
        /* the bits past the width stay clear: invert must count only real pixels */
        int64_t n = tt_mask_count(a.m);
        ENSURE_OK(tt_mask_invert(a.m));
        ENSURE(tt_mask_count(a.m) == (int64_t)a.w * a.h - n);
        drop(&a);
        drop(&b);
    }
}

TEST(mask_draw_onto_itself)
{
    tt_mask *m = tt_mask_create(130, 5, false);
    ENSURE_OK(tt_mask_set(m, 0, 0, true));
    ENSURE_OK(tt_mask_set(m, 64, 1, true));
    ENSURE_OK(tt_mask_draw(m, m, 1, 1)); /* each row is read before it is written */
    ENSURE(tt_mask_count(m) == 4);
    ENSURE(tt_mask_get(m, 1, 1) == 1 && tt_mask_get(m, 65, 2) == 1 && tt_mask_get(m, 2, 2) == 0);
    tt_mask_destroy(m);
}

TEST(mask_overlap_normal_points_out_of_a)
{
    /* a floor (bottom half of A) and a small square B sinking into it from above */
    tt_mask *a = tt_mask_create(40, 40, false), *b = tt_mask_create(8, 8, true);
    ENSURE_OK(tt_mask_fill_rect(a, 0, 20, 40, 20, true));
    tt_vec2 n;
    ENSURE_OK(tt_mask_overlap_normal(a, b, 10, 15, &n));
    ENSURE_NEAR(n.x, 0, 1e-12);
    ENSURE_NEAR(n.y, -1, 1e-12); /* up in the image: y down */
    ENSURE_OK(tt_mask_fill_rect(a, 0, 0, 40, 40, false));
    ENSURE_OK(tt_mask_fill_rect(a, 0, 0, 10, 40, true)); /* a wall on the left */
    ENSURE_OK(tt_mask_overlap_normal(a, b, 5, 10, &n));
    ENSURE_NEAR(n.x, 1, 1e-12);
    ENSURE_NEAR(n.y, 0, 1e-12);
    ENSURE_OK(tt_mask_overlap_normal(a, b, 30, 10, &n)); /* apart: no push */
    ENSURE(n.x == 0 && n.y == 0);
    tt_mask_destroy(a);
    tt_mask_destroy(b);
}

TEST(mask_overlap_refuses_bad_arguments)
{
    tt_mask *a = tt_mask_create(10, 10, true);
    int x = 5, y = 6;
    ENSURE(!tt_mask_overlap(NULL, a, 0, 0, &x, &y) && x == 5 && y == 6);
    ENSURE(strstr(tt_mask_last_error(), "tt_mask_overlap") != NULL);
    ENSURE(tt_mask_overlap_area(a, NULL, 0, 0) == -1);
    ENSURE(tt_mask_overlap_area(a, a, TT_MASK_MAX_OFFSET + 1, 0) == -1);
    ENSURE(tt_mask_overlap_area(a, a, -TT_MASK_MAX_OFFSET, TT_MASK_MAX_OFFSET) == 0);
    ENSURE(tt_mask_overlap_mask(a, a, 0, -TT_MASK_MAX_OFFSET - 1) == NULL);
    ENSURE(tt_mask_overlap_normal(a, a, 0, 0, NULL) == TT_EINVAL);
    ENSURE(tt_mask_draw(a, NULL, 0, 0) == TT_EINVAL);
    ENSURE(tt_mask_erase(NULL, a, 0, 0) == TT_EINVAL);
    ENSURE(tt_mask_overlap_area(a, a, 3, 4) == 42);
    tt_mask_destroy(a);
}

TEST(mask_convolve_matches_overlap_at_every_offset)
{
    int done = 0;
    for (int it = 0; it < 300; it++) {
        pair_mask a = make(), b = make();
        if (a.w > 80 || a.h > 80 || b.w > 80 || b.h > 80) { drop(&a); drop(&b); continue; }
        tt_mask *c = tt_mask_convolve(a.m, b.m);
        ENSURE(c != NULL);
        for (int y = 0; y < a.h + b.h - 1; y++)
            for (int x = 0; x < a.w + b.w - 1; x++)
                if (tt_mask_get(c, x, y) != (int)tt_mask_overlap(a.m, b.m, x - b.w + 1, y - b.h + 1, NULL, NULL)) {
                    tt_test_fail(__FILE__, __LINE__, "pair %d: pixel (%d, %d) differs", it, x, y);
                    return;
                }
        tt_mask_destroy(c);
        drop(&a);
        drop(&b);
        done++;
    }
    ENSURE(done > 20);
    tt_mask *big = tt_mask_create(8192, 8192, true), *small = tt_mask_create(40, 40, true);
    ENSURE(tt_mask_convolve(small, big) == NULL); /* 67 M pixels of B, each 40 rows of A: refused */
    ENSURE(strstr(tt_mask_last_error(), "word operations") != NULL);
    tt_mask_destroy(big);
    tt_mask_destroy(small);
}
