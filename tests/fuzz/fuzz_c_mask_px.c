/* tests/fuzz/fuzz_c_mask_px.c — wrappers of tether/mask.h, second part:
 * pixels (get, set, count, clear, fill, invert, rects, circles, polygons,
 * draw and erase, a mask onto itself included) and the overlaps of two
 * masks at every sort of offset. A refused call leaves its masks as they
 * were; known answers: a mask overlaps itself at (0, 0) by its count, the
 * overlap mask counts the overlap area, a rect filled inside the mask adds
 * exactly its clear pixels, clear counts 0, fill w·h, invert w·h − n and a
 * second invert gives the mask back. */
#include "fuzz_c.h"

#include <math.h>
#include <stdlib.h>

static void unchanged(fz *f, const tt_mask *m, uint64_t before, const char *what)
{
    if (m && fz_mask_sig(m) != before) fz_fail(f, "%s changed its mask's pixels", what);
}

static bool inside(const tt_mask *m, int x, int y)
{
    return m && x >= 0 && y >= 0 && x < fz_mask_w(m) && y < fz_mask_h(m);
}

static void c_mask_size(fz *f)
{
    int s;
    tt_mask *m = fz_mask_pick(f, &s);
    bool nw = fz_chance(f, 20), nh = fz_chance(f, 20);
    int w = -7, h = -7;
    fz_log(f, "tt_mask_size(%s, %s, %s)", fz_mn(s), nw ? "NULL" : "&w", nh ? "NULL" : "&h");
    FZ_HIT(f, tt_mask_size);
    tt_result r = tt_mask_size(m, nw ? NULL : &w, nh ? NULL : &h);
    fz_mres(f, r);
    if (r == TT_OK && ((!nw && (w < 1 || w > TT_MASK_MAX_SIDE)) || (!nh && (h < 1 || h > TT_MASK_MAX_SIDE))))
        fz_fail(f, "tt_mask_size gave %d x %d", w, h);
}

static void c_mask_get(fz *f)
{
    int s;
    tt_mask *m = fz_mask_pick(f, &s);
    int x = fz_mask_coord(f, fz_mask_w(m)), y = fz_mask_coord(f, fz_mask_h(m));
    if (!inside(m, x, y)) {
        f->must_fail = true;
        f->why_must = "a pixel outside";
    }
    fz_log(f, "tt_mask_get(%s, %d, %d)", fz_mn(s), x, y);
    FZ_HIT(f, tt_mask_get);
    int v = tt_mask_get(m, x, y);
    fz_log_more(f, " -> %d", v);
    if (v < -1 || v > 1) fz_fail(f, "tt_mask_get returned %d", v);
    f->failed = v < 0;
}

static void c_mask_set(fz *f)
{
    int s;
    tt_mask *m = fz_mask_pick(f, &s);
    int x = fz_mask_coord(f, fz_mask_w(m)), y = fz_mask_coord(f, fz_mask_h(m));
    bool v = fz_chance(f, 60);
    if (!inside(m, x, y)) {
        f->must_fail = true;
        f->why_must = "a pixel outside";
    }
    uint64_t before = fz_mask_sig(m);
    int64_t n = tt_mask_count(m);
    fz_log(f, "tt_mask_set(%s, %d, %d, %d)", fz_mn(s), x, y, v);
    FZ_HIT(f, tt_mask_set);
    tt_result r = tt_mask_set(m, x, y, v);
    fz_mres(f, r);
    if (r != TT_OK) unchanged(f, m, before, "a refused tt_mask_set");
    else if (tt_mask_get(m, x, y) != v || llabs(tt_mask_count(m) - n) > 1)
        fz_fail(f, "tt_mask_set did not set the one pixel");
}

static void c_mask_count(fz *f)
{
    int s;
    tt_mask *m = fz_mask_pick(f, &s);
    fz_log(f, "tt_mask_count(%s)", fz_mn(s));
    FZ_HIT(f, tt_mask_count);
    int64_t n = tt_mask_count(m);
    fz_log_more(f, " -> %lld", (long long)n);
    if (m ? n < 0 || n > (int64_t)fz_mask_w(m) * fz_mask_h(m) : n != 0) fz_fail(f, "tt_mask_count is %lld", (long long)n);
    f->failed = !m;
}

/* clear, fill and invert: what each must leave, and invert twice is the original. */
static void whole(fz *f, int which)
{
    static const char *names[] = { "tt_mask_clear", "tt_mask_fill", "tt_mask_invert" };
    int s;
    tt_mask *m = fz_mask_pick(f, &s);
    const int64_t area = (int64_t)fz_mask_w(m) * fz_mask_h(m), n = tt_mask_count(m);
    const uint64_t before = fz_mask_sig(m);
    const bool twice = which == 2 && fz_chance(f, 30);
    fz_log(f, "%s(%s)%s", names[which], fz_mn(s), twice ? " twice" : "");
    tt_result r = which == 0 ? tt_mask_clear(m) : which == 1 ? tt_mask_fill(m) : tt_mask_invert(m);
    fz_mres(f, r);
    if (r != TT_OK) return;
    const int64_t want = which == 0 ? 0 : which == 1 ? area : area - n;
    if (tt_mask_count(m) != want)
        fz_fail(f, "%s left a count of %lld, not %lld", names[which], (long long)tt_mask_count(m), (long long)want);
    if (twice && (tt_mask_invert(m) != TT_OK || fz_mask_sig(m) != before))
        fz_fail(f, "a mask inverted twice is not the original");
}

static void c_mask_clear(fz *f)
{
    FZ_HIT(f, tt_mask_clear);
    whole(f, 0);
}

static void c_mask_fill(fz *f)
{
    FZ_HIT(f, tt_mask_fill);
    whole(f, 1);
}

static void c_mask_invert(fz *f)
{
    FZ_HIT(f, tt_mask_invert);
    whole(f, 2);
}

static void c_mask_bounding_rect(fz *f)
{
    int s;
    tt_mask *m = fz_mask_pick(f, &s);
    bool nout = fz_chance(f, 3);
    if (nout) f->must_fail = true, f->why_must = "a NULL out";
    tt_mask_rect rc = { -5, -5, -5, -5 };
    fz_log(f, "tt_mask_bounding_rect(%s, %s)", fz_mn(s), nout ? "NULL" : "&r");
    FZ_HIT(f, tt_mask_bounding_rect);
    tt_result r = tt_mask_bounding_rect(m, nout ? NULL : &rc);
    fz_mres(f, r);
    if (r != TT_OK) return;
    fz_log_more(f, " {%d, %d, %d, %d}", rc.x, rc.y, rc.w, rc.h);
    int64_t n = tt_mask_count(m);
    if (n == 0 ? rc.w != 0 || rc.h != 0
               : rc.w < 1 || rc.h < 1 || rc.x < 0 || rc.y < 0 || rc.x + rc.w > fz_mask_w(m) || rc.y + rc.h > fz_mask_h(m) ||
                     (int64_t)rc.w * rc.h < n)
        fz_fail(f, "the bounding rect does not hold the %lld set pixels", (long long)n);
}

static void c_mask_centroid(fz *f)
{
    int s;
    tt_mask *m = fz_mask_pick(f, &s);
    bool nout = fz_chance(f, 3);
    if (nout) f->must_fail = true, f->why_must = "a NULL out";
    tt_vec2 c = { -5, -5 };
    fz_log(f, "tt_mask_centroid(%s, %s)", fz_mn(s), nout ? "NULL" : "&c");
    FZ_HIT(f, tt_mask_centroid);
    tt_result r = tt_mask_centroid(m, nout ? NULL : &c);
    fz_mres(f, r);
    if (r != TT_OK) return;
    fz_log_more(f, " %s", fz_v(c));
    if (!(c.x >= 0 && c.y >= 0 && c.x <= fz_mask_w(m) - 1 && c.y <= fz_mask_h(m) - 1))
        fz_fail(f, "the centroid %s lies outside the mask", fz_v(c));
}

/* draw (0) and erase (1) of src on dst, dst itself now and then. */
static void paint(fz *f, int which)
{
    int sd, ss;
    tt_mask *dst = fz_mask_pick(f, &sd);
    tt_mask *src = fz_chance(f, 20) ? dst : fz_mask_pick(f, &ss);
    if (src == dst) ss = sd;
    int dx = fz_mask_offset(f, fz_mask_w(dst), fz_mask_w(src)), dy = fz_mask_offset(f, fz_mask_h(dst), fz_mask_h(src));
    if (src == dst && fz_chance(f, 30)) dx = dy = 0;
    const uint64_t bd = fz_mask_sig(dst), bs = src == dst ? bd : fz_mask_sig(src);
    const int64_t n = tt_mask_count(dst);
    fz_log(f, "%s(%s, %s, %d, %d)", which ? "tt_mask_erase" : "tt_mask_draw", fz_mn(sd), fz_mn(ss), dx, dy);
    tt_result r = which ? tt_mask_erase(dst, src, dx, dy) : tt_mask_draw(dst, src, dx, dy);
    fz_mres(f, r);
    if (r != TT_OK) {
        unchanged(f, dst, bd, "a refused draw or erase");
        return;
    }
    if (src != dst) unchanged(f, src, bs, "a draw or erase's source");
    const int64_t after = tt_mask_count(dst);
    if (which ? after > n : after < n) fz_fail(f, "the count went from %lld to %lld", (long long)n, (long long)after);
    if (src == dst && dx == 0 && dy == 0 && (which ? after != 0 : fz_mask_sig(dst) != bd))
        fz_fail(f, "a mask drawn or erased on itself at (0, 0) is wrong");
}

static void c_mask_draw(fz *f)
{
    FZ_HIT(f, tt_mask_draw);
    paint(f, 0);
}

static void c_mask_erase(fz *f)
{
    FZ_HIT(f, tt_mask_erase);
    paint(f, 1);
}

/* A length in pixels: plausible, or past the ±1e6 limit, or not a number. */
static double pix(fz *f, double lo, double hi)
{
    return fz_chance(f, 92) ? fz_real(f, lo, hi) : fz_nasty(f);
}

static void c_mask_fill_circle(fz *f)
{
    int s;
    tt_mask *m = fz_mask_pick(f, &s);
    double cx = pix(f, -10, fz_mask_w(m) + 10), cy = pix(f, -10, fz_mask_h(m) + 10), r = pix(f, 0, 40);
    bool v = fz_chance(f, 60);
    if (!(fabs(cx) <= 1e6 && fabs(cy) <= 1e6 && r >= 0 && r <= 1e6)) f->must_fail = true, f->why_must = "a bad circle";
    const uint64_t before = fz_mask_sig(m);
    const int64_t n = tt_mask_count(m);
    fz_log(f, "tt_mask_fill_circle(%s, %s, %s, %s, %d)", fz_mn(s), fz_d(cx), fz_d(cy), fz_d(r), v);
    FZ_HIT(f, tt_mask_fill_circle);
    tt_result res = tt_mask_fill_circle(m, cx, cy, r, v);
    fz_mres(f, res);
    if (res != TT_OK) unchanged(f, m, before, "a refused tt_mask_fill_circle");
    else if (v ? tt_mask_count(m) < n : tt_mask_count(m) > n) fz_fail(f, "the count moved the wrong way");
}

static void c_mask_fill_rect(fz *f)
{
    int s;
    tt_mask *m = fz_mask_pick(f, &s);
    const int mw = fz_mask_w(m), mh = fz_mask_h(m);
    int x = fz_mask_coord(f, mw), y = fz_mask_coord(f, mh);
    int w = fz_chance(f, 90) ? (int)fz_below(f, (uint32_t)mw + 3) : fz_mask_coord(f, mw);
    int h = fz_chance(f, 90) ? (int)fz_below(f, (uint32_t)mh + 3) : fz_mask_coord(f, mh);
    bool v = fz_chance(f, 60);
    const bool within = m && x >= 0 && y >= 0 && w >= 0 && h >= 0 && (int64_t)x + w <= mw && (int64_t)y + h <= mh;
    int64_t clear = 0; /* the pixels the rect will change, when it lies within */
    for (int j = 0; within && j < h; j++)
        for (int i = 0; i < w; i++) clear += tt_mask_get(m, x + i, y + j) != v;
    const uint64_t before = fz_mask_sig(m);
    const int64_t n = tt_mask_count(m);
    fz_log(f, "tt_mask_fill_rect(%s, %d, %d, %d, %d, %d)", fz_mn(s), x, y, w, h, v);
    FZ_HIT(f, tt_mask_fill_rect);
    tt_result r = tt_mask_fill_rect(m, x, y, w, h, v);
    fz_mres(f, r);
    if (r != TT_OK) unchanged(f, m, before, "a refused tt_mask_fill_rect");
    else if (within && tt_mask_count(m) != n + (v ? clear : -clear))
        fz_fail(f, "a rect within the mask changed the count by %lld, not %lld", (long long)(tt_mask_count(m) - n),
                (long long)(v ? clear : -clear));
}

static void c_mask_fill_polygon(fz *f)
{
    int s;
    tt_mask *m = fz_mask_pick(f, &s);
    tt_vec2 pts[16];
    uint32_t n = 3 + fz_below(f, 14);
    for (uint32_t i = 0; i < n; i++)
        pts[i] = (tt_vec2){ fz_real(f, -5, fz_mask_w(m) + 5), fz_real(f, -5, fz_mask_h(m) + 5) };
    if (fz_chance(f, 10)) pts[fz_below(f, n)].x = fz_nasty(f); /* one bad point spoils the lot */
    bool nopts = fz_chance(f, 3);
    uint32_t pass = fz_chance(f, 90) ? n : (uint32_t[]){ 0, 1, 2, 1000001 }[fz_below(f, 4)];
    if (pass > n) nopts = true; /* never read past the array: a count past the limit goes with NULL */
    bool bad = nopts || pass < 3;
    for (uint32_t i = 0; i < n && !bad; i++) bad = !(fabs(pts[i].x) <= 1e6 && fabs(pts[i].y) <= 1e6);
    if (bad) f->must_fail = true, f->why_must = "a bad polygon";
    bool v = fz_chance(f, 60);
    const uint64_t before = fz_mask_sig(m);
    fz_log(f, "tt_mask_fill_polygon(%s, %s, %u, %d)", fz_mn(s), nopts ? "NULL" : "pts", pass, v);
    for (uint32_t i = 0; i < n && !nopts; i++) fz_log_more(f, " %s", fz_v(pts[i]));
    FZ_HIT(f, tt_mask_fill_polygon);
    tt_result r = tt_mask_fill_polygon(m, nopts ? NULL : pts, pass, v);
    fz_mres(f, r);
    if (r != TT_OK) unchanged(f, m, before, "a refused tt_mask_fill_polygon");
}

/* --- overlaps ---------------------------------------------------------------------- */

/* Two masks and B's offset on A; B is A itself at (0, 0) now and then. */
static void pair(fz *f, tt_mask **a, tt_mask **b, int *sa, int *sb, int *dx, int *dy)
{
    *a = fz_mask_pick(f, sa);
    *b = fz_chance(f, 15) ? *a : fz_mask_pick(f, sb);
    if (*b == *a) *sb = *sa;
    *dx = fz_mask_offset(f, fz_mask_w(*a), fz_mask_w(*b));
    *dy = fz_mask_offset(f, fz_mask_h(*a), fz_mask_h(*b));
    if (*a == *b && fz_chance(f, 50)) *dx = *dy = 0;
    if (llabs((long long)*dx) > TT_MASK_MAX_OFFSET || llabs((long long)*dy) > TT_MASK_MAX_OFFSET)
        f->must_fail = true, f->why_must = "an offset out of range";
}

static int64_t area_of(const tt_mask *a, const tt_mask *b, int dx, int dy) { return tt_mask_overlap_area(a, b, dx, dy); }

static void c_mask_overlap(fz *f)
{
    tt_mask *a, *b;
    int sa, sb, dx, dy, x = -9, y = -9;
    pair(f, &a, &b, &sa, &sb, &dx, &dy);
    bool nxy = fz_chance(f, 20);
    fz_log(f, "tt_mask_overlap(%s, %s, %d, %d, %s)", fz_mn(sa), fz_mn(sb), dx, dy, nxy ? "NULL, NULL" : "&x, &y");
    FZ_HIT(f, tt_mask_overlap);
    bool hit = tt_mask_overlap(a, b, dx, dy, nxy ? NULL : &x, nxy ? NULL : &y);
    fz_log_more(f, " -> %d (%d, %d)", hit, x, y);
    f->failed = !hit; /* no failure channel: a refusal reads as no overlap */
    int64_t area = area_of(a, b, dx, dy);
    if (hit != (area > 0)) fz_fail(f, "tt_mask_overlap says %d, the overlap area is %lld", hit, (long long)area);
    if (hit && !nxy && (tt_mask_get(a, x, y) != 1 || tt_mask_get(b, x - dx, y - dy) != 1))
        fz_fail(f, "the overlapping point (%d, %d) is not set in both", x, y);
}

static void c_mask_overlap_area(fz *f)
{
    tt_mask *a, *b;
    int sa, sb, dx, dy;
    pair(f, &a, &b, &sa, &sb, &dx, &dy);
    fz_log(f, "tt_mask_overlap_area(%s, %s, %d, %d)", fz_mn(sa), fz_mn(sb), dx, dy);
    FZ_HIT(f, tt_mask_overlap_area);
    int64_t n = tt_mask_overlap_area(a, b, dx, dy);
    fz_log_more(f, " -> %lld", (long long)n);
    f->failed = n < 0;
    if (n < -1) fz_fail(f, "tt_mask_overlap_area returned %lld", (long long)n);
    if (n >= 0 && (n > tt_mask_count(a) || n > tt_mask_count(b))) fz_fail(f, "the overlap area passes a count");
    if (a && a == b && dx == 0 && dy == 0 && n != tt_mask_count(a))
        fz_fail(f, "a mask overlaps itself by %lld, its count is %lld", (long long)n, (long long)tt_mask_count(a));
}

static void c_mask_overlap_mask(fz *f)
{
    tt_mask *a, *b;
    int sa, sb, dx, dy;
    pair(f, &a, &b, &sa, &sb, &dx, &dy);
    fz_log(f, "tt_mask_overlap_mask(%s, %s, %d, %d)", fz_mn(sa), fz_mn(sb), dx, dy);
    FZ_HIT(f, tt_mask_overlap_mask);
    tt_mask *m = tt_mask_overlap_mask(a, b, dx, dy);
    fz_log_more(f, " -> %s", m ? "mask" : "NULL");
    f->failed = !m;
    if (m && (fz_mask_w(m) != fz_mask_w(a) || fz_mask_h(m) != fz_mask_h(a) || tt_mask_count(m) != area_of(a, b, dx, dy)))
        fz_fail(f, "the overlap mask is not A's size or does not count the overlap area");
    fz_mask_put(f, m, "tt_mask_overlap_mask");
}

static void c_mask_overlap_mask_into(fz *f)
{
    tt_mask *a, *b;
    int sa, sb, dx, dy;
    pair(f, &a, &b, &sa, &sb, &dx, &dy);
    unsigned how = fz_below(f, 10); /* 0-5 a fresh mask of A's size, 6 A, 7 B, else a pool mask */
    tt_mask *fresh = how <= 5 && a ? tt_mask_create(fz_mask_w(a), fz_mask_h(a), fz_chance(f, 50)) : NULL;
    int so = -1;
    tt_mask *out = fresh ? fresh : how == 6 ? a : how == 7 ? b : fz_mask_pick(f, &so);
    if (how == 6 || how == 7) f->must_fail = true, f->why_must = "out is A or B";
    const uint64_t bo = fz_mask_sig(out), ba = fz_mask_sig(a), bb = fz_mask_sig(b);
    fz_log(f, "tt_mask_overlap_mask_into(%s, %s, %s, %d, %d)", fresh ? "fresh" : how == 6 ? "A" : how == 7 ? "B" : fz_mn(so),
           fz_mn(sa), fz_mn(sb), dx, dy);
    FZ_HIT(f, tt_mask_overlap_mask_into);
    tt_result r = tt_mask_overlap_mask_into(out, a, b, dx, dy);
    fz_mres(f, r);
    if (r != TT_OK) unchanged(f, out, bo, "a refused tt_mask_overlap_mask_into");
    if (out != a) unchanged(f, a, ba, "tt_mask_overlap_mask_into's A");
    if (out != b) unchanged(f, b, bb, "tt_mask_overlap_mask_into's B");
    if (r == TT_OK && tt_mask_count(out) != area_of(a, b, dx, dy)) fz_fail(f, "the overlap mask does not count the area");
    tt_mask_destroy(fresh);
}

static void c_mask_overlap_normal(fz *f)
{
    tt_mask *a, *b;
    int sa, sb, dx, dy;
    pair(f, &a, &b, &sa, &sb, &dx, &dy);
    bool nout = fz_chance(f, 3);
    if (nout) f->must_fail = true, f->why_must = "a NULL out";
    tt_vec2 v = { 9, 9 };
    fz_log(f, "tt_mask_overlap_normal(%s, %s, %d, %d, %s)", fz_mn(sa), fz_mn(sb), dx, dy, nout ? "NULL" : "&n");
    FZ_HIT(f, tt_mask_overlap_normal);
    tt_result r = tt_mask_overlap_normal(a, b, dx, dy, nout ? NULL : &v);
    fz_mres(f, r);
    if (r != TT_OK) return;
    double len = hypot(v.x, v.y);
    if (!(len == 0 || fabs(len - 1) < 1e-12)) fz_fail(f, "the normal %s is neither unit nor zero", fz_v(v));
}

static void c_mask_convolve(fz *f)
{
    int sa, sb;
    tt_mask *a = fz_mask_pick(f, &sa), *b = fz_mask_pick(f, &sb);
    /* a second of work is refused by the call; keep the rest under a few ms */
    double cost = (double)tt_mask_count(b) * fz_mask_h(a) * (fz_mask_w(a) / 64 + 1);
    if (cost > 3e6 && cost <= TT_MASK_MAX_CONVOLVE) b = NULL, sb = -1, f->must_fail = true, f->why_must = "a NULL mask";
    if (cost > TT_MASK_MAX_CONVOLVE) f->must_fail = true, f->why_must = "too much work";
    const uint64_t ba = fz_mask_sig(a), bb = fz_mask_sig(b);
    fz_log(f, "tt_mask_convolve(%s, %s)", fz_mn(sa), fz_mn(sb));
    FZ_HIT(f, tt_mask_convolve);
    tt_mask *m = tt_mask_convolve(a, b);
    fz_log_more(f, " -> %s", m ? "mask" : "NULL");
    f->failed = !m;
    unchanged(f, a, ba, "tt_mask_convolve's A");
    unchanged(f, b, bb, "tt_mask_convolve's B");
    if (m && (fz_mask_w(m) != fz_mask_w(a) + fz_mask_w(b) - 1 || fz_mask_h(m) != fz_mask_h(a) + fz_mask_h(b) - 1))
        fz_fail(f, "the convolution is %d x %d", fz_mask_w(m), fz_mask_h(m));
    fz_mask_put(f, m, "tt_mask_convolve");
}

const fz_entry fz_mask2_entries[] = {
    { "tt_mask_size", c_mask_size, 1 },
    { "tt_mask_get", c_mask_get, 1 },
    { "tt_mask_set", c_mask_set, 2 },
    { "tt_mask_count", c_mask_count, 1 },
    { "tt_mask_clear", c_mask_clear, 1 },
    { "tt_mask_fill", c_mask_fill, 1 },
    { "tt_mask_invert", c_mask_invert, 1 },
    { "tt_mask_bounding_rect", c_mask_bounding_rect, 1 },
    { "tt_mask_centroid", c_mask_centroid, 1 },
    { "tt_mask_draw", c_mask_draw, 2 },
    { "tt_mask_erase", c_mask_erase, 1 },
    { "tt_mask_fill_circle", c_mask_fill_circle, 3 },
    { "tt_mask_fill_rect", c_mask_fill_rect, 2 },
    { "tt_mask_fill_polygon", c_mask_fill_polygon, 2 },
    { "tt_mask_overlap", c_mask_overlap, 2 },
    { "tt_mask_overlap_area", c_mask_overlap_area, 2 },
    { "tt_mask_overlap_mask", c_mask_overlap_mask, 1 },
    { "tt_mask_overlap_mask_into", c_mask_overlap_mask_into, 1 },
    { "tt_mask_overlap_normal", c_mask_overlap_normal, 1 },
    { "tt_mask_convolve", c_mask_convolve, 1 },
    { NULL, NULL, 0 },
};
