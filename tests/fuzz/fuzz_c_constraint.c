/* tests/fuzz/fuzz_c_constraint.c — wrappers of tether/constraint.h: every
 * kind made from garbage defs over live, stale and foreign particles,
 * tearing (break strains), winches (max rates), moving anchors and boxes,
 * and the reads: errors, particles, lines, break events. */
#include "fuzz_c.h"

#include <math.h>
#include <stdlib.h>

#define PK TT_KIND_PARTICLE
#define CK TT_KIND_CONSTRAINT

static double angle(fz *f) { return fz_real(f, -M_PI, M_PI); }

#define DEF_DEFAULT(kind, check)                                                                     \
    static void c_##kind##_def_default(fz *f)                                                        \
    {                                                                                                \
        fz_log(f, "tt_" #kind "_def_default()");                                                     \
        FZ_HIT(f, tt_##kind##_def_default);                                                          \
        tt_##kind##_def d = tt_##kind##_def_default();                                               \
        if (!(check)) fz_fail(f, "tt_" #kind "_def_default is not the documented default");          \
    }
DEF_DEFAULT(distance, d.length == -1.0 && d.stiffness == 1.0 && d.compliance == 0.0)
DEF_DEFAULT(pin, d.anchor_here && d.stiffness == 1.0)
DEF_DEFAULT(bounds, !d.particles && d.count == 0 && d.min.x == -10.0 && d.max.y == 10.0)
DEF_DEFAULT(angle, d.use_current && d.stiffness == 1.0)
DEF_DEFAULT(area, d.count == 0 && d.use_current && d.pressure == 1.0)
DEF_DEFAULT(collinear, d.stiffness == 1.0 && d.compliance == 0.0)

static void created(fz *f, tt_constraint c) { fz_hres(f, CK, FZ_H(c)); }

static void c_distance_create(fz *f)
{
    tt_world *w = fz_world_pick(f);
    tt_distance_def d = tt_distance_def_default();
    fz_h a = fz_handle(f, PK), b = fz_chance(f, 3) ? a : fz_handle(f, PK);
    d.a = FZ_P(a);
    d.b = FZ_P(b);
    d.mode = (tt_distance_mode)fz_enum(f, 3);
    d.length = fz_chance(f, 50) ? -1.0 : fz_real(f, 0, 5);
    d.stiffness = fz_stiffness(f);
    d.compliance = fz_compliance(f);
    d.break_strain = fz_chance(f, 60) ? 0.0 : fz_real(f, 0, 1);
    d.collide = fz_chance(f, 30);
    d.max_rate = fz_chance(f, 70) ? 0.0 : fz_real(f, 0, 10);
    fz_log(f, "tt_distance_create(%s, &(tt_distance_def){%s, %s, mode %d, length %s, stiffness %s, compliance %s, "
              "break_strain %s, collide %d, max_rate %s})", fz_wn(f, w), fz_hn(a, PK), fz_hn(b, PK), (int)d.mode,
           fz_d(d.length), fz_d(d.stiffness), fz_d(d.compliance), fz_d(d.break_strain), d.collide, fz_d(d.max_rate));
    FZ_HIT(f, tt_distance_create);
    created(f, tt_distance_create(w, fz_chance(f, 2) ? NULL : &d));
}

static void c_pin_create(fz *f)
{
    tt_world *w = fz_world_pick(f);
    tt_pin_def d = tt_pin_def_default();
    fz_h p = fz_handle(f, PK);
    d.particle = FZ_P(p);
    d.anchor_here = fz_chance(f, 50);
    d.anchor = fz_point(f);
    d.stiffness = fz_stiffness(f);
    d.compliance = fz_compliance(f);
    d.max_rate = fz_chance(f, 70) ? 0.0 : fz_real(f, 0, 10);
    fz_log(f, "tt_pin_create(%s, &(tt_pin_def){%s, anchor_here %d, %s, stiffness %s, compliance %s, max_rate %s})",
           fz_wn(f, w), fz_hn(p, PK), d.anchor_here, fz_v(d.anchor), fz_d(d.stiffness), fz_d(d.compliance),
           fz_d(d.max_rate));
    FZ_HIT(f, tt_pin_create);
    created(f, tt_pin_create(w, fz_chance(f, 2) ? NULL : &d));
}

/* A box around the room, and now and then an inverted, flat or far one. */
static void box(fz *f, tt_vec2 *lo, tt_vec2 *hi)
{
    double s = fz_real(f, 1, 60);
    *lo = (tt_vec2){ -s, -s * fz_real(f, 0.2, 1) };
    *hi = (tt_vec2){ s, s * fz_real(f, 0.2, 1) };
    if (fz_chance(f, 8)) *lo = fz_point(f);
    if (fz_chance(f, 8)) *hi = fz_point(f);
}

static void c_bounds_create(fz *f)
{
    tt_world *w = fz_world_pick(f);
    tt_bounds_def d = tt_bounds_def_default();
    tt_particle *ps = NULL;
    if (fz_chance(f, 50)) {
        d.count = fz_count(f, 0, 16);
        if (d.count <= 4096 && fz_chance(f, 95)) ps = fz_particles(f, d.count);
        d.particles = ps;
    }
    box(f, &d.min, &d.max);
    d.outside = fz_chance(f, 15);
    d.friction = fz_chance(f, 50) ? 0.0 : fz_real(f, 0, 1);
    fz_log(f, "tt_bounds_create(%s, &(tt_bounds_def){%s, %u, %s, %s, outside %d, friction %s})", fz_wn(f, w),
           ps ? "particles" : "NULL", d.count, fz_v(d.min), fz_v(d.max), d.outside, fz_d(d.friction));
    FZ_HIT(f, tt_bounds_create);
    created(f, tt_bounds_create(w, fz_chance(f, 2) ? NULL : &d));
    free(ps);
}

static void three(fz *f, fz_h *a, fz_h *b, fz_h *c)
{
    *a = fz_handle(f, PK);
    *b = fz_chance(f, 3) ? *a : fz_handle(f, PK);
    *c = fz_handle(f, PK);
}

static void c_angle_create(fz *f)
{
    tt_world *w = fz_world_pick(f);
    tt_angle_def d = tt_angle_def_default();
    fz_h a, b, c;
    three(f, &a, &b, &c);
    d.a = FZ_P(a);
    d.b = FZ_P(b);
    d.c = FZ_P(c);
    d.use_current = fz_chance(f, 50);
    d.min = angle(f);
    d.max = angle(f);
    d.stiffness = fz_stiffness(f);
    d.compliance = fz_compliance(f);
    fz_log(f, "tt_angle_create(%s, &(tt_angle_def){%s, %s, %s, %s, %s, use_current %d, %s, %s})", fz_wn(f, w),
           fz_hn(a, PK), fz_hn(b, PK), fz_hn(c, PK), fz_d(d.min), fz_d(d.max), d.use_current, fz_d(d.stiffness),
           fz_d(d.compliance));
    FZ_HIT(f, tt_angle_create);
    created(f, tt_angle_create(w, fz_chance(f, 2) ? NULL : &d));
}

static void c_area_create(fz *f)
{
    tt_world *w = fz_world_pick(f);
    tt_area_def d = tt_area_def_default();
    d.count = fz_count(f, 3, 24);
    tt_particle *ps = d.count <= 70000 && fz_chance(f, 97) ? fz_particles(f, d.count) : NULL;
    d.particles = ps;
    d.use_current = fz_chance(f, 60);
    d.area = fz_real(f, -10, 10);
    d.pressure = fz_real(f, 0.5, 2);
    d.stiffness = fz_stiffness(f);
    d.compliance = fz_compliance(f);
    fz_log(f, "tt_area_create(%s, &(tt_area_def){%s, %u, area %s, use_current %d, pressure %s, %s, %s})", fz_wn(f, w),
           ps ? "particles" : "NULL", d.count, fz_d(d.area), d.use_current, fz_d(d.pressure), fz_d(d.stiffness),
           fz_d(d.compliance));
    FZ_HIT(f, tt_area_create);
    created(f, tt_area_create(w, fz_chance(f, 2) ? NULL : &d));
    free(ps);
}

static void c_collinear_create(fz *f)
{
    tt_world *w = fz_world_pick(f);
    tt_collinear_def d = tt_collinear_def_default();
    fz_h a, b, c;
    three(f, &a, &b, &c);
    d.a = FZ_P(a);
    d.b = FZ_P(b);
    d.c = FZ_P(c);
    d.stiffness = fz_stiffness(f);
    d.compliance = fz_compliance(f);
    fz_log(f, "tt_collinear_create(%s, &(tt_collinear_def){%s, %s, %s, %s, %s})", fz_wn(f, w), fz_hn(a, PK),
           fz_hn(b, PK), fz_hn(c, PK), fz_d(d.stiffness), fz_d(d.compliance));
    FZ_HIT(f, tt_collinear_create);
    created(f, tt_collinear_create(w, fz_chance(f, 2) ? NULL : &d));
}

static void c_constraint_destroy(fz *f)
{
    tt_world *w = fz_world_pick(f);
    fz_h h = fz_handle(f, CK);
    fz_log(f, "tt_constraint_destroy(%s, %s)", fz_wn(f, w), fz_hn(h, CK));
    FZ_HIT(f, tt_constraint_destroy);
    fz_res(f, tt_constraint_destroy(w, FZ_C(h)));
    if (!f->failed) fz_forget(f, CK, h);
}

static void c_constraint_is_valid(fz *f)
{
    tt_world *w = fz_world_any(f);
    fz_h h = fz_handle(f, CK);
    fz_log(f, "tt_constraint_is_valid(%s, %s)", fz_wn(f, w), fz_hn(h, CK));
    FZ_HIT(f, tt_constraint_is_valid);
    bool ok = tt_constraint_is_valid(w, FZ_C(h));
    fz_log_more(f, " -> %s", ok ? "true" : "false");
    f->failed = !ok;
    if (!w && ok) fz_fail(f, "tt_constraint_is_valid said true for a NULL world");
    if (!w) f->must_fail = false;
}

#define GET_C(fn, T, check)                                                                          \
    static void c_##fn(fz *f)                                                                        \
    {                                                                                                \
        tt_world *w = fz_world_pick(f);                                                              \
        f->readonly = true;                                                                          \
        fz_h h = fz_handle(f, CK);                                                                   \
        T out;                                                                                       \
        bool null_out = fz_chance(f, 4);                                                             \
        fz_log(f, #fn "(%s, %s, %s)", fz_wn(f, w), fz_hn(h, CK), null_out ? "NULL" : "&out");        \
        FZ_HIT(f, fn);                                                                               \
        fz_res(f, fn(w, FZ_C(h), null_out ? NULL : &out));                                           \
        if (!f->failed && null_out) fz_fail(f, #fn " accepted a NULL out");                          \
        if (!f->failed) check;                                                                       \
    }
#define SET_C(fn, T, draw, show)                                                                     \
    static void c_##fn(fz *f)                                                                        \
    {                                                                                                \
        tt_world *w = fz_world_pick(f);                                                              \
        fz_h h = fz_handle(f, CK);                                                                   \
        T v = draw;                                                                                  \
        fz_log(f, #fn "(%s, %s, %s)", fz_wn(f, w), fz_hn(h, CK), show);                              \
        FZ_HIT(f, fn);                                                                               \
        fz_res(f, fn(w, FZ_C(h), v));                                                                \
    }
GET_C(tt_constraint_get_kind, tt_constraint_kind,
      if (out < TT_CONSTRAINT_DISTANCE || out > TT_CONSTRAINT_COLLINEAR) fz_fail(f, "kind %d", (int)out))
GET_C(tt_constraint_get_error, double, fz_finite(f, out, "a constraint's error"))
GET_C(tt_distance_get_length, double, fz_finite(f, out, "a distance's length"))
GET_C(tt_pin_get_anchor, tt_vec2, fz_finite_vec(f, out, "a pin's anchor"))
GET_C(tt_constraint_get_max_rate, double, fz_finite(f, out, "a max rate"))
SET_C(tt_constraint_set_stiffness, double, fz_stiffness(f), fz_d(v))
SET_C(tt_constraint_set_compliance, double, fz_compliance(f), fz_d(v))
SET_C(tt_distance_set_length, double, fz_real(f, 0, 10), fz_d(v))
SET_C(tt_pin_set_anchor, tt_vec2, fz_point(f), fz_v(v))
SET_C(tt_constraint_set_max_rate, double, fz_chance(f, 30) ? 0.0 : fz_real(f, 0, 10), fz_d(v))

static void c_constraint_get_particles(fz *f)
{
    tt_world *w = fz_world_pick(f);
    f->readonly = true;
    fz_h h = fz_handle(f, CK);
    uint32_t cap, count = 0;
    tt_particle *out = fz_buffer(f, &cap, 8, sizeof *out);
    bool null_count = fz_chance(f, 4);
    fz_log(f, "tt_constraint_get_particles(%s, %s, %s, %u, %s)", fz_wn(f, w), fz_hn(h, CK), out ? "out" : "NULL", cap,
           null_count ? "NULL" : "&count");
    FZ_HIT(f, tt_constraint_get_particles);
    fz_res(f, tt_constraint_get_particles(w, FZ_C(h), out, cap, null_count ? NULL : &count));
    for (uint32_t i = 0; !f->failed && out && i < count && i < cap; i++) fz_remember(f, PK, FZ_H(out[i]));
    free(out);
}

static void c_bounds_set_box(fz *f)
{
    tt_world *w = fz_world_pick(f);
    fz_h h = fz_handle(f, CK);
    tt_vec2 lo, hi;
    box(f, &lo, &hi);
    fz_log(f, "tt_bounds_set_box(%s, %s, %s, %s)", fz_wn(f, w), fz_hn(h, CK), fz_v(lo), fz_v(hi));
    FZ_HIT(f, tt_bounds_set_box);
    fz_res(f, tt_bounds_set_box(w, FZ_C(h), lo, hi));
}

static void c_world_constraint_count(fz *f)
{
    tt_world *w = fz_world_any(f);
    fz_log(f, "tt_world_constraint_count(%s)", fz_wn(f, w));
    FZ_HIT(f, tt_world_constraint_count);
    uint32_t n = tt_world_constraint_count(w);
    fz_log_more(f, " -> %u", n);
    if (!w && n) fz_fail(f, "tt_world_constraint_count(NULL) is %u", n);
}

static void c_world_read_constraint_lines(fz *f)
{
    tt_world *w = fz_world_any(f);
    uint32_t cap, all = w ? tt_world_read_constraint_lines(w, NULL, 0) : 0;
    double *xy = fz_buffer(f, &cap, all, 4 * sizeof *xy);
    fz_log(f, "tt_world_read_constraint_lines(%s, %s, %u)", fz_wn(f, w), xy ? "xy" : "NULL", cap);
    FZ_HIT(f, tt_world_read_constraint_lines);
    uint32_t n = tt_world_read_constraint_lines(w, xy, cap);
    fz_log_more(f, " -> %u", n);
    if (n != all) fz_fail(f, "tt_world_read_constraint_lines says %u, then %u", all, n);
    for (uint32_t i = 0; xy && i < 4 * n && i < 4 * cap; i++) fz_finite(f, xy[i], "a constraint line");
    free(xy);
}

static void c_world_get_break_events(fz *f)
{
    tt_world *w = fz_world_pick(f);
    f->readonly = true;
    const tt_break_event *ev = NULL;
    uint32_t n = 0;
    bool null_ev = fz_chance(f, 4), null_n = fz_chance(f, 4);
    fz_log(f, "tt_world_get_break_events(%s, %s, %s)", fz_wn(f, w), null_ev ? "NULL" : "&events", null_n ? "NULL" : "&n");
    FZ_HIT(f, tt_world_get_break_events);
    fz_res(f, tt_world_get_break_events(w, null_ev ? NULL : &ev, null_n ? NULL : &n));
    for (uint32_t i = 0; !f->failed && ev && !null_n && i < n; i++) {
        fz_finite(f, ev[i].strain, "a break event's strain");
        fz_forget(f, CK, FZ_H(ev[i].constraint)); /* a torn link is removed: stale from now on */
    }
}

const fz_entry fz_constraint_entries[] = {
    { "tt_distance_def_default", c_distance_def_default, 1 },
    { "tt_pin_def_default", c_pin_def_default, 1 },
    { "tt_bounds_def_default", c_bounds_def_default, 1 },
    { "tt_angle_def_default", c_angle_def_default, 1 },
    { "tt_area_def_default", c_area_def_default, 1 },
    { "tt_collinear_def_default", c_collinear_def_default, 1 },
    { "tt_distance_create", c_distance_create, 10 },
    { "tt_pin_create", c_pin_create, 4 },
    { "tt_bounds_create", c_bounds_create, 3 },
    { "tt_angle_create", c_angle_create, 3 },
    { "tt_area_create", c_area_create, 3 },
    { "tt_collinear_create", c_collinear_create, 3 },
    { "tt_constraint_destroy", c_constraint_destroy, 3 },
    { "tt_constraint_is_valid", c_constraint_is_valid, 1 },
    { "tt_constraint_get_kind", c_tt_constraint_get_kind, 1 },
    { "tt_constraint_get_error", c_tt_constraint_get_error, 2 },
    { "tt_constraint_get_particles", c_constraint_get_particles, 2 },
    { "tt_constraint_set_stiffness", c_tt_constraint_set_stiffness, 2 },
    { "tt_constraint_set_compliance", c_tt_constraint_set_compliance, 2 },
    { "tt_distance_set_length", c_tt_distance_set_length, 3 },
    { "tt_distance_get_length", c_tt_distance_get_length, 1 },
    { "tt_pin_set_anchor", c_tt_pin_set_anchor, 3 },
    { "tt_pin_get_anchor", c_tt_pin_get_anchor, 1 },
    { "tt_constraint_set_max_rate", c_tt_constraint_set_max_rate, 2 },
    { "tt_constraint_get_max_rate", c_tt_constraint_get_max_rate, 1 },
    { "tt_bounds_set_box", c_bounds_set_box, 2 },
    { "tt_world_constraint_count", c_world_constraint_count, 1 },
    { "tt_world_read_constraint_lines", c_world_read_constraint_lines, 2 },
    { "tt_world_get_break_events", c_world_get_break_events, 2 },
    { NULL, NULL, 0 },
};
