/* tests/fuzz/fuzz_c_scene.c — rays and queries, and scenes: one fuzzer
 * call that makes many particles in a loop, so a world gets deep fast and
 * takes the shapes that broke tether before: rows sharing one y far apart
 * (finding 1), piles of touching balls on a floor, coincident clusters
 * joined by links (finding 10), particles near the coordinate limit. */
#include "fuzz_c.h"

#include <float.h>
#include <stdlib.h>

#define PK TT_KIND_PARTICLE

static void c_world_raycast(fz *f)
{
    tt_world *w = fz_world_pick(f);
    f->readonly = true;
    tt_vec2 a = fz_point(f), b = fz_chance(f, 20) ? a : fz_point(f);
    if (fz_chance(f, 20)) b = (tt_vec2){ b.x, a.y }; /* along a row or a segment (finding 10) */
    uint16_t mask = fz_bits16(f);
    tt_ray_hit hit;
    bool null_out = fz_chance(f, 4);
    fz_log(f, "tt_world_raycast(%s, %s, %s, %#x, %s)", fz_wn(f, w), fz_v(a), fz_v(b), mask, null_out ? "NULL" : "&hit");
    FZ_HIT(f, tt_world_raycast);
    fz_res(f, tt_world_raycast(w, a, b, mask, null_out ? NULL : &hit));
    if (f->failed || null_out || !hit.hit) return;
    fz_finite_vec(f, hit.point, "a ray hit's point");
    fz_finite_vec(f, hit.normal, "a ray hit's normal");
    if (!(hit.fraction >= 0.0 && hit.fraction <= 1.0)) fz_fail(f, "a ray hit's fraction is %s", fz_d(hit.fraction));
}

/* Shared by both queries: buffers, call, check the counts. */
typedef tt_result (*query_fn)(tt_world *, tt_vec2, tt_vec2, uint16_t, tt_particle *, uint32_t, uint32_t *, tt_shape *,
                              uint32_t, uint32_t *);

static tt_result point_query(tt_world *w, tt_vec2 p, tt_vec2 unused, uint16_t m, tt_particle *ps, uint32_t pc,
                             uint32_t *np, tt_shape *ss, uint32_t sc, uint32_t *ns)
{
    (void)unused;
    return tt_world_query_point(w, p, m, ps, pc, np, ss, sc, ns);
}

static void query(fz *f, const char *name, query_fn fn, bool box)
{
    tt_world *w = fz_world_pick(f);
    f->readonly = true;
    tt_vec2 lo = fz_point(f), hi = box ? fz_point(f) : lo;
    if (box && fz_chance(f, 70)) hi = (tt_vec2){ lo.x + fz_real(f, 0, 40), lo.y + fz_real(f, 0, 40) };
    uint16_t mask = fz_bits16(f);
    uint32_t pcap, scap, np = 0, ns = 0;
    tt_particle *ps = fz_buffer(f, &pcap, 64, sizeof *ps);
    tt_shape *ss = fz_buffer(f, &scap, 16, sizeof *ss);
    bool null_np = fz_chance(f, 4), null_ns = fz_chance(f, 4);
    fz_log(f, "%s(%s, %s, %s, %#x, %s, %u, %s, %s, %u, %s)", name, fz_wn(f, w), fz_v(lo), box ? fz_v(hi) : "-", mask,
           ps ? "ps" : "NULL", pcap, null_np ? "NULL" : "&np", ss ? "ss" : "NULL", scap, null_ns ? "NULL" : "&ns");
    fz_res(f, fn(w, lo, hi, mask, ps, pcap, null_np ? NULL : &np, ss, scap, null_ns ? NULL : &ns));
    for (uint32_t i = 0; !f->failed && ps && !null_np && i < np && i < pcap; i++) fz_remember(f, PK, FZ_H(ps[i]));
    free(ps);
    free(ss);
}

static void c_world_query_point(fz *f)
{
    FZ_HIT(f, tt_world_query_point);
    query(f, "tt_world_query_point", point_query, false);
}

static void c_world_query_aabb(fz *f)
{
    FZ_HIT(f, tt_world_query_aabb);
    query(f, "tt_world_query_aabb", tt_world_query_aabb, true);
}

/* n particles at origin + i·step (+ j·step2 for piles), made one by one:
 * each failed create must leave the count as it was. */
static void make_particles(fz *f, tt_world *w, uint32_t n, uint32_t per_row, tt_vec2 o, tt_vec2 step, tt_vec2 step2,
                           double radius)
{
    tt_particle_def d = tt_particle_def_default();
    d.radius = radius;
    d.mass = fz_chance(f, 80) ? 1.0 : fz_real(f, TT_MIN_MASS, 100);
    for (uint32_t i = 0; i < n; i++) {
        uint32_t col = per_row ? i % per_row : i, row = per_row ? i / per_row : 0;
        d.position = (tt_vec2){ o.x + col * step.x + row * step2.x, o.y + col * step.y + row * step2.y };
        uint32_t before = tt_world_particle_count(w);
        FZ_HIT(f, tt_particle_create);
        tt_particle p = tt_particle_create(w, &d);
        if (p.index || p.gen) fz_remember(f, PK, FZ_H(p));
        else if (tt_world_particle_count(w) != before) fz_fail(f, "a failed tt_particle_create changed the count");
    }
}

/* Collisions switched on for the scene half the time, often with a tiny cell. */
static void maybe_collide(fz *f, tt_world *w)
{
    if (fz_chance(f, 35)) return;
    static const double cells[] = { 0.0, 0.0, 1e-3, 1e-300, 1e-12, 0.5 };
    tt_collision_settings s = tt_collision_settings_default();
    s.cell_size = cells[fz_below(f, sizeof cells / sizeof cells[0])];
    s.events = fz_below(f, 8);
    fz_log(f, "tt_world_set_collision(%s, &(tt_collision_settings){.particles = true, .cell_size = %s, .events = %#x})",
           fz_wn(f, w), fz_d(s.cell_size), s.events);
    FZ_HIT(f, tt_world_set_collision);
    tt_result r = tt_world_set_collision(w, &s);
    fz_log_more(f, " -> %s", fz_res_name(r));
}

static tt_world *scene_world(fz *f)
{
    tt_world *w = fz_world_pick(f);
    if (!w) { /* a NULL world: one create, which must fail */
        fz_log(f, "tt_particle_create(NULL, &def)");
        FZ_HIT(f, tt_particle_create);
        fz_hres(f, PK, FZ_H(tt_particle_create(NULL, &(tt_particle_def){ .mass = 1 })));
        return NULL;
    }
    if (fz_chance(f, 40)) w = fz_world_fresh(f, f->cur);
    return w;
}

static void c_scene_row(fz *f)
{
    static const double steps[] = { 10.0, 1.0, 0.5, 1e-3, 100.0, 0.1 };
    tt_world *w = scene_world(f);
    if (!w) return;
    uint32_t n = 20 + fz_below(f, 280);
    tt_vec2 o = { fz_chance(f, 50) ? 0.0 : fz_coord(f), fz_coord(f) };
    tt_vec2 step = { steps[fz_below(f, sizeof steps / sizeof steps[0])], 0.0 };
    if (fz_chance(f, 30)) step = (tt_vec2){ 0.0, step.x }; /* a column: one shared x */
    double r = fz_chance(f, 40) ? 0.0 : fz_real(f, 0.01, 0.5);
    fz_log(f, "for (i = 0; i < %u; i++) tt_particle_create(%s, &(tt_particle_def){.position = {%s + i * %s, %s + i * %s}, "
              ".radius = %s, .mass = 1})", n, fz_wn(f, w), fz_d(o.x), fz_d(step.x), fz_d(o.y), fz_d(step.y), fz_d(r));
    make_particles(f, w, n, 0, o, step, step, r);
    maybe_collide(f, w);
}

static void c_scene_pile(fz *f)
{
    tt_world *w = scene_world(f);
    if (!w) return;
    uint32_t cols = 2 + fz_below(f, 30), rows = 1 + fz_below(f, 30);
    double r = fz_real(f, 0.02, 0.5), gap = fz_chance(f, 50) ? 2.0 * r : 2.0 * r * fz_real(f, 0.5, 1.5);
    tt_vec2 o = fz_chance(f, 80) ? fz_vec(f, -20, 20) : fz_point(f);
    fz_log(f, "for (i = 0; i < %u; i++) tt_particle_create(%s, &(tt_particle_def){.position = {%s + (i %% %u) * %s, "
              "%s + (i / %u) * %s}, .radius = %s})", cols * rows, fz_wn(f, w), fz_d(o.x), cols, fz_d(gap), fz_d(o.y),
           cols, fz_d(gap), fz_d(r));
    make_particles(f, w, cols * rows, cols, o, (tt_vec2){ gap, 0 }, (tt_vec2){ 0, gap }, r);
    tt_shape_def floor = tt_shape_def_default();
    floor.type = TT_SHAPE_AABB;
    floor.a = (tt_vec2){ o.x - 50, o.y - 2 };
    floor.b = (tt_vec2){ o.x + 50 + cols * gap, o.y - r };
    fz_log(f, "tt_shape_create(%s, &(tt_shape_def){.type = TT_SHAPE_AABB, .a = %s, .b = %s})", fz_wn(f, w), fz_v(floor.a),
           fz_v(floor.b));
    FZ_HIT(f, tt_shape_create);
    tt_shape s = tt_shape_create(w, &floor);
    if (s.index || s.gen) fz_remember(f, TT_KIND_SHAPE, FZ_H(s));
    maybe_collide(f, w);
}

static void c_scene_cluster(fz *f)
{
    tt_world *w = scene_world(f);
    if (!w) return;
    uint32_t n = 2 + fz_below(f, 60);
    tt_vec2 o = fz_point(f);
    double r = fz_chance(f, 50) ? 0.0 : fz_real(f, 0.01, 0.5);
    fz_log(f, "for (i = 0; i < %u; i++) tt_particle_create(%s, &(tt_particle_def){.position = %s, .radius = %s}); "
              "and a length-1 link between each and the next", n, fz_wn(f, w), fz_v(o), fz_d(r));
    make_particles(f, w, n, 0, o, (tt_vec2){ 0, 0 }, (tt_vec2){ 0, 0 }, r);
    tt_particle *ps = malloc(n * sizeof *ps);
    if (!ps) abort();
    uint32_t all = tt_world_particle_count(w), got = all < n ? all : n;
    tt_particle *every = malloc((all ? all : 1) * sizeof *every);
    if (!every) abort();
    tt_world_list_particles(w, every, all);
    for (uint32_t i = 0; i < got; i++) ps[i] = every[all - got + i]; /* the newest slots: usually these */
    for (uint32_t i = 0; i + 1 < got; i++) {
        tt_distance_def d = tt_distance_def_default();
        d.a = ps[i];
        d.b = ps[i + 1];
        d.length = 1.0;
        FZ_HIT(f, tt_distance_create);
        tt_constraint c = tt_distance_create(w, &d);
        if (c.index || c.gen) fz_remember(f, TT_KIND_CONSTRAINT, FZ_H(c));
    }
    free(every);
    free(ps);
    maybe_collide(f, w);
}

const fz_entry fz_scene_entries[] = {
    { "tt_world_raycast", c_world_raycast, 3 },
    { "tt_world_query_point", c_world_query_point, 2 },
    { "tt_world_query_aabb", c_world_query_aabb, 2 },
    { "scene: a row sharing one y (or a column sharing x)", c_scene_row, 3 },
    { "scene: a pile of touching balls on a floor", c_scene_pile, 2 },
    { "scene: coincident particles joined by links", c_scene_cluster, 2 },
    { NULL, NULL, 0 },
};
