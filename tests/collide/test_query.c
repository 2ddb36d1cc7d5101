/* Queries through the broadphase agree with brute force over every
 * particle and primitive, on random scenes (particles far outside the grid
 * included), and see teleports made between steps; a ray exactly along a
 * segment hits its nearer end. */
#include "test.h"
#include "collide/collide_internal.h"

#include <stdlib.h>
#include <string.h>

static uint64_t rs;
static double rnd(void)
{
    rs = rs * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(rs >> 11) / 9007199254740992.0;
}

static tt_world *scene(uint64_t seed)
{
    rs = seed;
    tt_world *w = tt_world_create(NULL);
    tt_collision_settings cs = tt_collision_settings_default();
    tt_world_set_collision(w, &cs);
    for (int i = 0; i < 400; i++) {
        tt_particle_def pd = tt_particle_def_default();
        pd.radius = rnd() < 0.1 ? 0 : 0.1 + rnd() * 0.6;
        pd.position = (tt_vec2){rnd() * 40 - 20, rnd() * 40 - 20};
        if (i % 97 == 0) pd.position = (tt_vec2){(rnd() - 0.5) * 1e5, (rnd() - 0.5) * 1e5};
        pd.category = (uint16_t)(rnd() < 0.2 ? 2 : 1);
        tt_particle_create(w, &pd);
    }
    for (int k = 0; k < 60; k++) {
        tt_shape_def sd = tt_shape_def_default();
        sd.position = (tt_vec2){rnd() * 40 - 20, rnd() * 40 - 20};
        sd.angle = rnd() * 6;
        double u = rnd();
        tt_vec2 pts[5] = {{0, 0}, {1.5, -0.3}, {2, 1}, {0.8, 1.8}, {-0.4, 1}};
        if (u < 0.2) { sd.type = TT_SHAPE_CIRCLE; sd.radius = 0.2 + rnd(); }
        else if (u < 0.4) { sd.type = TT_SHAPE_BOX; sd.half_extents = (tt_vec2){0.2 + rnd(), 0.2 + rnd() * 3}; }
        else if (u < 0.55) { sd.type = TT_SHAPE_AABB; sd.angle = 0; sd.a = (tt_vec2){0, 0}; sd.b = (tt_vec2){rnd() * 3, rnd() * 3}; }
        else if (u < 0.7) { sd.type = TT_SHAPE_CAPSULE; sd.b = (tt_vec2){rnd() * 4, 0}; sd.radius = rnd() * 0.5; }
        else if (u < 0.8) { sd.type = TT_SHAPE_POLYGON; sd.points = pts; sd.count = 5; }
        else if (u < 0.9) { sd.type = TT_SHAPE_CHAIN; sd.points = pts; sd.count = 5; }
        else { sd.type = TT_SHAPE_SEGMENT; sd.b = (tt_vec2){rnd() * 8, 0}; }
        if (k == 0) { sd.type = TT_SHAPE_SEGMENT; sd.position = (tt_vec2){-30, -25}; sd.angle = 0; sd.b = (tt_vec2){60, 0}; } /* long: the big list */
        sd.category = (uint16_t)(rnd() < 0.2 ? 2 : 1);
        tt_shape_create(w, &sd);
    }
    for (int s = 0; s < 3; s++) tt_world_step(w, 1.0 / 60);
    return w;
}

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return (x > y) - (x < y);
}

TEST(raycast_agrees_with_brute_force)
{
    for (uint64_t seed = 1; seed <= 6; seed++) {
        tt_world *w = scene(seed);
        tt__collide *c = tt__collide_peek(w);
        int hits = 0;
        for (int q = 0; q < 300; q++) {
            tt_vec2 a = {rnd() * 50 - 25, rnd() * 50 - 25}, b = {rnd() * 50 - 25, rnd() * 50 - 25};
            uint16_t mask = q % 5 == 0 ? 2 : 0xFFFF;
            tt_ray_hit hit;
            ENSURE_OK(tt_world_raycast(w, a, b, mask, &hit));
            /* brute force: every primitive, every particle */
            double best = INFINITY, t, nx, ny;
            for (uint32_t k = 0; k < c->nprim; k++) {
                const tt__shape *sh = &c->shapes[c->prims[k].shape];
                if (sh->def.sensor || !(sh->def.category & mask)) continue;
                if (tt__ray_vs_prim(c, &c->prims[k], a.x, a.y, b.x - a.x, b.y - a.y, 0, 1, &t, &nx, &ny)) best = fmin(best, t);
            }
            for (uint32_t i = 0; i < w->ppool.count; i++) {
                if (!(w->flags[i] & TT__PF_ALIVE) || !(w->category[i] & mask)) continue;
                if (tt__ray_vs_circle(a.x, a.y, b.x - a.x, b.y - a.y, w->px[i], w->py[i], w->radius[i], 1, &t, &nx, &ny)) best = fmin(best, t);
            }
            ENSURE(hit.hit == (best <= 1));
            if (hit.hit) {
                hits++;
                ENSURE(hit.fraction == best);
                ENSURE((hit.particle.gen != 0) != (hit.shape.gen != 0));
                ENSURE_NEAR(hypot(hit.normal.x, hit.normal.y), 1, 1e-9);
            }
        }
        ENSURE(hits > 100);
        tt_world_destroy(w);
    }
}

static void check_area(tt_world *w, bool point, tt_vec2 lo, tt_vec2 hi, uint16_t mask, int *found)
{
    tt__collide *c = tt__collide_peek(w);
    tt_particle ps[512];
    tt_shape ss[128];
    uint32_t np, ns;
    if (point) tt_world_query_point(w, lo, mask, ps, 512, &np, ss, 128, &ns);
    else tt_world_query_aabb(w, lo, hi, mask, ps, 512, &np, ss, 128, &ns);
    uint64_t got[512], want[512];
    uint32_t nw = 0;
    for (uint32_t k = 0; k < np; k++) got[k] = ps[k].index;
    for (uint32_t i = 0; i < w->ppool.count; i++) {
        if (!(w->flags[i] & TT__PF_ALIVE) || !(w->category[i] & mask)) continue;
        double x = w->px[i], y = w->py[i], r = w->radius[i];
        double dx = fmax(fmax(lo.x - x, x - hi.x), 0), dy = fmax(fmax(lo.y - y, y - hi.y), 0);
        if (dx * dx + dy * dy <= r * r) want[nw++] = i;
    }
    qsort(got, np, 8, cmp_u64);
    qsort(want, nw, 8, cmp_u64);
    if (np != nw) tt_test_fail(__FILE__, __LINE__, "particles: %u found, %u by brute force", np, nw);
    for (uint32_t k = 0; k < np && k < nw; k++)
        if (got[k] != want[k]) tt_test_fail(__FILE__, __LINE__, "particle sets differ");
    /* shapes */
    bool in[4096] = {false};
    for (uint32_t k = 0; k < c->nprim; k++) {
        const tt__prim *p = &c->prims[k];
        if (!(c->shapes[p->shape].def.category & mask)) continue;
        bool hit;
        if (point) {
            tt__hit h;
            tt__circle_vs_prim(c, p, lo.x, lo.y, 0, &h);
            hit = h.depth >= 0;
        } else {
            hit = tt__prim_vs_aabb(c, p, lo.x, lo.y, hi.x, hi.y);
        }
        if (hit) in[p->shape] = true;
    }
    uint32_t nb = 0;
    for (uint32_t k = 0; k < 4096; k++) nb += in[k];
    if (ns != nb) tt_test_fail(__FILE__, __LINE__, "shapes: %u found, %u by brute force", ns, nb);
    for (uint32_t k = 0; k < ns; k++)
        if (!in[ss[k].index]) tt_test_fail(__FILE__, __LINE__, "shape %u should not be there", ss[k].index);
    *found += (int)(np + ns);
}

TEST(point_and_box_queries_agree_with_brute_force)
{
    for (uint64_t seed = 11; seed <= 16; seed++) {
        tt_world *w = scene(seed);
        int found = 0;
        for (int q = 0; q < 300; q++) {
            tt_vec2 a = {rnd() * 44 - 22, rnd() * 44 - 22};
            tt_vec2 b = {a.x + rnd() * 6, a.y + rnd() * 6};
            uint16_t mask = q % 5 == 0 ? 2 : 0xFFFF;
            check_area(w, true, a, a, mask, &found);
            check_area(w, false, a, b, mask, &found);
        }
        check_area(w, false, (tt_vec2){-1e6, -1e6}, (tt_vec2){1e6, 1e6}, 0xFFFF, &found); /* everything, far ones too */
        ENSURE(found > 1000);
        tt_world_destroy(w);
    }
}

TEST(queries_see_particles_moved_and_made_between_steps)
{
    tt_world *w = tt_world_create(NULL);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.5;
    tt_particle a = tt_particle_create(w, &pd);
    tt_ray_hit hit;
    ENSURE_OK(tt_world_raycast(w, (tt_vec2){-5, 0}, (tt_vec2){5, 0}, 0xFFFF, &hit));
    ENSURE(hit.hit && hit.particle.index == a.index);
    ENSURE_NEAR(hit.fraction, 0.45, 1e-12);
    ENSURE_NEAR(hit.point.x, -0.5, 1e-12);
    tt_particle_set_position(w, a, (tt_vec2){100, 100}, TT_MOVE_RESET_VELOCITY);
    ENSURE_OK(tt_world_raycast(w, (tt_vec2){-5, 0}, (tt_vec2){5, 0}, 0xFFFF, &hit));
    ENSURE(!hit.hit);
    pd.position = (tt_vec2){2, 0};
    tt_particle b = tt_particle_create(w, &pd);
    uint32_t np = 0, ns = 0;
    tt_particle got[4];
    ENSURE_OK(tt_world_query_point(w, (tt_vec2){2.2, 0.1}, 0xFFFF, got, 4, &np, NULL, 0, &ns));
    ENSURE(np == 1 && got[0].index == b.index && ns == 0);
    tt_world_destroy(w);
}

/* One shape in an otherwise empty world, the first hit of from → to. */
static tt_ray_hit ray_at(const tt_shape_def *sd, tt_vec2 from, tt_vec2 to)
{
    tt_world *w = tt_world_create(NULL);
    tt_collision_settings cs = tt_collision_settings_default();
    tt_world_set_collision(w, &cs);
    tt_shape_create(w, sd);
    tt_ray_hit hit;
    memset(&hit, 0, sizeof hit);
    if (tt_world_raycast(w, from, to, 0xFFFF, &hit) != TT_OK) hit.fraction = -1;
    tt_world_destroy(w);
    return hit;
}

/* Issue 14, finding 10: a ray exactly along a segment is parallel to both
 * of its faces, and a segment has no end circles, so it went through.
 * It hits the nearer end point, the normal facing the ray. */
TEST(a_ray_along_a_segment_hits_its_nearer_end)
{
    tt_shape_def sd = tt_shape_def_default();
    sd.type = TT_SHAPE_SEGMENT;
    const struct { tt_vec2 a, b, from, to, point; double fraction; } cases[] = {
        {{-1, 0}, {1, 0}, {-5, 0}, {5, 0}, {-1, 0}, 0.4},          /* along +x: end a */
        {{-1, 0}, {1, 0}, {5, 0}, {-5, 0}, {1, 0}, 0.4},           /* along −x: end b */
        {{2, -3}, {2, 7}, {2, 10}, {2, -10}, {2, 7}, 0.15},         /* vertical, downwards */
        {{0, 0}, {3, 4}, {-3, -4}, {9, 12}, {0, 0}, 0.25},         /* diagonal, exactly collinear */
        {{-1, 0.25}, {1, 0.25}, {-2, 0.25}, {2, 0.25}, {-1, 0.25}, 0.25},
    };
    for (unsigned k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        sd.a = cases[k].a;
        sd.b = cases[k].b;
        tt_ray_hit hit = ray_at(&sd, cases[k].from, cases[k].to);
        if (!hit.hit) {
            tt_test_fail(__FILE__, __LINE__, "case %u: the ray along the segment missed it", k);
            continue;
        }
        ENSURE_NEAR(hit.fraction, cases[k].fraction, 1e-15);
        ENSURE_NEAR(hit.point.x, cases[k].point.x, 1e-12);
        ENSURE_NEAR(hit.point.y, cases[k].point.y, 1e-12);
        double dx = cases[k].to.x - cases[k].from.x, dy = cases[k].to.y - cases[k].from.y, l = hypot(dx, dy);
        ENSURE_NEAR(hit.normal.x, -dx / l, 1e-12);
        ENSURE_NEAR(hit.normal.y, -dy / l, 1e-12);
    }
    /* on the line but short of the segment, or pointing away from it: no hit */
    sd.a = (tt_vec2){-1, 0};
    sd.b = (tt_vec2){1, 0};
    ENSURE(!ray_at(&sd, (tt_vec2){-5, 0}, (tt_vec2){-1.5, 0}).hit);
    ENSURE(!ray_at(&sd, (tt_vec2){-5, 0}, (tt_vec2){-9, 0}).hit);
    ENSURE(ray_at(&sd, (tt_vec2){-5, 0}, (tt_vec2){-1, 0}).hit); /* just reaching it */
    /* starting on the segment: at once */
    tt_ray_hit hit = ray_at(&sd, (tt_vec2){0.5, 0}, (tt_vec2){5, 0});
    ENSURE(hit.hit && hit.fraction == 0.0);
    /* a chain's segments and a box's edges too */
    tt_vec2 pts[3] = {{0, 0}, {4, 0}, {4, 4}};
    sd.type = TT_SHAPE_CHAIN;
    sd.points = pts;
    sd.count = 3;
    hit = ray_at(&sd, (tt_vec2){10, 0}, (tt_vec2){-10, 0});
    ENSURE(hit.hit);
    ENSURE_NEAR(hit.point.x, 4, 1e-12);
    sd = tt_shape_def_default();
    sd.type = TT_SHAPE_AABB;
    sd.a = (tt_vec2){0, 0};
    sd.b = (tt_vec2){2, 1};
    hit = ray_at(&sd, (tt_vec2){-3, 1}, (tt_vec2){5, 1});
    ENSURE(hit.hit);
    ENSURE_NEAR(hit.point.x, 0, 1e-12);
}

/* Found by the C fuzzer: a query on a world that never used collisions made
 * the collision state on the way (for its grid), and that state entered the
 * hash, so two worlds in the same state hashed differently after one of
 * them was only read. */
TEST(a_query_of_a_world_without_collisions_leaves_its_hash)
{
    tt_world *a = tt_world_create(NULL), *b = tt_world_create(NULL);
    for (int i = 0; i < 10; i++) {
        tt_particle_def pd = tt_particle_def_default();
        pd.position = (tt_vec2){i * 0.5, 1.0 + i};
        pd.radius = 0.2;
        tt_particle_create(a, &pd);
        tt_particle_create(b, &pd);
    }
    ENSURE(tt_world_hash(a) == tt_world_hash(b));
    tt_ray_hit hit;
    uint32_t np = 0, ns = 0;
    ENSURE_OK(tt_world_raycast(a, (tt_vec2){-5, 1}, (tt_vec2){5, 1}, 0xFFFF, &hit));
    ENSURE(hit.hit);
    ENSURE_OK(tt_world_query_point(a, (tt_vec2){0, 1}, 0xFFFF, NULL, 0, &np, NULL, 0, &ns));
    ENSURE_OK(tt_world_query_aabb(a, (tt_vec2){-0.1, 0.9}, (tt_vec2){0.1, 1.1}, 0xFFFF, NULL, 0, &np, NULL, 0, &ns));
    ENSURE(np == 1);
    ENSURE(tt_world_hash(a) == tt_world_hash(b));
    for (int s = 0; s < 30; s++) {
        ENSURE_OK(tt_world_step(a, 1.0 / 60));
        ENSURE_OK(tt_world_step(b, 1.0 / 60));
    }
    ENSURE(tt_world_hash(a) == tt_world_hash(b));
    /* Once collisions are switched on, both are the same world again. */
    tt_collision_settings cs = tt_collision_settings_default();
    cs.restitution = 0.5;
    ENSURE_OK(tt_world_set_collision(a, &cs));
    ENSURE_OK(tt_world_set_collision(b, &cs));
    for (int s = 0; s < 30; s++) {
        ENSURE_OK(tt_world_step(a, 1.0 / 60));
        ENSURE_OK(tt_world_step(b, 1.0 / 60));
    }
    ENSURE(tt_world_hash(a) == tt_world_hash(b));
    tt_world_destroy(a);
    tt_world_destroy(b);
}
