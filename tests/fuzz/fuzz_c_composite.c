/* tests/fuzz/fuzz_c_composite.c — wrappers of tether/composite.h: ropes
 * (often flat and long, so their particles share a y, as in finding 1),
 * cloth that tears, ragdolls, soft bodies, lattices from rectangles and
 * polygons, each from a def with garbage fields now and then; the new
 * particles and constraints join the handles later calls draw from. */
#include "fuzz_c.h"

#include <math.h>
#include <stdlib.h>

#define PK TT_KIND_PARTICLE
#define CK TT_KIND_CONSTRAINT
#define OK_ TT_KIND_COMPOSITE

static tt_composite_common common(fz *f)
{
    tt_composite_common c = { 1.0, 0.0, 1.0, 0.0, false };
    c.mass = fz_chance(f, 60) ? 1.0 : fz_real(f, TT_MIN_MASS, 10);
    c.radius = fz_chance(f, 40) ? 0.0 : fz_real(f, 0, 0.5);
    c.stiffness = fz_stiffness(f);
    c.compliance = fz_compliance(f);
    c.collide = fz_chance(f, 30);
    return c;
}

/* The composite's particles and constraints become drawable handles. */
static void adopt(fz *f, tt_world *w, tt_composite c)
{
    fz_hres(f, OK_, FZ_H(c));
    if (f->failed || !w) return;
    uint32_t n = 0;
    tt_composite_get_particles(w, c, NULL, 0, &n);
    tt_particle *ps = malloc((n ? n : 1) * sizeof *ps);
    if (!ps) abort();
    tt_composite_get_particles(w, c, ps, n, &n);
    for (uint32_t i = 0; i < n; i += 1 + n / 64) fz_remember(f, PK, FZ_H(ps[i]));
    free(ps);
    tt_composite_get_constraints(w, c, NULL, 0, &n);
    tt_constraint *cs = malloc((n ? n : 1) * sizeof *cs);
    if (!cs) abort();
    tt_composite_get_constraints(w, c, cs, n, &n);
    for (uint32_t i = 0; i < n; i += 1 + n / 64) fz_remember(f, CK, FZ_H(cs[i]));
    free(cs);
}

#define DEF_DEFAULT(kind, check)                                                                     \
    static void c_##kind##_def_default(fz *f)                                                        \
    {                                                                                                \
        fz_log(f, "tt_" #kind "_def_default()");                                                     \
        FZ_HIT(f, tt_##kind##_def_default);                                                          \
        tt_##kind##_def d = tt_##kind##_def_default();                                               \
        if (!(check)) fz_fail(f, "tt_" #kind "_def_default is not the documented default");          \
    }
DEF_DEFAULT(rope, d.segments == 10 && d.pin_start && d.common.mass == 1.0)
DEF_DEFAULT(cloth, d.columns == 16 && d.rows == 16 && d.pin_top_corners)
DEF_DEFAULT(ragdoll, d.height == 1.8 && d.limits)
DEF_DEFAULT(soft_body, d.segments == 16 && d.ring_radius == 1.0)
DEF_DEFAULT(lattice, d.columns == 2 && d.rows == 2 && !d.points)

static void c_rope_create(fz *f)
{
    tt_world *w = fz_world_pick(f);
    tt_rope_def d = tt_rope_def_default();
    d.common = common(f);
    d.start = fz_point(f);
    d.finish = (tt_vec2){ d.start.x + fz_real(f, -10, 10), d.start.y + fz_real(f, -10, 10) };
    if (fz_chance(f, 30)) d.finish = (tt_vec2){ d.start.x + fz_real(f, 1, 2000), d.start.y }; /* flat: one shared y */
    if (fz_chance(f, 5)) d.finish = fz_point(f);
    d.segments = fz_count(f, 1, 120);
    d.pin_start = fz_chance(f, 50);
    d.pin_finish = fz_chance(f, 20);
    d.slack = fz_chance(f, 30);
    d.break_strain = fz_chance(f, 70) ? 0.0 : fz_real(f, 0, 0.5);
    fz_log(f, "tt_rope_create(%s, &(tt_rope_def){mass %s, radius %s, stiffness %s, compliance %s, collide %d, %s, %s, "
              "segments %u, pins %d %d, slack %d, break %s})", fz_wn(f, w), fz_d(d.common.mass), fz_d(d.common.radius),
           fz_d(d.common.stiffness), fz_d(d.common.compliance), d.common.collide, fz_v(d.start), fz_v(d.finish),
           d.segments, d.pin_start, d.pin_finish, d.slack, fz_d(d.break_strain));
    FZ_HIT(f, tt_rope_create);
    adopt(f, w, tt_rope_create(w, fz_chance(f, 2) ? NULL : &d));
}

static void c_cloth_create(fz *f)
{
    tt_world *w = fz_world_pick(f);
    tt_cloth_def d = tt_cloth_def_default();
    d.common = common(f);
    d.origin = fz_point(f);
    d.width = fz_real(f, 0.1, 10);
    d.height = fz_real(f, 0.1, 10);
    d.columns = fz_count(f, 2, 24);
    d.rows = fz_count(f, 2, 24);
    d.shear_stiffness = fz_chance(f, 30) ? 0.0 : fz_stiffness(f);
    d.bend_stiffness = fz_chance(f, 30) ? 0.0 : fz_stiffness(f);
    d.pin_top_corners = fz_chance(f, 70);
    d.pin_top_row = fz_chance(f, 20);
    d.break_strain = fz_chance(f, 60) ? 0.0 : fz_real(f, 0.01, 0.5); /* tearing */
    d.long_range = fz_chance(f, 25); /* refused with tearing */
    fz_log(f, "tt_cloth_create(%s, &(tt_cloth_def){mass %s, radius %s, stiffness %s, compliance %s, %s, %s x %s, "
              "%u x %u, shear %s, bend %s, pins %d %d, break %s, long_range %d})", fz_wn(f, w), fz_d(d.common.mass),
           fz_d(d.common.radius), fz_d(d.common.stiffness), fz_d(d.common.compliance), fz_v(d.origin), fz_d(d.width),
           fz_d(d.height), d.columns, d.rows, fz_d(d.shear_stiffness), fz_d(d.bend_stiffness), d.pin_top_corners,
           d.pin_top_row, fz_d(d.break_strain), d.long_range);
    FZ_HIT(f, tt_cloth_create);
    adopt(f, w, tt_cloth_create(w, fz_chance(f, 2) ? NULL : &d));
}

static void c_ragdoll_create(fz *f)
{
    tt_world *w = fz_world_pick(f);
    tt_ragdoll_def d = tt_ragdoll_def_default();
    d.common = common(f);
    d.position = fz_point(f);
    d.height = fz_real(f, 0.1, 3);
    d.limits = fz_chance(f, 70);
    fz_log(f, "tt_ragdoll_create(%s, &(tt_ragdoll_def){mass %s, radius %s, stiffness %s, compliance %s, %s, height %s, "
              "limits %d})", fz_wn(f, w), fz_d(d.common.mass), fz_d(d.common.radius), fz_d(d.common.stiffness),
           fz_d(d.common.compliance), fz_v(d.position), fz_d(d.height), d.limits);
    FZ_HIT(f, tt_ragdoll_create);
    adopt(f, w, tt_ragdoll_create(w, fz_chance(f, 2) ? NULL : &d));
}

static void c_soft_body_create(fz *f)
{
    tt_world *w = fz_world_pick(f);
    tt_soft_body_def d = tt_soft_body_def_default();
    d.common = common(f);
    d.center = fz_point(f);
    d.ring_radius = fz_real(f, 0.1, 3);
    d.segments = fz_count(f, 3, 40);
    if (d.segments == 65536) d.segments++; /* the largest ring takes a second to make (its area checks n² pairs) */
    d.pressure = fz_real(f, 0.5, 2);
    d.area_stiffness = fz_stiffness(f);
    d.area_compliance = fz_compliance(f);
    fz_log(f, "tt_soft_body_create(%s, &(tt_soft_body_def){mass %s, radius %s, stiffness %s, compliance %s, %s, ring %s, "
              "segments %u, pressure %s, area %s %s})", fz_wn(f, w), fz_d(d.common.mass), fz_d(d.common.radius),
           fz_d(d.common.stiffness), fz_d(d.common.compliance), fz_v(d.center), fz_d(d.ring_radius), d.segments,
           fz_d(d.pressure), fz_d(d.area_stiffness), fz_d(d.area_compliance));
    FZ_HIT(f, tt_soft_body_create);
    adopt(f, w, tt_soft_body_create(w, fz_chance(f, 2) ? NULL : &d));
}

/* A polygon: regular and convex most of the time (any winding), now and
 * then with a repeated point or three on a line; n points into pts. */
uint32_t fz_polygon(fz *f, tt_vec2 *pts, uint32_t max)
{
    uint32_t n = fz_count(f, 3, 12);
    if (n > max) n = max;
    tt_vec2 c = fz_chance(f, 70) ? fz_vec(f, -20, 20) : fz_point(f);
    double r = fz_real(f, 0.1, 5), turn = fz_chance(f, 50) ? 1.0 : -1.0, a0 = fz_unit(f) * 6.283185307179586;
    for (uint32_t i = 0; i < n; i++) {
        double a = a0 + turn * 6.283185307179586 * i / n;
        pts[i] = (tt_vec2){ c.x + r * cos(a), c.y + r * sin(a) };
    }
    if (n >= 3 && fz_chance(f, 5)) pts[1] = pts[0];
    if (n >= 3 && fz_chance(f, 5)) pts[1] = (tt_vec2){ (pts[0].x + pts[2].x) / 2, (pts[0].y + pts[2].y) / 2 };
    if (n >= 1 && fz_chance(f, 3)) pts[fz_below(f, n)] = fz_point(f);
    return n;
}

static void c_lattice_create(fz *f)
{
    tt_world *w = fz_world_pick(f);
    tt_lattice_def d = tt_lattice_def_default();
    tt_vec2 pts[80] = {{0, 0}}; /* a count past the points made reads zeros, not the stack: a seed replays */
    d.common = common(f);
    d.center = fz_point(f);
    d.width = fz_real(f, 0.1, 5);
    d.height = fz_real(f, 0.1, 5);
    d.angle = fz_real(f, -4, 4);
    d.columns = fz_count(f, 2, 12);
    d.rows = fz_count(f, 2, 12);
    if (fz_chance(f, 25)) {
        d.point_count = fz_polygon(f, pts, 80);
        d.points = fz_chance(f, 97) ? pts : NULL;
        if (fz_chance(f, 5)) d.point_count = fz_count(f, 0, 80);
        if (d.point_count > 80 && d.points) d.point_count = 80;
    }
    fz_log(f, "tt_lattice_create(%s, &(tt_lattice_def){mass %s, radius %s, stiffness %s, compliance %s, %s, %s x %s, "
              "angle %s, %u x %u, points %s, %u})", fz_wn(f, w), fz_d(d.common.mass), fz_d(d.common.radius),
           fz_d(d.common.stiffness), fz_d(d.common.compliance), fz_v(d.center), fz_d(d.width), fz_d(d.height),
           fz_d(d.angle), d.columns, d.rows, d.points ? "pts" : "NULL", d.point_count);
    FZ_HIT(f, tt_lattice_create);
    adopt(f, w, tt_lattice_create(w, fz_chance(f, 2) ? NULL : &d));
}

static void c_composite_destroy(fz *f)
{
    tt_world *w = fz_world_pick(f);
    fz_h h = fz_handle(f, OK_);
    fz_log(f, "tt_composite_destroy(%s, %s)", fz_wn(f, w), fz_hn(h, OK_));
    FZ_HIT(f, tt_composite_destroy);
    fz_res(f, tt_composite_destroy(w, FZ_CO(h)));
    if (!f->failed) fz_forget(f, OK_, h);
}

static void c_composite_is_valid(fz *f)
{
    tt_world *w = fz_world_any(f);
    fz_h h = fz_handle(f, OK_);
    fz_log(f, "tt_composite_is_valid(%s, %s)", fz_wn(f, w), fz_hn(h, OK_));
    FZ_HIT(f, tt_composite_is_valid);
    bool ok = tt_composite_is_valid(w, FZ_CO(h));
    fz_log_more(f, " -> %s", ok ? "true" : "false");
    f->failed = !ok;
    if (!w && ok) fz_fail(f, "tt_composite_is_valid said true for a NULL world");
    if (!w) f->must_fail = false;
}

#define GET_MEMBERS(fn, K, T)                                                                        \
    static void c_##fn(fz *f)                                                                        \
    {                                                                                                \
        tt_world *w = fz_world_pick(f);                                                              \
        f->readonly = true;                                                                          \
        fz_h h = fz_handle(f, OK_);                                                                  \
        uint32_t cap, count = 0;                                                                     \
        T *out = fz_buffer(f, &cap, 64, sizeof *out);                                                \
        bool null_count = fz_chance(f, 4);                                                           \
        fz_log(f, #fn "(%s, %s, %s, %u, %s)", fz_wn(f, w), fz_hn(h, OK_), out ? "out" : "NULL", cap, \
               null_count ? "NULL" : "&count");                                                      \
        FZ_HIT(f, fn);                                                                               \
        fz_res(f, fn(w, FZ_CO(h), out, cap, null_count ? NULL : &count));                            \
        for (uint32_t i = 0; !f->failed && out && i < count && i < cap; i++) fz_remember(f, K, FZ_H(out[i])); \
        free(out);                                                                                   \
    }
GET_MEMBERS(tt_composite_get_particles, PK, tt_particle)
GET_MEMBERS(tt_composite_get_constraints, CK, tt_constraint)

#define GET_CO(fn, T, check)                                                                         \
    static void c_##fn(fz *f)                                                                        \
    {                                                                                                \
        tt_world *w = fz_world_pick(f);                                                              \
        f->readonly = true;                                                                          \
        fz_h h = fz_handle(f, OK_);                                                                  \
        T out;                                                                                       \
        bool null_out = fz_chance(f, 4);                                                             \
        fz_log(f, #fn "(%s, %s, %s)", fz_wn(f, w), fz_hn(h, OK_), null_out ? "NULL" : "&out");       \
        FZ_HIT(f, fn);                                                                               \
        fz_res(f, fn(w, FZ_CO(h), null_out ? NULL : &out));                                          \
        if (!f->failed && null_out) fz_fail(f, #fn " accepted a NULL out");                          \
        if (!f->failed) check;                                                                       \
    }
GET_CO(tt_composite_get_center, tt_vec2, fz_finite_vec(f, out, "a composite's centre"))
GET_CO(tt_composite_get_angle, double, fz_finite(f, out, "a composite's angle"))

static void c_world_composite_count(fz *f)
{
    tt_world *w = fz_world_any(f);
    fz_log(f, "tt_world_composite_count(%s)", fz_wn(f, w));
    FZ_HIT(f, tt_world_composite_count);
    uint32_t n = tt_world_composite_count(w);
    fz_log_more(f, " -> %u", n);
    if (!w && n) fz_fail(f, "tt_world_composite_count(NULL) is %u", n);
}

const fz_entry fz_composite_entries[] = {
    { "tt_rope_def_default", c_rope_def_default, 1 },
    { "tt_cloth_def_default", c_cloth_def_default, 1 },
    { "tt_ragdoll_def_default", c_ragdoll_def_default, 1 },
    { "tt_soft_body_def_default", c_soft_body_def_default, 1 },
    { "tt_lattice_def_default", c_lattice_def_default, 1 },
    { "tt_rope_create", c_rope_create, 4 },
    { "tt_cloth_create", c_cloth_create, 3 },
    { "tt_ragdoll_create", c_ragdoll_create, 3 },
    { "tt_soft_body_create", c_soft_body_create, 3 },
    { "tt_lattice_create", c_lattice_create, 3 },
    { "tt_composite_destroy", c_composite_destroy, 2 },
    { "tt_composite_is_valid", c_composite_is_valid, 1 },
    { "tt_composite_get_particles", c_tt_composite_get_particles, 2 },
    { "tt_composite_get_constraints", c_tt_composite_get_constraints, 2 },
    { "tt_composite_get_center", c_tt_composite_get_center, 1 },
    { "tt_composite_get_angle", c_tt_composite_get_angle, 1 },
    { "tt_world_composite_count", c_world_composite_count, 1 },
    { NULL, NULL, 0 },
};
