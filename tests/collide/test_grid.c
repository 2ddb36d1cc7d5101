/* The particle broadphase: grid and brute force give the same pair set on
 * random scenes (varied radii, far outside the grid, on cell edges,
 * coincident centres, layers and exclusions); no per-step malloc after
 * warm-up; a world without collisions has no collision state at all; the
 * grid keeps at least one row and column, and cell counts an int holds, for
 * particles on one row and for absurd cell sizes; while some sleep, the
 * grid holds the awake ones and the sleepers within reach of one, with the
 * same pairs. */
#include "test.h"
#include "collide/collide_internal.h"

#include <string.h>
#include <stdlib.h>

static uint64_t rng_state;
static double rnd(void) /* xorshift64*, deterministic */
{
    rng_state ^= rng_state >> 12;
    rng_state ^= rng_state << 25;
    rng_state ^= rng_state >> 27;
    return (double)((rng_state * 2685821657736338717ull) >> 11) * (1.0 / 9007199254740992.0);
}

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return (x > y) - (x < y);
}

/* The pair set as sorted (min, max) keys. */
static uint64_t *pair_set(const tt__collide *c)
{
    uint64_t *k = malloc((c->scr.npairs + 1) * sizeof *k);
    for (uint32_t i = 0; i < c->scr.npairs; i++) {
        uint32_t a = c->scr.pairs[i].a, b = c->scr.pairs[i].b;
        k[i] = a < b ? ((uint64_t)a << 32) | b : ((uint64_t)b << 32) | a;
    }
    qsort(k, c->scr.npairs, sizeof *k, cmp_u64);
    return k;
}

static tt_world *random_scene(uint64_t seed, int n, tt_particle *ps)
{
    rng_state = seed * 0x9E3779B97F4A7C15ull + 1;
    tt_world *w = tt_world_create(NULL);
    tt_collision_settings cs = tt_collision_settings_default();
    tt_world_set_collision(w, &cs);
    for (int i = 0; i < n; i++) {
        tt_particle_def pd = tt_particle_def_default();
        double kind = rnd();
        pd.radius = kind < 0.05 ? 0.0 : 0.05 + rnd() * (kind < 0.5 ? 0.3 : 1.2);
        pd.position = (tt_vec2){rnd() * 24 - 12, rnd() * 24 - 12};
        if (kind > 0.97) pd.position = (tt_vec2){(rnd() - 0.5) * 2e6, (rnd() - 0.5) * 2e6}; /* far outside */
        if (kind > 0.9 && kind <= 0.93) pd.position = (tt_vec2){floor(pd.position.x), floor(pd.position.y)}; /* grid lines */
        if (i > 0 && kind > 0.85 && kind <= 0.9) { /* coincident with an earlier one */
            tt_particle_get_position(w, ps[(int)(rnd() * i)], &pd.position);
        }
        if (kind > 0.8 && kind <= 0.82) pd.pinned = true;
        pd.category = (uint16_t)(rnd() < 0.1 ? 2 : 1);
        pd.mask = (uint16_t)(rnd() < 0.1 ? 1 : 0xFFFF);
        ps[i] = tt_particle_create(w, &pd);
    }
    for (int k = 0; k < n / 50; k++) { /* a few switched-off pairs */
        int a = (int)(rnd() * n), b = (int)(rnd() * n);
        if (a != b) tt_world_set_pair_collision(w, ps[a], ps[b], false);
    }
    return w;
}

TEST(grid_and_brute_force_give_identical_pair_sets_on_random_scenes)
{
    enum { N = 1000 };
    tt_particle *ps = malloc(N * sizeof *ps);
    uint64_t total = 0;
    for (uint64_t seed = 1; seed <= 24; seed++) {
        tt_world *w = random_scene(seed, N, ps);
        if (seed % 3 == 0) tt_particle_destroy(w, ps[7]); /* a hole in the slots */
        tt__collide *c = tt__collide_peek(w);
        ENSURE(c);
        c->scr.npairs = 0;
        ENSURE(tt__grid_build(w, &c->scr.grid, seed % 2 ? 0.0 : 3.0) && tt__grid_pairs(w, c));
        ENSURE(c->scr.grid.nout > 0);                                /* some are outside the grid */
        ENSURE(c->scr.grid.ncell <= 4 * c->scr.grid.n + 1024);           /* and the grid stayed small */
        uint32_t ng = c->scr.npairs;
        uint64_t *g = pair_set(c);
        c->scr.npairs = 0;
        ENSURE(tt__brute_pairs(w, c));
        uint64_t *b = pair_set(c);
        ENSURE(ng == c->scr.npairs);
        for (uint32_t i = 0; i < ng; i++) ENSURE(g[i] == b[i]);
        for (uint32_t i = 1; i < ng; i++) ENSURE(g[i] != g[i - 1]); /* no pair twice */
        total += ng;
        free(g);
        free(b);
        tt_world_destroy(w);
    }
    ENSURE(total > 24 * 1000); /* the scenes are not trivially empty */
    free(ps);
}

TEST(grid_arrays_are_reused_step_after_step)
{
    tt_world *w = tt_world_create(NULL);
    tt_collision_settings cs = tt_collision_settings_default();
    tt_world_set_collision(w, &cs);
    tt_shape_def sd = tt_shape_def_default();
    sd.type = TT_SHAPE_AABB;
    sd.a = (tt_vec2){-20, -1};
    sd.b = (tt_vec2){20, 0};
    tt_shape_create(w, &sd);
    for (int i = 0; i < 400; i++) {
        tt_particle_def pd = tt_particle_def_default();
        pd.radius = 0.5;
        pd.position = (tt_vec2){-10 + (i % 20), 0.5 + (i / 20)};
        tt_particle_create(w, &pd);
    }
    for (int s = 0; s < 30; s++) tt_world_step(w, 1.0 / 60);
    tt__collide *c = tt__collide_peek(w);
    void *p0 = c->scr.grid.idx, *p1 = c->scr.grid.start, *p2 = c->scr.pairs, *p3 = c->scr.sc;
    uint32_t caps[4] = {c->scr.grid.cap_n, c->scr.grid.cap_cells, c->scr.paircap, c->scr.sccap};
    for (int s = 0; s < 60; s++) tt_world_step(w, 1.0 / 60);
    ENSURE(p0 == c->scr.grid.idx && p1 == c->scr.grid.start && p2 == c->scr.pairs && p3 == c->scr.sc);
    ENSURE(caps[0] == c->scr.grid.cap_n && caps[1] == c->scr.grid.cap_cells && caps[2] == c->scr.paircap && caps[3] == c->scr.sccap);
    tt_collision_stats st;
    ENSURE_OK(tt_world_get_collision_stats(w, &st));
    ENSURE(st.static_rebuilds == 1); /* the static index was built once */
    ENSURE(st.broadphase_bytes_per_particle > 0 && st.broadphase_bytes_per_particle < 200);
    tt_world_destroy(w);
}

/* The grid's own time (build and pair search), for the linear-cost figure:
 * that of the last step, all substeps, and none when it found no pairs. */
TEST(broadphase_time_is_the_last_steps)
{
    tt_world_def wd = tt_world_def_default();
    wd.substeps = 4;
    tt_world *w = tt_world_create(&wd);
    tt_collision_settings cs = tt_collision_settings_default();
    ENSURE_OK(tt_world_set_collision(w, &cs));
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.5;
    for (int i = 0; i < 2000; i++) {
        pd.position = (tt_vec2){(i % 50) * 1.02, (i / 50) * 1.02};
        tt_particle_create(w, &pd);
    }
    tt_collision_stats st;
    ENSURE_OK(tt_world_get_collision_stats(w, &st));
    ENSURE(st.broadphase_ms == 0.0); /* no step yet */
    ENSURE_OK(tt_world_step(w, 1.0 / 60));
    tt_stats ws;
    ENSURE_OK(tt_world_get_stats(w, &ws));
    ENSURE_OK(tt_world_get_collision_stats(w, &st));
    ENSURE(st.broadphase_ms > 0.0 && st.broadphase_ms <= ws.stage_ms[TT_STAGE_COLLIDE]);
    cs.particles = false; /* shapes only: no grid */
    ENSURE_OK(tt_world_set_collision(w, &cs));
    ENSURE_OK(tt_world_step(w, 1.0 / 60));
    ENSURE_OK(tt_world_get_collision_stats(w, &st));
    ENSURE(st.broadphase_ms == 0.0);
    tt_world_destroy(w);
}

TEST(a_world_without_collisions_has_no_collision_state)
{
    tt_world *w = tt_world_create(NULL);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 1;
    tt_particle a = tt_particle_create(w, &pd);
    tt_particle b = tt_particle_create(w, &pd); /* same place: would be pushed apart if collisions were on */
    tt_world_step(w, 1.0 / 60);
    ENSURE(tt__collide_peek(w) == NULL);
    ENSURE(w->group_count == 1 && strcmp(w->groups[0].ops->name, "sleep") == 0); /* on by default, no other */
    tt_vec2 xa, xb;
    tt_particle_get_position(w, a, &xa);
    tt_particle_get_position(w, b, &xb);
    ENSURE(xa.x == xb.x && xa.y == xb.y);
    tt_collision_settings s;
    ENSURE_OK(tt_world_get_collision(w, &s));
    ENSURE(!s.particles);
    tt_world_destroy(w);
}

TEST(far_away_particles_still_collide)
{
    tt_world *w = tt_world_create(NULL);
    tt_world_set_gravity(w, (tt_vec2){0, 0});
    tt_collision_settings cs = tt_collision_settings_default();
    tt_world_set_collision(w, &cs);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.5;
    for (int i = 0; i < 200; i++) { /* a crowd near the origin */
        pd.position = (tt_vec2){(i % 20) * 1.5, (i / 20) * 1.5};
        tt_particle_create(w, &pd);
    }
    pd.position = (tt_vec2){1e9, -1e9};
    tt_particle a = tt_particle_create(w, &pd);
    pd.position = (tt_vec2){1e9 + 0.5, -1e9};
    tt_particle b = tt_particle_create(w, &pd);
    tt_world_step(w, 1.0 / 60);
    tt_vec2 xa, xb;
    tt_particle_get_position(w, a, &xa);
    tt_particle_get_position(w, b, &xb);
    ENSURE_NEAR(xb.x - xa.x, 1.0, 1e-6);
    tt_world_destroy(w);
}

/* The grid's shape after a build: at least one row and column, the cell
 * count their product, and every sorted particle's cell inside it. */
static bool grid_sane(const tt__grid *g)
{
    if (g->n == 0) return g->ncell == 0;
    if (g->nx < 1 || g->ny < 1 || g->ncell != (uint32_t)g->nx * (uint32_t)g->ny) return false;
    if (g->start[g->ncell] != g->n) return false;
    for (uint32_t c = 0; c < g->ncell; c++)
        if (g->start[c] > g->start[c + 1]) return false;
    return true;
}

/* Issue 14, finding 1: every particle on one row, far apart, so the grid
 * narrows itself to mean ± 4σ; the mean of the equal y rounds above them
 * and the row count came out 0 (a heap overflow in the counting sort). */
TEST(balls_resting_far_apart_on_a_long_floor_keep_a_grid_row)
{
    tt_world *w = tt_world_create(NULL);
    tt_collision_settings cs = tt_collision_settings_default();
    ENSURE_OK(tt_world_set_collision(w, &cs));
    tt_shape_def sd = tt_shape_def_default();
    sd.type = TT_SHAPE_AABB;
    sd.a = (tt_vec2){-10, -1};
    sd.b = (tt_vec2){1010, 0};
    tt_shape_create(w, &sd);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.05;
    for (int i = 0; i < 100; i++) {
        pd.position = (tt_vec2){i * 10.0, 0.05};
        tt_particle_create(w, &pd);
    }
    tt__collide *c = tt__collide_peek(w);
    ENSURE(tt__grid_build(w, &c->scr.grid, 0.0));
    ENSURE(grid_sane(&c->scr.grid));
    for (int s = 0; s < 120; s++) ENSURE_OK(tt_world_step(w, 1.0 / 60));
    ENSURE(grid_sane(&c->scr.grid));
    double xy[200];
    ENSURE(tt_world_read_positions(w, xy, 100) == 100);
    for (int i = 0; i < 100; i++) {
        ENSURE_NEAR(xy[2 * i], i * 10.0, 1e-9);
        ENSURE_NEAR(xy[2 * i + 1], 0.05, 1e-3);
    }
    tt_world_destroy(w);
}

/* Point particles on one row with a cell size (given) far below their spacing. */
static tt_world *points_in_a_row(double cell_size, double y)
{
    tt_world *w = tt_world_create(NULL);
    tt_world_set_gravity(w, (tt_vec2){0, 0});
    tt_collision_settings cs = tt_collision_settings_default();
    cs.cell_size = cell_size;
    tt_world_set_collision(w, &cs);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.0;
    for (int i = 0; i < 100; i++) {
        pd.position = (tt_vec2){i * 1.0, y};
        tt_particle_create(w, &pd);
    }
    return w;
}

TEST(points_with_a_tiny_cell_size_keep_a_sane_grid)
{
    const double ys[] = {0.0, 0.05, 0.1, 0.3, -7.7, 1e6 + 0.1};
    for (unsigned k = 0; k < sizeof ys / sizeof ys[0]; k++) {
        tt_world *w = points_in_a_row(1e-3, ys[k]);
        tt__collide *c = tt__collide_peek(w);
        ENSURE(tt__grid_build(w, &c->scr.grid, 1e-3));
        ENSURE(grid_sane(&c->scr.grid));
        ENSURE(c->scr.grid.ncell <= 4 * c->scr.grid.n + 1024);
        for (int s = 0; s < 10; s++) ENSURE_OK(tt_world_step(w, 1.0 / 60));
        ENSURE(grid_sane(&c->scr.grid));
        tt_world_destroy(w);
    }
}

/* cell_size 1e-300: the cell counts are ±1e283 and more before they
 * become integers (negative when the mean rounds above the row, as at y =
 * 0.3 and −7.7, where the mean ± 4σ box is inverted by one rounding). */
TEST(an_absurdly_small_cell_size_does_not_overflow_the_cell_counts)
{
    const double sizes[] = {1e-300, 4.9e-324, 1e-12};
    const double ys[] = {0.3, 0.05, -7.7};
    for (unsigned k = 0; k < 9; k++) {
        tt_world *w = points_in_a_row(sizes[k % 3], ys[k / 3]);
        tt__collide *c = tt__collide_peek(w);
        ENSURE(tt__grid_build(w, &c->scr.grid, sizes[k % 3]));
        ENSURE(grid_sane(&c->scr.grid));
        ENSURE(c->scr.grid.ncell <= 4 * c->scr.grid.n + 1024);
        for (int s = 0; s < 10; s++) ENSURE_OK(tt_world_step(w, 1.0 / 60));
        ENSURE(grid_sane(&c->scr.grid));
        tt_ray_hit hit;
        ENSURE_OK(tt_world_raycast(w, (tt_vec2){-1, ys[k / 3]}, (tt_vec2){200, ys[k / 3]}, 0xFFFF, &hit));
        uint32_t np = 0;
        ENSURE_OK(tt_world_query_aabb(w, (tt_vec2){-1, ys[k / 3] - 1}, (tt_vec2){200, ys[k / 3] + 1}, 0xFFFF, NULL, 0, &np,
                                      NULL, 0, NULL));
        ENSURE(np == 100);
        tt_world_destroy(w);
    }
}

/* The pair grid while some particles sleep (grid_awake.c): it holds the
 * awake particles and the sleepers within reach of one, so a sleeping pile
 * adds nothing to it; the pairs are those of brute force over every
 * particle, whatever the radii, layers or distances. */

static uint32_t sleeping(const tt_world *w)
{
    tt_stats st;
    tt_world_get_stats(w, &st);
    return st.sleeping;
}

static void platform(tt_world *w, double x0, double x1, double top)
{
    tt_shape_def g = tt_shape_def_default();
    g.type = TT_SHAPE_AABB;
    g.a = (tt_vec2){x0, top - 1.0}, g.b = (tt_vec2){x1, top};
    ENSURE(tt_shape_is_valid(w, tt_shape_create(w, &g)));
}

/* Two rows of circles of radii 0.05 to 0.8 resting on two floors, some
 * touching their neighbours, some on another layer, all asleep: saved into
 * *buf, *size bytes. */
static void sleeping_rows(unsigned char **buf, size_t *size)
{
    tt_world *w = tt_world_create(NULL);
    tt_collision_settings cs = tt_collision_settings_default();
    ENSURE_OK(tt_world_set_collision(w, &cs));
    platform(w, -40.0, 40.0, 0.0);
    platform(w, -40.0, 40.0, 3.0);
    rng_state = 7;
    uint32_t m = 0;
    for (int row = 0; row < 2; row++)
        for (double x = -30.0; x < 30.0; m++) {
            tt_particle_def pd = tt_particle_def_default();
            pd.radius = rnd() < 0.1 ? 0.8 : 0.05 + 0.3 * rnd();
            x += pd.radius;
            pd.position = (tt_vec2){x, 3.0 * row + pd.radius};
            x += pd.radius + (rnd() < 0.4 ? 0.0 : 0.2 * rnd());
            if (rnd() < 0.1) pd.category = 2;
            tt_particle_create(w, &pd);
        }
    for (int s = 0; s < 600 && sleeping(w) < m; s++) tt_world_step(w, 1.0 / 60.0);
    ENSURE(sleeping(w) == m);
    ENSURE(tt_world_save(w, NULL, 0, size) == TT_ENOMEM);
    *buf = malloc(*size);
    ENSURE_OK(tt_world_save(w, *buf, *size, size));
    tt_world_destroy(w);
}

/* Awake particles dropped among the sleepers at random (radii 0 to 1.2,
 * pinned ones, one far off, some on another layer): the grid's pairs are
 * brute force's, and the grid holds far fewer than every particle. */
TEST(grid_with_sleepers_gives_the_brute_force_pair_set)
{
    unsigned char *buf = NULL;
    size_t size = 0;
    sleeping_rows(&buf, &size);
    uint64_t mixed = 0;
    for (uint64_t seed = 1; seed <= 16; seed++) {
        tt_world *w = tt_world_load(buf, size);
        ENSURE(w);
        const uint32_t asleep = sleeping(w);
        rng_state = seed * 0x9E3779B97F4A7C15ull + 1;
        for (int k = 0; k < 40; k++) {
            tt_particle_def pd = tt_particle_def_default();
            const double kind = rnd();
            pd.radius = kind < 0.05 ? 0.0 : 0.05 + rnd() * (kind < 0.5 ? 0.3 : 1.2);
            pd.position = (tt_vec2){rnd() * 64 - 32, rnd() * 5 - 0.5};
            if (kind > 0.97) pd.position = (tt_vec2){(rnd() - 0.5) * 2e6, (rnd() - 0.5) * 2e6};
            pd.pinned = kind > 0.9 && kind <= 0.93;
            if (rnd() < 0.1) pd.mask = 1;
            ENSURE(tt_particle_is_valid(w, tt_particle_create(w, &pd)));
        }
        ENSURE(sleeping(w) == asleep); /* made beside the sleepers: nothing woke */
        tt__collide *c = tt__collide_peek(w);
        c->scr.npairs = 0;
        ENSURE(tt__grid_detect(w, c));
        ENSURE(c->scr.grid.n < 40 + asleep / 2); /* the sleepers far from every awake one are not in it */
        const uint32_t ng = c->scr.npairs;
        uint64_t *g = pair_set(c);
        c->scr.npairs = 0;
        ENSURE(tt__brute_pairs(w, c));
        uint64_t *b = pair_set(c);
        ENSURE(ng == c->scr.npairs);
        for (uint32_t i = 0; i < ng && i < c->scr.npairs; i++) ENSURE(g[i] == b[i]);
        for (uint32_t i = 0; i < ng; i++) /* pairs of an awake particle with a sleeper */
            mixed += !(w->flags[g[i] >> 32] & TT__PF_ASLEEP) != !(w->flags[(uint32_t)g[i]] & TT__PF_ASLEEP);
        free(g);
        free(b);
        tt_world_destroy(w);
    }
    ENSURE(mixed > 50); /* the scenes test what they are for */
    free(buf);
}

/* One particle falling far above a sleeping pile: each substep's grid holds
 * it alone (one cell, or none when no grid was needed), and it falls freely
 * while the pile sleeps on. */
TEST(grid_of_one_awake_particle_beside_a_sleeping_pile_is_one_cell)
{
    unsigned char *buf = NULL;
    size_t size = 0;
    sleeping_rows(&buf, &size);
    tt_world *w = tt_world_load(buf, size);
    const uint32_t asleep = sleeping(w);
    tt_particle_def pd = tt_particle_def_default();
    pd.position = (tt_vec2){0.0, 1e4};
    pd.radius = 0.5;
    tt_particle p = tt_particle_create(w, &pd);
    for (int s = 0; s < 30; s++) {
        ENSURE_OK(tt_world_step(w, 1.0 / 60.0));
        tt_collision_stats st;
        ENSURE_OK(tt_world_get_collision_stats(w, &st));
        ENSURE(st.cells <= 1);
    }
    tt_vec2 x;
    tt_particle_get_position(w, p, &x);
    ENSURE(x.y < 1e4 - 1.2 && x.y > 1e4 - 1.3); /* 0.5 s of free fall: 1.23 m (1.27 as the steps sum it) */
    ENSURE(sleeping(w) == asleep);
    tt_world_destroy(w);
    free(buf);
}
