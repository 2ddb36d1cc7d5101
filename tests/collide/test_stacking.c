/* tether — stacking (tt_collision_settings.stacking, issue 21): mass
 * scaling by height keeps a deep pile from sinking into itself at few
 * sweeps, gives the same bits in scalar code and in vector lanes, and is
 * part of the world's state. */
#include "test.h"
#include "collide/collide_internal.h"
#include "scenes/scene.h"
#include "small_pour.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { STACK_ROWS = 100 };

/* A box 10 wide, and circles of radius 0.5 packed hexagonally in it at
 * rest, exactly touching, rows of 10 and 9 alternating: 950 circles, 100
 * rows, 86 m tall. Gravity −10, 1 substep, `iterations` sweeps, sleeping
 * off; stacking as given. */
static tt_world *hex_stack(double stacking, uint32_t iterations, uint32_t rows, tt_particle *ps, uint32_t *n)
{
    tt_world_def wd = tt_world_def_default();
    wd.gravity = (tt_vec2){0, -10};
    wd.substeps = 1;
    wd.iterations = iterations;
    wd.sleep = false;
    tt_world *w = tt_world_create(&wd);
    tt_collision_settings cs = tt_collision_settings_default();
    cs.stacking = stacking;
    if (tt_world_set_collision(w, &cs) != TT_OK) return NULL;
    tt_shape_def sd = tt_shape_def_default();
    sd.type = TT_SHAPE_AABB;
    sd.a = (tt_vec2){-1, -1}; sd.b = (tt_vec2){11, 0};   tt_shape_create(w, &sd);
    sd.a = (tt_vec2){-1, 0};  sd.b = (tt_vec2){0, 200};  tt_shape_create(w, &sd);
    sd.a = (tt_vec2){10, 0};  sd.b = (tt_vec2){11, 200}; tt_shape_create(w, &sd);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.5;
    uint32_t k = 0;
    for (uint32_t r = 0; r < rows; r++)
        for (uint32_t i = 0; i < (r % 2 ? 9u : 10u); i++) {
            pd.position = (tt_vec2){(r % 2 ? 1.0 : 0.5) + i, 0.5 + r * sqrt(0.75)};
            ps[k++] = tt_particle_create(w, &pd);
        }
    *n = k;
    return w;
}

/* The deepest overlap of two circles of radius 0.5, fraction of a radius. */
static double deepest(const tt_world *w, const tt_particle *ps, uint32_t n)
{
    double *x = malloc(2 * (size_t)n * sizeof *x), worst = 0.0;
    tt_particles_get_positions(w, ps, n, x);
    for (uint32_t i = 0; i < n; i++)
        for (uint32_t j = i + 1; j < n; j++) {
            const double dx = x[2 * i] - x[2 * j], dy = x[2 * i + 1] - x[2 * j + 1];
            if (fabs(dy) < 1.0 && fabs(dx) < 1.0) worst = fmax(worst, (1.0 - sqrt(dx * dx + dy * dy)) / 0.5);
        }
    free(x);
    return worst;
}

static double kinetic_per_kg(const tt_world *w, const tt_particle *ps, uint32_t n)
{
    double e = 0.0;
    for (uint32_t i = 0; i < n; i++) {
        tt_vec2 v;
        tt_particle_get_velocity(w, ps[i], &v);
        e += 0.5 * (v.x * v.x + v.y * v.y);
    }
    return e / n;
}

/* 950 circles packed 100 rows deep, at rest: rigid discs that hold each
 * other up, without overlap. At 1 substep × 8 sweeps the load of 100 rows
 * does not reach the floor in the sweeps of a step, and the pile sinks
 * into itself (3 % of a radius in 5 s); with stacking 2 it holds within 1 %
 * (0.17 %), and rests. */
TEST(stacking_holds_a_hundred_rows_at_rest_within_one_percent)
{
    tt_particle *ps = malloc(STACK_ROWS * 10 * sizeof *ps);
    double over[2], ke[2];
    for (int on = 0; on < 2; on++) {
        uint32_t n;
        tt_world *w = hex_stack(on ? 2.0 : 0.0, 8, STACK_ROWS, ps, &n);
        ENSURE(w && n == 950);
        over[on] = 0.0;
        for (int s = 0; s < 300; s++) {
            ENSURE_OK(tt_world_step(w, 1.0 / 60));
            if (s % 30 == 29) over[on] = fmax(over[on], deepest(w, ps, n));
        }
        ke[on] = kinetic_per_kg(w, ps, n);
        tt_world_destroy(w);
    }
    printf("    100 rows at rest, 1 x 8, 5 s: deepest overlap %.2f %% of a radius without stacking, %.3f %% with 2;"
           " KE %.1e / %.1e J/kg\n", 100 * over[0], 100 * over[1], ke[0], ke[1]);
    ENSURE(over[0] > 0.02); /* without it the pile is over the 1 % */
    ENSURE(over[1] <= 0.01);
    ENSURE(ke[1] <= 1e-4);
    free(ps);
}

/* The small pours from starts 1 and 2 at 1 × iterations, with or without
 * anchored friction: at 15 s no two circles more than deepest (a share of
 * a radius) into each other, and KE at most ke_max. */
static void small_pours(bool anchored, uint32_t iterations, double deepest, double ke_max)
{
    if (getenv("TT_MEMCHECK")) return; /* two 15 s pours: minutes under valgrind */
    for (uint64_t seed = 1; seed <= 2; seed++) {
        double deep, ke;
        ENSURE(small_pour(seed, anchored, iterations, 0.0, &deep, &ke));
        ENSURE(deep <= deepest);
        ENSURE(ke <= ke_max);
    }
}

/* With anchored friction: at 15 s at rest, and no two circles more than
 * 1.5 % of a radius into each other at 1 × 8. Pairs that pushed a particle
 * into the wall it leans on (the wall pushing it back, last, into its
 * neighbour) left the layers by the walls 1.8–6.2 % deep on these starts
 * (docs/collisions.md "Particles against a shape"); held off the walls,
 * 1.06 and 0.99 % (0.52–1.06 % on starts 1–8). */
TEST(stacking_with_anchored_friction_keeps_the_layers_by_the_walls_apart) { small_pours(true, 8, 0.015, 1e-4); }

/* At 1 × 12, what piles under 1 % needed before the warm start
 * (test_warm.c: 1 × 4 with it): the same pours at rest under 1 %, 0.37 and
 * 0.72 % (0.37–0.88 % on starts 1–8). */
TEST(stacking_with_anchored_friction_at_1x12_rests_under_one_percent) { small_pours(true, 12, 0.01, 1e-4); }

/* Without anchored friction the same pours rest under 1 % (KE ≤ 1e-9 J/kg
 * at 15 s): the walls' hold is not applied there, where it kept the piles
 * moving (2.4e-4 … 4.0e-3 J/kg on starts 0–3). */
TEST(stacking_alone_rests_in_a_box) { small_pours(false, 8, 0.01, 1e-6); }

/* A column that collapses into itself at landing: 2 000 circles by the
 * reference pour's rules in a box 10 wide (250 rows, the top one 274 m up),
 * stacking 2, 1 × 8, 20 s. It lands into itself (mean overlap 22 % of a
 * radius at 4 s, the deepest pairs on one centre), and the pile must come
 * apart without anything thrown: no circle ever higher than the highest
 * started. With pre-stabilisation unweighted, the stacked sweeps undid the
 * collapse as speed and threw a circle to 537.8 m (the 100 k pour's pile
 * stood 830 m high at 16 s). */
TEST(stacking_undoes_a_collapsed_column_without_throwing_it)
{
    ts_scene sc;
    ts_scene_pour(&sc, 2000, 10.0);
    ts_tether_settings set = ts_tether_settings_default();
    ts_tether t;
    const char *why = NULL;
    ENSURE(ts_tether_build(&sc, &set, &t, &why) == TT_OK);
    const double top = ts_scene_highest(&sc);
    tt_collision_settings cs;
    tt_world_get_collision(t.world, &cs);
    cs.stacking = 2.0;
    bool ok = tt_world_set_collision(t.world, &cs) == TT_OK;
    double *xy = malloc(2 * sizeof *xy * t.circle_count), highest = 0.0;
    const int steps = getenv("TT_MEMCHECK") ? 400 : 1200; /* 400 already caught the throw */
    for (int s = 0; ok && xy && s < steps; s++) {
        ok = tt_world_step(t.world, sc.dt) == TT_OK &&
             tt_particles_get_positions(t.world, t.circles, t.circle_count, xy) == TT_OK;
        for (uint32_t i = 0; ok && i < t.circle_count; i++) highest = fmax(highest, xy[2 * i + 1]);
    }
    printf("    2 000 circles in a box 10 wide, stacking 2, 1 x 8: highest centre %.1f m (started at most %.1f m)\n", highest,
           top);
    free(xy);
    ts_tether_free(&t);
    ts_scene_free(&sc);
    ENSURE(ok);
    ENSURE(highest <= top);
}

/* Stacking's weights in the sweeps and the velocity pass, in vector lanes
 * and in scalar code: the same bits; with anchored friction too (its
 * friction in the lanes beside the weighted pushes, the pushes of particles
 * against the walls in scalar code), and with its warm start. A stack 30
 * rows deep with circles dropped on it from 20 m (impacts, sliding, a pile
 * that settles). */
static uint64_t stacking_run(tt__simd_mode mode, bool anchored, double warm)
{
    tt_particle ps[400];
    uint32_t n;
    tt_world *w = hex_stack(3.0, 6, 30, ps, &n);
    if (!w || !tt__contacts_set_simd(w, mode)) {
        tt_world_destroy(w);
        return 0;
    }
    tt_collision_settings cs;
    tt_world_get_collision(w, &cs);
    cs.anchored_friction = anchored;
    cs.warm_start = warm;
    if (tt_world_set_collision(w, &cs) != TT_OK) {
        tt_world_destroy(w);
        return 0;
    }
    tt_particle_def pd = tt_particle_def_default();
    for (int j = 0; j < 40; j++) {
        pd.radius = 0.3 + 0.005 * j;
        pd.position = (tt_vec2){0.7 + 0.21 * j, 45.0 + (j % 5)};
        tt_particle_create(w, &pd);
    }
    for (int s = 0; s < 150; s++) tt_world_step(w, 1.0 / 60);
    const uint64_t h = tt_world_hash(w);
    tt_world_destroy(w);
    return h;
}

TEST(stacking_is_bit_identical_in_vector_lanes_and_scalar_code)
{
    for (int anchored = 0; anchored < 3; anchored++) { /* 2: anchored with warm start */
        const double warm = anchored == 2 ? 0.75 : 0.0;
        const uint64_t ref = stacking_run(TT__SIMD_SCALAR, anchored, warm);
        ENSURE(ref != 0);
        const tt__simd_mode modes[] = {TT__SIMD_AUTO, TT__SIMD_AVX2, TT__SIMD_AVX512};
        int ran = 0;
        for (int m = 0; m < 3; m++) {
            const uint64_t h = stacking_run(modes[m], anchored, warm);
            if (h == 0) continue; /* not in this build or on this processor */
            ENSURE(h == ref);
            ran++;
        }
        printf("    stacking%s%s: %d vector kernel(s) give the scalar code's bits\n", anchored ? " with anchored friction" : "",
               warm > 0.0 ? " and warm start" : "", ran);
    }
}

/* The setting is checked, kept, saved and loaded; a world without it
 * saves what it saved before the setting existed (the golden hashes). */
TEST(stacking_is_checked_and_saved)
{
    tt_world *w = tt_world_create(NULL);
    tt_collision_settings cs = tt_collision_settings_default();
    ENSURE(cs.stacking == 0.0);
    cs.stacking = -1.0;
    ENSURE(tt_world_set_collision(w, &cs) == TT_EINVAL);
    ENSURE(strstr(tt_last_error(w), "stacking") != NULL);
    cs.stacking = NAN;
    ENSURE(tt_world_set_collision(w, &cs) == TT_EINVAL);
    cs.stacking = 0.0;
    ENSURE_OK(tt_world_set_collision(w, &cs));
    size_t off = 0, on = 0;
    tt_world_save(w, NULL, 0, &off);
    cs.stacking = 2.5;
    ENSURE_OK(tt_world_set_collision(w, &cs));
    tt_world_save(w, NULL, 0, &on);
    ENSURE(on == off + 12); /* a marker and the number, only when on */
    void *buf = malloc(on);
    ENSURE_OK(tt_world_save(w, buf, on, NULL));
    tt_world *v = tt_world_load(buf, on);
    ENSURE(v != NULL);
    tt_collision_settings got;
    ENSURE_OK(tt_world_get_collision(v, &got));
    ENSURE(got.stacking == 2.5);
    ENSURE(tt_world_hash(v) == tt_world_hash(w));
    tt_world_destroy(v);
    free(buf);
    tt_world_destroy(w);
}
