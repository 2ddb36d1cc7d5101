/* tests/fuzz/fuzz_c_terrain.c — wrappers of tether/terrain.h: terrains from
 * random small masks with garbage placements, bands and materials; carves
 * and fills of every size (NaN, huge, wholly outside); masks painted at
 * huge offsets; reads with NULL outputs. */
#include "fuzz_c.h"

#include <math.h>
#include <stdlib.h>

#define TK TT_KIND_TERRAIN

/* A small mask with a few filled rectangles and circles (freed by the caller). */
static tt_mask *some_mask(fz *f)
{
    int w = 1 + (int)fz_below(f, 96), h = 1 + (int)fz_below(f, 64);
    tt_mask *m = tt_mask_create(w, h, fz_chance(f, 10));
    if (!m) abort();
    for (uint32_t k = fz_below(f, 5); k > 0; k--)
        tt_mask_fill_rect(m, (int)fz_below(f, (uint32_t)w), (int)fz_below(f, (uint32_t)h), 1 + (int)fz_below(f, 40),
                          1 + (int)fz_below(f, 40), true);
    if (fz_chance(f, 50)) tt_mask_fill_circle(m, fz_real(f, 0, w), fz_real(f, 0, h), fz_real(f, 0, 20), fz_chance(f, 50));
    return m;
}

static void c_terrain_def_default(fz *f)
{
    fz_log(f, "tt_terrain_def_default()");
    FZ_HIT(f, tt_terrain_def_default);
    tt_terrain_def d = tt_terrain_def_default();
    if (d.solid || d.pixel != 0.05 || d.band != 10 || d.mask != 0xFFFF) fz_fail(f, "tt_terrain_def_default is not the documented default");
}

static void c_terrain_create(fz *f)
{
    tt_world *w = fz_world_pick(f);
    tt_mask *m = some_mask(f);
    tt_terrain_def d = tt_terrain_def_default();
    d.solid = fz_chance(f, 3) ? NULL : m;
    d.origin = fz_chance(f, 50) ? fz_vec(f, -20, 20) : fz_point(f);
    d.pixel = fz_chance(f, 80) ? fz_real(f, 0.01, 0.5) : fz_nasty(f);
    if (fz_chance(f, 10)) d.band = (int)fz_below(f, 41) - (fz_chance(f, 10) ? 100 : 0);
    d.restitution = fz_chance(f, 90) ? fz_real(f, 0, 1) : fz_nasty(f);
    d.friction_static = fz_real(f, 0, 1);
    d.friction_kinetic = fz_chance(f, 95) ? fz_real(f, 0, 1) : fz_nasty(f);
    if (fz_chance(f, 20)) d.category = fz_bits16(f);
    if (fz_chance(f, 20)) d.mask = fz_bits16(f);
    d.user = fz_rand(f);
    fz_log(f, "tt_terrain_create(%s, &(tt_terrain_def){solid %s, origin %s, pixel %s, band %d, material %s %s %s, filter %#x/%#x})",
           fz_wn(f, w), d.solid ? "m" : "NULL", fz_v(d.origin), fz_d(d.pixel), d.band, fz_d(d.restitution),
           fz_d(d.friction_static), fz_d(d.friction_kinetic), d.category, d.mask);
    FZ_HIT(f, tt_terrain_create);
    fz_hres(f, TK, FZ_H(tt_terrain_create(w, fz_chance(f, 2) ? NULL : &d)));
    tt_mask_destroy(m);
}

static void c_terrain_destroy(fz *f)
{
    tt_world *w = fz_world_pick(f);
    fz_h h = fz_handle(f, TK);
    fz_log(f, "tt_terrain_destroy(%s, %s)", fz_wn(f, w), fz_hn(h, TK));
    FZ_HIT(f, tt_terrain_destroy);
    fz_res(f, tt_terrain_destroy(w, FZ_T(h)));
    if (!f->failed) fz_forget(f, TK, h);
}

static void c_terrain_is_valid(fz *f)
{
    tt_world *w = fz_world_any(f);
    fz_h h = fz_handle(f, TK);
    fz_log(f, "tt_terrain_is_valid(%s, %s)", fz_wn(f, w), fz_hn(h, TK));
    FZ_HIT(f, tt_terrain_is_valid);
    bool ok = tt_terrain_is_valid(w, FZ_T(h));
    fz_log_more(f, " -> %s", ok ? "true" : "false");
    f->failed = !ok;
    if (!w && ok) fz_fail(f, "tt_terrain_is_valid said true for a NULL world");
    if (!w) f->must_fail = false;
}

static void c_world_terrain_count(fz *f)
{
    tt_world *w = fz_world_any(f);
    fz_log(f, "tt_world_terrain_count(%s)", fz_wn(f, w));
    FZ_HIT(f, tt_world_terrain_count);
    uint32_t n = tt_world_terrain_count(w);
    fz_log_more(f, " -> %u", n);
    if (!w && n) fz_fail(f, "tt_world_terrain_count(NULL) is %u", n);
}

/* A call on one terrain handle: pick, draw, log, call; OUT is true for reads. */
#define ON_TERRAIN(name, OUT, draw, show, call)                                                      \
    static void c_##name(fz *f)                                                                      \
    {                                                                                                \
        tt_world *w = fz_world_pick(f);                                                              \
        f->readonly = OUT;                                                                           \
        fz_h h = fz_handle(f, TK);                                                                   \
        draw;                                                                                        \
        fz_log(f, #name "(%s, %s, %s)", fz_wn(f, w), fz_hn(h, TK), show);                            \
        FZ_HIT(f, name);                                                                             \
        fz_res(f, call);                                                                             \
    }
#define OUTP(p) (fz_chance(f, 4) ? NULL : (p))

ON_TERRAIN(tt_terrain_paint_circle, false, tt_vec2 c = fz_chance(f, 70) ? fz_vec(f, -30, 30) : fz_point(f);
           double r = fz_chance(f, 85) ? fz_real(f, 0, 3) : fz_nasty(f); bool s = fz_chance(f, 30),
           fz_v(c), tt_terrain_paint_circle(w, FZ_T(h), c, r, s))
ON_TERRAIN(tt_terrain_set_material, false, double e = fz_chance(f, 90) ? fz_real(f, 0, 1) : fz_nasty(f),
           fz_d(e), tt_terrain_set_material(w, FZ_T(h), e, fz_real(f, 0, 1), fz_real(f, 0, 1)))
ON_TERRAIN(tt_terrain_get_mask, true, const tt_mask *m, "&mask", tt_terrain_get_mask(w, FZ_T(h), OUTP(&m)))
ON_TERRAIN(tt_terrain_get_place, true, tt_mask_place p, "&place", tt_terrain_get_place(w, FZ_T(h), OUTP(&p)))
ON_TERRAIN(tt_terrain_get_user, true, uint64_t u, "&user", tt_terrain_get_user(w, FZ_T(h), OUTP(&u)))
ON_TERRAIN(tt_terrain_is_solid, true, bool s; tt_vec2 p = fz_chance(f, 80) ? fz_vec(f, -30, 30) : fz_point(f),
           fz_v(p), tt_terrain_is_solid(w, FZ_T(h), p, OUTP(&s)))

static void c_terrain_distance(fz *f)
{
    tt_world *w = fz_world_pick(f);
    f->readonly = true;
    fz_h h = fz_handle(f, TK);
    tt_vec2 p = fz_chance(f, 80) ? fz_vec(f, -30, 30) : fz_point(f), n = {0, 0};
    double d = 0.0;
    fz_log(f, "tt_terrain_distance(%s, %s, %s)", fz_wn(f, w), fz_hn(h, TK), fz_v(p));
    FZ_HIT(f, tt_terrain_distance);
    fz_res(f, tt_terrain_distance(w, FZ_T(h), p, OUTP(&d), OUTP(&n)));
    fz_finite(f, d, "a terrain distance");
    fz_finite_vec(f, n, "a terrain normal");
}

static void c_world_query_terrains(fz *f)
{
    tt_world *w = fz_world_pick(f);
    f->readonly = true;
    tt_vec2 lo = fz_chance(f, 80) ? fz_vec(f, -30, 30) : fz_point(f), hi = lo;
    if (fz_chance(f, 60)) hi = fz_chance(f, 80) ? (tt_vec2){lo.x + fz_real(f, 0, 20), lo.y + fz_real(f, 0, 20)} : fz_point(f);
    uint16_t mask = fz_bits16(f);
    uint32_t cap, n = 0;
    tt_terrain *out = fz_buffer(f, &cap, 4, sizeof *out);
    bool null_n = fz_chance(f, 4);
    fz_log(f, "tt_world_query_terrains(%s, %s, %s, %#x, %s, %u, %s)", fz_wn(f, w), fz_v(lo), fz_v(hi), mask,
           out ? "out" : "NULL", cap, null_n ? "NULL" : "&n");
    FZ_HIT(f, tt_world_query_terrains);
    fz_res(f, tt_world_query_terrains(w, lo, hi, mask, out, cap, null_n ? NULL : &n));
    for (uint32_t i = 0; !f->failed && out && !null_n && i < n && i < cap; i++)
        if (!tt_terrain_is_valid(w, out[i])) fz_fail(f, "tt_world_query_terrains listed a stale terrain");
    free(out);
}

static void c_terrain_paint_mask(fz *f)
{
    tt_world *w = fz_world_pick(f);
    fz_h h = fz_handle(f, TK);
    tt_mask *m = some_mask(f);
    int dx = fz_chance(f, 90) ? (int)fz_below(f, 120) - 30 : (int)(fz_rand(f) % 2000000001) - 1000000000;
    int dy = fz_chance(f, 90) ? (int)fz_below(f, 80) - 20 : (int)(fz_rand(f) % 2000000001) - 1000000000;
    bool null = fz_chance(f, 3), s = fz_chance(f, 40);
    fz_log(f, "tt_terrain_paint_mask(%s, %s, %s, %d, %d, %d)", fz_wn(f, w), fz_hn(h, TK), null ? "NULL" : "m", dx, dy, s);
    FZ_HIT(f, tt_terrain_paint_mask);
    fz_res(f, tt_terrain_paint_mask(w, FZ_T(h), null ? NULL : m, dx, dy, s));
    tt_mask_destroy(m);
}

const fz_entry fz_terrain_entries[] = {
    { "tt_terrain_def_default", c_terrain_def_default, 1 },
    { "tt_terrain_create", c_terrain_create, 4 },
    { "tt_terrain_destroy", c_terrain_destroy, 1 },
    { "tt_terrain_is_valid", c_terrain_is_valid, 1 },
    { "tt_world_terrain_count", c_world_terrain_count, 1 },
    { "tt_terrain_paint_circle", c_tt_terrain_paint_circle, 4 },
    { "tt_terrain_paint_mask", c_terrain_paint_mask, 2 },
    { "tt_terrain_get_mask", c_tt_terrain_get_mask, 1 },
    { "tt_terrain_get_place", c_tt_terrain_get_place, 1 },
    { "tt_terrain_set_material", c_tt_terrain_set_material, 1 },
    { "tt_terrain_get_user", c_tt_terrain_get_user, 1 },
    { "tt_terrain_distance", c_terrain_distance, 1 },
    { "tt_terrain_is_solid", c_tt_terrain_is_solid, 1 },
    { "tt_world_query_terrains", c_world_query_terrains, 1 },
    { NULL, NULL, 0 },
};
