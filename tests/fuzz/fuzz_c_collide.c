/* tests/fuzz/fuzz_c_collide.c — wrappers of tether/collide.h: shapes of
 * every type from garbage defs, collision settings with tiny and huge cells
 * (finding 1 was a grid of cell_size 1e-3), every event kind, materials,
 * bullets, pair switches, rays and queries with zero and huge capacities. */
#include "fuzz_c.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>

#define PK TT_KIND_PARTICLE
#define SHK TT_KIND_SHAPE


static uint32_t chain(fz *f, tt_vec2 *pts, uint32_t max)
{
    uint32_t n = fz_count(f, 2, 40);
    if (n > max) n = max;
    tt_vec2 p = fz_vec(f, -30, 30);
    for (uint32_t i = 0; i < n; i++) {
        pts[i] = p;
        p.x += fz_real(f, 0.01, 3);
        p.y += fz_real(f, -1, 1);
    }
    if (n >= 2 && fz_chance(f, 5)) pts[1] = pts[0];
    return n;
}

static tt_shape_def shape_def(fz *f, tt_vec2 *pts, uint32_t max)
{
    tt_shape_def d = tt_shape_def_default();
    d.type = (tt_shape_type)fz_enum(f, TT_SHAPE_TYPE_COUNT);
    d.position = fz_chance(f, 50) ? (tt_vec2){ 0, 0 } : fz_point(f);
    d.angle = fz_chance(f, 60) ? 0.0 : fz_real(f, -4, 4);
    d.a = fz_vec(f, -30, 30);
    d.b = (tt_vec2){ d.a.x + fz_real(f, -20, 20), d.a.y + fz_real(f, -20, 20) };
    if (d.type == TT_SHAPE_AABB && fz_chance(f, 80)) d.b = (tt_vec2){ d.a.x + fz_real(f, 0.1, 20), d.a.y + fz_real(f, 0.1, 20) };
    d.half_extents = fz_vec(f, 0.05, 5);
    d.radius = fz_real(f, 0.05, 3);
    if (d.type == TT_SHAPE_CHAIN) d.count = chain(f, pts, max);
    else if (d.type == TT_SHAPE_POLYGON) d.count = fz_polygon(f, pts, max);
    else d.count = fz_chance(f, 5) ? fz_count(f, 0, 10) : 0;
    d.points = fz_chance(f, 97) ? pts : NULL;
    if (fz_chance(f, 3)) d.count = fz_count(f, 0, max + 1);
    if (d.count > max && d.points) d.count = max; /* a lying count is beyond any check */
    d.loop = fz_chance(f, 30);
    d.restitution = fz_real(f, 0, 1);
    d.friction_static = fz_real(f, 0, 1);
    d.friction_kinetic = fz_real(f, 0, 1);
    if (fz_chance(f, 20)) d.category = fz_bits16(f);
    if (fz_chance(f, 20)) d.mask = fz_bits16(f);
    d.sensor = fz_chance(f, 10);
    d.user = fz_rand(f);
    return d;
}

static void c_shape_def_default(fz *f)
{
    fz_log(f, "tt_shape_def_default()");
    FZ_HIT(f, tt_shape_def_default);
    tt_shape_def d = tt_shape_def_default();
    if (d.type != TT_SHAPE_SEGMENT || d.radius != 0.5 || d.mask != 0xFFFF) fz_fail(f, "tt_shape_def_default is not the documented default");
}

static void c_shape_create(fz *f)
{
    tt_world *w = fz_world_pick(f);
    tt_vec2 pts[80] = {{0, 0}}; /* a count past the points made reads zeros, not the stack: a seed replays */
    tt_shape_def d = shape_def(f, pts, 80);
    fz_log(f, "tt_shape_create(%s, &(tt_shape_def){type %d, %s, angle %s, a %s, b %s, half %s, radius %s, points %s, %u, "
              "loop %d, material %s %s %s, filter %#x/%#x, sensor %d})", fz_wn(f, w), (int)d.type, fz_v(d.position),
           fz_d(d.angle), fz_v(d.a), fz_v(d.b), fz_v(d.half_extents), fz_d(d.radius), d.points ? "pts" : "NULL",
           d.count, d.loop, fz_d(d.restitution), fz_d(d.friction_static), fz_d(d.friction_kinetic), d.category,
           d.mask, d.sensor);
    FZ_HIT(f, tt_shape_create);
    fz_hres(f, SHK, FZ_H(tt_shape_create(w, fz_chance(f, 2) ? NULL : &d)));
}

static void c_shape_destroy(fz *f)
{
    tt_world *w = fz_world_pick(f);
    fz_h h = fz_handle(f, SHK);
    fz_log(f, "tt_shape_destroy(%s, %s)", fz_wn(f, w), fz_hn(h, SHK));
    FZ_HIT(f, tt_shape_destroy);
    fz_res(f, tt_shape_destroy(w, FZ_SH(h)));
    if (!f->failed) fz_forget(f, SHK, h);
}

static void c_shape_is_valid(fz *f)
{
    tt_world *w = fz_world_any(f);
    fz_h h = fz_handle(f, SHK);
    fz_log(f, "tt_shape_is_valid(%s, %s)", fz_wn(f, w), fz_hn(h, SHK));
    FZ_HIT(f, tt_shape_is_valid);
    bool ok = tt_shape_is_valid(w, FZ_SH(h));
    fz_log_more(f, " -> %s", ok ? "true" : "false");
    f->failed = !ok;
    if (!w && ok) fz_fail(f, "tt_shape_is_valid said true for a NULL world");
    if (!w) f->must_fail = false;
}

/* A call on one handle: pick, draw, log, call; OUT is true for reads. */
#define ON_HANDLE(name, K, OUT, draw, show, call)                                                    \
    static void c_##name(fz *f)                                                                      \
    {                                                                                                \
        tt_world *w = fz_world_pick(f);                                                              \
        f->readonly = OUT;                                                                           \
        fz_h h = fz_handle(f, K);                                                                    \
        draw;                                                                                        \
        fz_log(f, #name "(%s, %s, %s)", fz_wn(f, w), fz_hn(h, K), show);                             \
        FZ_HIT(f, name);                                                                             \
        fz_res(f, call);                                                                             \
    }
#define OUTP(p) (fz_chance(f, 4) ? NULL : (p))

ON_HANDLE(tt_shape_set_transform, SHK, false, tt_vec2 p = fz_point(f); double a = fz_real(f, -4, 4),
          fz_v(p), tt_shape_set_transform(w, FZ_SH(h), p, fz_chance(f, 50) ? 0.0 : a))
ON_HANDLE(tt_shape_get_transform, SHK, true, tt_vec2 p; double a; tt_vec2 *pp = OUTP(&p); double *ap = OUTP(&a),
          "&p, &a", tt_shape_get_transform(w, FZ_SH(h), pp, ap))
ON_HANDLE(tt_shape_set_material, SHK, false, double r = fz_real(f, 0, 1); double s = fz_real(f, 0, 1),
          fz_d(r), tt_shape_set_material(w, FZ_SH(h), r, s, fz_real(f, 0, 1)))
ON_HANDLE(tt_shape_set_filter, SHK, false, uint16_t c = fz_bits16(f); uint16_t m = fz_bits16(f),
          fz_u(c), tt_shape_set_filter(w, FZ_SH(h), c, m))
ON_HANDLE(tt_shape_set_sensor, SHK, false, bool s = fz_chance(f, 50), s ? "true" : "false",
          tt_shape_set_sensor(w, FZ_SH(h), s))
ON_HANDLE(tt_shape_get_type, SHK, true, tt_shape_type t, "&type", tt_shape_get_type(w, FZ_SH(h), OUTP(&t)))
ON_HANDLE(tt_shape_get_user, SHK, true, uint64_t u, "&user", tt_shape_get_user(w, FZ_SH(h), OUTP(&u)))
ON_HANDLE(tt_shape_get_sensor, SHK, true, bool s, "&sensor", tt_shape_get_sensor(w, FZ_SH(h), OUTP(&s)))
ON_HANDLE(tt_shape_get_aabb, SHK, true, tt_vec2 lo; tt_vec2 hi, "&lo, &hi",
          tt_shape_get_aabb(w, FZ_SH(h), OUTP(&lo), OUTP(&hi)))
ON_HANDLE(tt_particle_set_material, PK, false, double r = fz_real(f, 0, 1); double s = fz_real(f, 0, 1),
          fz_d(r), tt_particle_set_material(w, FZ_P(h), r, s, fz_real(f, 0, 1)))
ON_HANDLE(tt_particle_get_material, PK, true, double r; double s; double k, "&r, &s, &k",
          tt_particle_get_material(w, FZ_P(h), OUTP(&r), OUTP(&s), OUTP(&k)))
ON_HANDLE(tt_particle_set_bullet, PK, false, bool b = fz_chance(f, 50), b ? "true" : "false",
          tt_particle_set_bullet(w, FZ_P(h), b))
ON_HANDLE(tt_particle_get_bullet, PK, true, bool b, "&bullet", tt_particle_get_bullet(w, FZ_P(h), OUTP(&b)))

static void c_shape_get_outline(fz *f)
{
    tt_world *w = fz_world_pick(f);
    f->readonly = true;
    fz_h h = fz_handle(f, SHK);
    uint32_t cap, count = 0;
    bool closed;
    tt_vec2 *out = fz_buffer(f, &cap, 40, sizeof *out);
    bool null_count = fz_chance(f, 4);
    fz_log(f, "tt_shape_get_outline(%s, %s, %s, %u, %s, &closed)", fz_wn(f, w), fz_hn(h, SHK), out ? "out" : "NULL", cap,
           null_count ? "NULL" : "&count");
    FZ_HIT(f, tt_shape_get_outline);
    fz_res(f, tt_shape_get_outline(w, FZ_SH(h), out, cap, null_count ? NULL : &count, fz_chance(f, 4) ? NULL : &closed));
    for (uint32_t i = 0; !f->failed && out && i < count && i < cap; i++) fz_finite_vec(f, out[i], "an outline point");
    free(out);
}

static void c_world_shape_count(fz *f)
{
    tt_world *w = fz_world_any(f);
    fz_log(f, "tt_world_shape_count(%s)", fz_wn(f, w));
    FZ_HIT(f, tt_world_shape_count);
    uint32_t n = tt_world_shape_count(w);
    fz_log_more(f, " -> %u", n);
    if (!w && n) fz_fail(f, "tt_world_shape_count(NULL) is %u", n);
}

static void c_world_list_shapes(fz *f)
{
    tt_world *w = fz_world_any(f);
    uint32_t cap, live = w ? tt_world_shape_count(w) : 0;
    tt_shape *out = fz_buffer(f, &cap, live, sizeof *out);
    fz_log(f, "tt_world_list_shapes(%s, %s, %u)", fz_wn(f, w), out ? "out" : "NULL", cap);
    FZ_HIT(f, tt_world_list_shapes);
    uint32_t n = tt_world_list_shapes(w, out, cap);
    fz_log_more(f, " -> %u", n);
    if (n != live) fz_fail(f, "tt_world_list_shapes says %u, the count says %u", n, live);
    for (uint32_t i = 0; out && i < n && i < cap; i++) fz_remember(f, SHK, FZ_H(out[i]));
    free(out);
}

static void c_shape_type_name(fz *f)
{
    tt_shape_type t = (tt_shape_type)fz_enum(f, TT_SHAPE_TYPE_COUNT);
    fz_log(f, "tt_shape_type_name(%d)", (int)t);
    FZ_HIT(f, tt_shape_type_name);
    if (!tt_shape_type_name(t)) fz_fail(f, "tt_shape_type_name returned NULL");
}

static void c_collision_settings_default(fz *f)
{
    fz_log(f, "tt_collision_settings_default()");
    FZ_HIT(f, tt_collision_settings_default);
    tt_collision_settings s = tt_collision_settings_default();
    if (!s.particles || s.cell_size != 0.0 || s.events != 0) fz_fail(f, "tt_collision_settings_default is not the documented default");
}

/* Cells: auto most often, then plausible, then the tiny ones that broke the grid. */
static double cell_size(fz *f)
{
    static const double tiny[] = { 1e-3, 1e-300, 4.9e-324, 1e-12, 1e-6, DBL_MIN, 1e6 };
    unsigned r = fz_below(f, 100);
    if (r < 50) return 0.0;
    if (r < 75) return fz_real(f, 1e-3, 5);
    if (r < 95) return tiny[fz_below(f, sizeof tiny / sizeof tiny[0])];
    return fz_nasty(f);
}

static void c_world_set_collision(fz *f)
{
    tt_world *w = fz_world_pick(f);
    tt_collision_settings s = tt_collision_settings_default();
    s.particles = fz_chance(f, 85);
    s.broadphase = fz_chance(f, 85) ? TT_BROADPHASE_GRID : (tt_broadphase)fz_enum(f, 2);
    s.cell_size = cell_size(f);
    s.restitution = fz_real(f, 0, 1);
    s.friction_static = fz_real(f, 0, 1);
    s.friction_kinetic = fz_real(f, 0, 1);
    s.restitution_threshold = fz_chance(f, 60) ? -1.0 : fz_real(f, 0, 5);
    s.events = fz_chance(f, 90) ? fz_below(f, 8) : (uint32_t)fz_rand(f);
    s.stacking = fz_chance(f, 60) ? 0.0 : fz_chance(f, 95) ? fz_real(f, 0, 10) : fz_real(f, -1, 1e13);
    s.anchored_friction = fz_chance(f, 40);
    s.warm_start = fz_chance(f, 50) ? 0.0 : fz_chance(f, 95) ? fz_real(f, 0, 1) : fz_real(f, -1, 2);
    fz_log(f, "tt_world_set_collision(%s, &(tt_collision_settings){particles %d, broadphase %d, cell %s, material %s %s "
              "%s, threshold %s, events %#x, stacking %s, anchored %d, warm %s})", fz_wn(f, w), s.particles, (int)s.broadphase,
           fz_d(s.cell_size), fz_d(s.restitution), fz_d(s.friction_static), fz_d(s.friction_kinetic), fz_d(s.restitution_threshold),
           s.events, fz_d(s.stacking), s.anchored_friction, fz_d(s.warm_start));
    FZ_HIT(f, tt_world_set_collision);
    fz_res(f, tt_world_set_collision(w, fz_chance(f, 2) ? NULL : &s));
}

static void c_world_get_collision(fz *f)
{
    tt_world *w = fz_world_pick(f);
    f->readonly = true;
    tt_collision_settings s;
    fz_log(f, "tt_world_get_collision(%s, &settings)", fz_wn(f, w));
    FZ_HIT(f, tt_world_get_collision);
    fz_res(f, tt_world_get_collision(w, OUTP(&s)));
}

static void c_world_get_collision_stats(fz *f)
{
    tt_world *w = fz_world_pick(f);
    f->readonly = true;
    tt_collision_stats s;
    tt_collision_stats *out = OUTP(&s);
    fz_log(f, "tt_world_get_collision_stats(%s, %s)", fz_wn(f, w), out ? "&stats" : "NULL");
    FZ_HIT(f, tt_world_get_collision_stats);
    fz_res(f, tt_world_get_collision_stats(w, out));
    if (!f->failed && out) fz_finite(f, s.broadphase_ms + s.broadphase_bytes_per_particle, "collision stats");
}

static void c_world_set_pair_collision(fz *f)
{
    tt_world *w = fz_world_pick(f);
    fz_h a = fz_handle(f, PK), b = fz_chance(f, 3) ? a : fz_handle(f, PK);
    bool on = fz_chance(f, 50);
    fz_log(f, "tt_world_set_pair_collision(%s, %s, %s, %d)", fz_wn(f, w), fz_hn(a, PK), fz_hn(b, PK), on);
    FZ_HIT(f, tt_world_set_pair_collision);
    fz_res(f, tt_world_set_pair_collision(w, FZ_P(a), FZ_P(b), on));
}

static void c_world_get_contact_events(fz *f)
{
    tt_world *w = fz_world_any(f);
    uint32_t n = 0;
    bool null_n = fz_chance(f, 4);
    fz_log(f, "tt_world_get_contact_events(%s, %s)", fz_wn(f, w), null_n ? "NULL" : "&n");
    FZ_HIT(f, tt_world_get_contact_events);
    const tt_contact_event *ev = tt_world_get_contact_events(w, null_n ? NULL : &n);
    fz_log_more(f, " -> %u", n);
    for (uint32_t i = 0; ev && !null_n && i < n; i++) {
        fz_finite_vec(f, ev[i].point, "a contact event's point");
        fz_finite(f, ev[i].impulse, "a contact event's impulse");
    }
}

const fz_entry fz_collide_entries[] = {
    { "tt_shape_def_default", c_shape_def_default, 1 },
    { "tt_shape_create", c_shape_create, 8 },
    { "tt_shape_destroy", c_shape_destroy, 2 },
    { "tt_shape_is_valid", c_shape_is_valid, 1 },
    { "tt_shape_set_transform", c_tt_shape_set_transform, 3 },
    { "tt_shape_get_transform", c_tt_shape_get_transform, 1 },
    { "tt_shape_set_material", c_tt_shape_set_material, 1 },
    { "tt_shape_set_filter", c_tt_shape_set_filter, 1 },
    { "tt_shape_set_sensor", c_tt_shape_set_sensor, 1 },
    { "tt_shape_get_type", c_tt_shape_get_type, 1 },
    { "tt_shape_get_user", c_tt_shape_get_user, 1 },
    { "tt_shape_get_aabb", c_tt_shape_get_aabb, 1 },
    { "tt_world_shape_count", c_world_shape_count, 1 },
    { "tt_shape_get_sensor", c_tt_shape_get_sensor, 1 },
    { "tt_world_list_shapes", c_world_list_shapes, 1 },
    { "tt_shape_get_outline", c_shape_get_outline, 2 },
    { "tt_shape_type_name", c_shape_type_name, 1 },
    { "tt_collision_settings_default", c_collision_settings_default, 1 },
    { "tt_world_set_collision", c_world_set_collision, 6 },
    { "tt_world_get_collision", c_world_get_collision, 1 },
    { "tt_world_get_collision_stats", c_world_get_collision_stats, 1 },
    { "tt_particle_set_material", c_tt_particle_set_material, 2 },
    { "tt_particle_get_material", c_tt_particle_get_material, 1 },
    { "tt_particle_set_bullet", c_tt_particle_set_bullet, 2 },
    { "tt_particle_get_bullet", c_tt_particle_get_bullet, 1 },
    { "tt_world_set_pair_collision", c_world_set_pair_collision, 2 },
    { "tt_world_get_contact_events", c_world_get_contact_events, 2 },
    { NULL, NULL, 0 },
};
