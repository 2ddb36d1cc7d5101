/* tests/fuzz/fuzz_c_mask_shape.c — wrappers of tether/mask.h, third part:
 * the shape of the set pixels (components, their rects, the outline,
 * marching-squares polylines) and masks in the world (places, the
 * conversions, tt_mask_to_chains into the fuzzer's worlds). Every call here
 * but tt_mask_to_chains only reads its mask: the mask must stay as it was.
 * Known answers: as many component rects as components, no more components
 * than set pixels, a component no larger than its mask, outline points on
 * set pixels, polyline points on the mask's corners grid, a place's
 * conversions undo each other, and a chain call adds *count shapes (a
 * refused one none: the harness checks the world's hash). */
#include "fuzz_c.h"

#include <math.h>
#include <stdlib.h>

static void unchanged(fz *f, const tt_mask *m, uint64_t before, const char *what)
{
    if (m && fz_mask_sig(m) != before) fz_fail(f, "%s changed its mask's pixels", what);
}

static void c_mask_component_count(fz *f)
{
    int s;
    tt_mask *m = fz_mask_pick(f, &s);
    const uint64_t before = fz_mask_sig(m);
    fz_log(f, "tt_mask_component_count(%s)", fz_mn(s));
    FZ_HIT(f, tt_mask_component_count);
    int64_t n = tt_mask_component_count(m);
    fz_log_more(f, " -> %lld", (long long)n);
    f->failed = n < 0;
    unchanged(f, m, before, "tt_mask_component_count");
    if (!m) return;
    uint32_t rects = 0;
    if (n < 0 || n > tt_mask_count(m) || (n > 0) != (tt_mask_count(m) > 0))
        fz_fail(f, "%lld components of %lld pixels", (long long)n, (long long)tt_mask_count(m));
    if (tt_mask_component_rects(m, NULL, 0, &rects) != TT_OK || rects != n)
        fz_fail(f, "%lld components but %u component rects", (long long)n, rects);
}

static void c_mask_component(fz *f)
{
    int s;
    tt_mask *m = fz_mask_pick(f, &s);
    bool largest = fz_chance(f, 30);
    int x = largest ? -1 : fz_mask_coord(f, fz_mask_w(m)), y = largest ? -1 : fz_mask_coord(f, fz_mask_h(m));
    if (m && !(x == -1 && y == -1) && !(x >= 0 && y >= 0 && x < fz_mask_w(m) && y < fz_mask_h(m)))
        f->must_fail = true, f->why_must = "a pixel outside";
    const uint64_t before = fz_mask_sig(m);
    fz_log(f, "tt_mask_component(%s, %d, %d)", fz_mn(s), x, y);
    FZ_HIT(f, tt_mask_component);
    tt_mask *c = tt_mask_component(m, x, y);
    fz_log_more(f, " -> %s", c ? "mask" : "NULL");
    f->failed = !c;
    unchanged(f, m, before, "tt_mask_component");
    if (c && (fz_mask_w(c) != fz_mask_w(m) || fz_mask_h(c) != fz_mask_h(m) || tt_mask_count(c) > tt_mask_count(m) ||
              tt_mask_overlap_area(c, m, 0, 0) != tt_mask_count(c) || (tt_mask_count(c) > 0 && tt_mask_component_count(c) != 1)))
        fz_fail(f, "the component is not one piece of its mask");
    if (c && !largest && tt_mask_get(m, x, y) == 1 && tt_mask_get(c, x, y) != 1)
        fz_fail(f, "the component of (%d, %d) does not hold it", x, y);
    fz_mask_put(f, c, "tt_mask_component");
}

static void c_mask_component_rects(fz *f)
{
    int s;
    tt_mask *m = fz_mask_pick(f, &s);
    uint32_t cap = 0, count = 0xdead;
    tt_mask_rect *out = fz_buffer(f, &cap, 16, sizeof *out);
    uint32_t pass = out ? cap : 0;
    bool ncount = fz_chance(f, 3);
    if (ncount) f->must_fail = true, f->why_must = "a NULL count";
    const uint64_t before = fz_mask_sig(m);
    fz_log(f, "tt_mask_component_rects(%s, %s, %u, %s)", fz_mn(s), out ? "out" : "NULL", pass, ncount ? "NULL" : "&n");
    FZ_HIT(f, tt_mask_component_rects);
    tt_result r = tt_mask_component_rects(m, out, pass, ncount ? NULL : &count);
    fz_mres(f, r);
    unchanged(f, m, before, "tt_mask_component_rects");
    if (r == TT_OK) {
        fz_log_more(f, " %u", count);
        for (uint32_t i = 0; i < count && i < pass; i++) {
            tt_mask_rect q = out[i];
            if (q.w < 1 || q.h < 1 || q.x < 0 || q.y < 0 || q.x + q.w > fz_mask_w(m) || q.y + q.h > fz_mask_h(m))
                fz_fail(f, "component rect %u {%d, %d, %d, %d} is not in the mask", i, q.x, q.y, q.w, q.h);
        }
    }
    free(out);
}

static void c_mask_outline(fz *f)
{
    int s;
    tt_mask *m = fz_mask_pick(f, &s);
    uint32_t cap = 0, count = 0xdead;
    int *xy = fz_buffer(f, &cap, 256, 2 * sizeof *xy);
    uint32_t pass = xy ? cap : 0;
    bool ncount = fz_chance(f, 3);
    if (ncount) f->must_fail = true, f->why_must = "a NULL count";
    const uint64_t before = fz_mask_sig(m);
    fz_log(f, "tt_mask_outline(%s, %s, %u, %s)", fz_mn(s), xy ? "xy" : "NULL", pass, ncount ? "NULL" : "&n");
    FZ_HIT(f, tt_mask_outline);
    tt_result r = tt_mask_outline(m, xy, pass, ncount ? NULL : &count);
    fz_mres(f, r);
    unchanged(f, m, before, "tt_mask_outline");
    if (r == TT_OK) {
        fz_log_more(f, " %u", count);
        for (uint32_t i = 0; i < count && i < pass; i++)
            if (tt_mask_get(m, xy[2 * i], xy[2 * i + 1]) != 1)
                fz_fail(f, "outline point %u (%d, %d) is not a set pixel", i, xy[2 * i], xy[2 * i + 1]);
    }
    free(xy);
}

static void c_mask_polylines(fz *f)
{
    int s;
    tt_mask *m = fz_mask_pick(f, &s);
    if (m && (int64_t)fz_mask_w(m) * fz_mask_h(m) > 40000 && fz_chance(f, 80)) m = NULL, s = -1, f->must_fail = true;
    unsigned r0 = fz_below(f, 100);
    double tol = r0 < 30 ? 0.0 : r0 < 90 ? fz_real(f, 0, 3) : fz_nasty(f);
    if (!(tol >= 0 && tol <= 1e6)) f->must_fail = true, f->why_must = "a bad tolerance";
    bool nlines = fz_chance(f, 3), ncount = fz_chance(f, 3);
    if (nlines || ncount) f->must_fail = true, f->why_must = "a NULL out";
    tt_mask_polyline *lines = NULL;
    uint32_t count = 0;
    const uint64_t before = fz_mask_sig(m);
    fz_log(f, "tt_mask_polylines(%s, %s, %s, %s)", fz_mn(s), fz_d(tol), nlines ? "NULL" : "&lines", ncount ? "NULL" : "&n");
    FZ_HIT(f, tt_mask_polylines);
    tt_result r = tt_mask_polylines(m, tol, nlines ? NULL : &lines, ncount ? NULL : &count);
    fz_mres(f, r);
    unchanged(f, m, before, "tt_mask_polylines");
    if (r == TT_OK) {
        fz_log_more(f, " %u lines", count);
        if (count && !lines) fz_fail(f, "%u polylines and no array", count);
        if ((count > 0) != (tt_mask_count(m) > 0)) fz_fail(f, "%u polylines of a mask counting %lld", count, (long long)tt_mask_count(m));
        for (uint32_t i = 0; i < count; i++) {
            if (lines[i].count < 3) fz_fail(f, "polyline %u has %u points", i, lines[i].count);
            for (uint32_t k = 0; k < lines[i].count; k++) {
                tt_vec2 p = lines[i].points[k];
                if (!(p.x >= 0 && p.y >= 0 && p.x <= fz_mask_w(m) && p.y <= fz_mask_h(m) && p.x * 2 == floor(p.x * 2) &&
                      p.y * 2 == floor(p.y * 2)))
                    fz_fail(f, "polyline %u point %u %s is off the mask's half-pixel grid", i, k, fz_v(p));
            }
        }
    }
    FZ_HIT(f, tt_mask_polylines_free);
    tt_mask_polylines_free(lines, count);
}

/* tt_mask_polylines_free on nothing: NULL and any count. */
static void c_mask_polylines_free(fz *f)
{
    uint32_t n = fz_chance(f, 50) ? 0 : fz_rand(f) & 0xffff;
    fz_log(f, "tt_mask_polylines_free(NULL, %u)", n);
    FZ_HIT(f, tt_mask_polylines_free);
    tt_mask_polylines_free(NULL, n);
}

static tt_mask_place place(fz *f)
{
    tt_mask_place p = { fz_vec(f, -100, 100), fz_real(f, 0.01, 2) };
    if (fz_chance(f, 8)) p.pixel = fz_nasty(f);
    if (fz_chance(f, 5)) p.origin.x = fz_nasty(f);
    return p;
}

static bool place_ok(const tt_mask_place *p)
{
    return p && isfinite(p->origin.x) && isfinite(p->origin.y) && p->pixel > 0 && isfinite(p->pixel) &&
           fabs(p->origin.x) < 1e12 && fabs(p->origin.y) < 1e12 && p->pixel > 1e-6 && p->pixel < 1e6;
}

static void c_mask_place_default(fz *f)
{
    fz_log(f, "tt_mask_place_default()");
    FZ_HIT(f, tt_mask_place_default);
    tt_mask_place p = tt_mask_place_default();
    if (p.origin.x != 0 || p.origin.y != 0 || p.pixel != 1) fz_fail(f, "the default place is not (0, 0), 1");
}

/* to_world (0) and from_world (1): plausible places round-trip. */
static void convert(fz *f, int which)
{
    tt_mask_place p = place(f);
    bool np = fz_chance(f, 3);
    tt_vec2 q = fz_chance(f, 90) ? fz_vec(f, -200, 200) : (tt_vec2){ fz_nasty(f), fz_nasty(f) };
    fz_log(f, "%s(%s {%s, %s}, %s)", which ? "tt_mask_from_world" : "tt_mask_to_world", np ? "NULL" : "&place",
           fz_v(p.origin), fz_d(p.pixel), fz_v(q));
    tt_vec2 out = which ? tt_mask_from_world(np ? NULL : &p, q) : tt_mask_to_world(np ? NULL : &p, q);
    fz_log_more(f, " -> %s", fz_v(out));
    if (np || !place_ok(&p) || !(fabs(q.x) <= 1e6 && fabs(q.y) <= 1e6)) return;
    fz_finite_vec(f, out, "a converted point");
    tt_vec2 back = which ? tt_mask_to_world(&p, out) : tt_mask_from_world(&p, out);
    double tol = 1e-9 * (1 + fabs(q.x) + fabs(q.y) + (fabs(p.origin.x) + fabs(p.origin.y)) / p.pixel + p.pixel);
    if (!(fabs(back.x - q.x) <= tol && fabs(back.y - q.y) <= tol))
        fz_fail(f, "a point converted there and back moved from %s to %s", fz_v(q), fz_v(back));
}

static void c_mask_to_world(fz *f)
{
    FZ_HIT(f, tt_mask_to_world);
    convert(f, 0);
}

static void c_mask_from_world(fz *f)
{
    FZ_HIT(f, tt_mask_from_world);
    convert(f, 1);
}

static void c_mask_to_chains(fz *f)
{
    int s;
    tt_mask *m = fz_mask_pick(f, &s);
    bool mnull = !m;
    if (m && (int64_t)fz_mask_w(m) * fz_mask_h(m) > 40000) m = NULL, s = -1, mnull = true;
    tt_world *w = fz_world_pick(f); /* after the mask: it sets the world the harness checks */
    if (mnull) f->must_fail = true, f->why_must = "a NULL mask";
    tt_mask_place p = place(f);
    bool np = fz_chance(f, 3);
    double tol = fz_chance(f, 90) ? fz_real(f, 0, 3) : fz_nasty(f);
    tt_shape_def d = tt_shape_def_default();
    d.friction_kinetic = fz_chance(f, 90) ? fz_real(f, 0, 0.6) : fz_nasty(f);
    bool nd = fz_chance(f, 30);
    uint32_t cap = 0, count = 0xdead;
    tt_shape *out = fz_buffer(f, &cap, 24, sizeof *out);
    uint32_t pass = out ? cap : 0;
    bool ncount = fz_chance(f, 3);
    if (ncount) f->must_fail = true, f->why_must = "a NULL count";
    const uint64_t before = fz_mask_sig(m);
    const uint32_t shapes = w ? tt_world_shape_count(w) : 0;
    fz_log(f, "tt_mask_to_chains(%s, %s, %s, %s, %s, %s, %u, %s)", fz_mn(s), fz_wn(f, w), np ? "NULL" : "&place",
           fz_d(tol), nd ? "NULL" : "&def", out ? "out" : "NULL", pass, ncount ? "NULL" : "&n");
    fz_log_more(f, " /* place %s %s, friction %s */", fz_v(p.origin), fz_d(p.pixel), fz_d(d.friction_kinetic));
    FZ_HIT(f, tt_mask_to_chains);
    tt_result r = tt_mask_to_chains(m, w, np ? NULL : &p, tol, nd ? NULL : &d, out, pass, ncount ? NULL : &count);
    fz_log_more(f, " -> %s", fz_res_name(r));
    if (r != TT_OK) {
        fz_log_more(f, " \"%.200s\"", tt_mask_last_error());
        f->failed = true;
    }
    unchanged(f, m, before, "tt_mask_to_chains");
    if (r == TT_OK) {
        fz_log_more(f, " %u shapes", count);
        if (count > pass || tt_world_shape_count(w) != shapes + count)
            fz_fail(f, "tt_mask_to_chains made %u shapes (cap %u), the world has %u more", count, pass,
                    tt_world_shape_count(w) - shapes);
        for (uint32_t i = 0; i < count; i++) {
            fz_h h = FZ_H(out[i]);
            fz_remember(f, TT_KIND_SHAPE, h);
            tt_shape_type type = TT_SHAPE_SEGMENT;
            if (!tt_shape_is_valid(w, out[i]) || tt_shape_get_type(w, out[i], &type) != TT_OK || type != TT_SHAPE_CHAIN)
                fz_fail(f, "tt_mask_to_chains gave shape %u that is no live chain", i);
        }
    }
    free(out);
}

const fz_entry fz_mask3_entries[] = {
    { "tt_mask_component_count", c_mask_component_count, 1 },
    { "tt_mask_component", c_mask_component, 1 },
    { "tt_mask_component_rects", c_mask_component_rects, 1 },
    { "tt_mask_outline", c_mask_outline, 1 },
    { "tt_mask_polylines", c_mask_polylines, 2 },
    { "tt_mask_polylines_free", c_mask_polylines_free, 1 },
    { "tt_mask_place_default", c_mask_place_default, 1 },
    { "tt_mask_to_world", c_mask_to_world, 1 },
    { "tt_mask_from_world", c_mask_from_world, 1 },
    { "tt_mask_to_chains", c_mask_to_chains, 2 },
    { NULL, NULL, 0 },
};
