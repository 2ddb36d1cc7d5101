/* tether — time reversal (src/core/reverse.c): forward N steps, reverse,
 * N steps, reverse comes back to the start: bit for bit where every
 * operation is exact (dyadic numbers under gravity), to rounding with
 * springs in floating point (measured and printed: the README's table);
 * any world with something irreversible is refused, naming it. */
#include "test.h"
#include "core/scenes.h"

#include <tether.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static tt_world *verlet_world(tt_vec2 g)
{
    tt_world_def wd = tt_world_def_default();
    wd.gravity = g;
    wd.integrator = TT_VERLET;
    wd.dt_hint = 1.0 / 64;
    return tt_world_create(&wd);
}

/* Largest distance of any particle from where it was (xy0: 2n doubles). */
static double max_error(const tt_world *w, const double *xy0, uint32_t n)
{
    double *xy = malloc(2 * (size_t)n * sizeof *xy);
    uint32_t got = 0;
    got = tt_world_read_positions(w, xy, n);
    double e = 0;
    for (uint32_t i = 0; i < 2 * got; i++) e = fmax(e, fabs(xy[i] - xy0[i]));
    free(xy);
    return e;
}

TEST(reverse_gravity_with_dyadic_numbers_comes_back_bit_for_bit)
{
    tt_world *w = verlet_world((tt_vec2){0, -8});
    ENSURE(w);
    for (int i = 0; i < 100; i++) {
        tt_particle_def pd = tt_particle_def_default();
        pd.position = (tt_vec2){i / 1024.0, 100 + i / 256.0};
        pd.velocity = (tt_vec2){(i % 7) / 8.0, (i % 5) / 4.0};
        tt_particle_create(w, &pd);
    }
    tt_world_step(w, 1.0 / 64); /* the exact first step of a set velocity is not reversible: start after it */
    for (int s = 0; s < 1000; s++) tt_world_step(w, 1.0 / 64);
    ENSURE_OK(tt_world_reverse(w));
    for (int s = 0; s < 1000; s++) tt_world_step(w, 1.0 / 64);
    ENSURE_OK(tt_world_reverse(w));
    tt_stats st;
    tt_world_get_stats(w, &st);
    ENSURE(st.steps == 2001); /* the counters went on; the state is the start's */
    double xy0[200], xy[200];
    uint32_t got;
    /* positions bit for bit: compare with a fresh run of one step */
    tt_world *fresh = verlet_world((tt_vec2){0, -8});
    for (int i = 0; i < 100; i++) {
        tt_particle_def pd = tt_particle_def_default();
        pd.position = (tt_vec2){i / 1024.0, 100 + i / 256.0};
        pd.velocity = (tt_vec2){(i % 7) / 8.0, (i % 5) / 4.0};
        tt_particle_create(fresh, &pd);
    }
    tt_world_step(fresh, 1.0 / 64);
    got = tt_world_read_positions(fresh, xy0, 100);
    got = tt_world_read_positions(w, xy, 100);
    ENSURE(got == 100 && memcmp(xy, xy0, sizeof xy) == 0);
    /* and the next step too (the previous positions came back as well) */
    tt_world_step(fresh, 1.0 / 64);
    tt_world_step(w, 1.0 / 64);
    got = tt_world_read_positions(fresh, xy0, 100);
    got = tt_world_read_positions(w, xy, 100);
    ENSURE(memcmp(xy, xy0, sizeof xy) == 0);
    tt_world_destroy(fresh);
    tt_world_destroy(w);
}

/* A 40 × 25 spring network (1 000 particles, undamped springs to the
 * right and below, the top row pinned) under gravity: the round trip in
 * floating point, its error printed for the README. */
TEST(reverse_a_spring_network_in_floating_point_comes_back_to_rounding)
{
    enum { COLS = 40, ROWS = 25, N = COLS * ROWS };
    const int runs[] = {100, 1000, 10000};
    for (int r = 0; r < 3; r++) {
        tt_world *w = verlet_world((tt_vec2){0, -9.81});
        ENSURE(w);
        scene_spring_network(w, COLS, ROWS);
        tt_world_step(w, 1.0 / 60);
        double xy0[2 * N];
        uint32_t got;
        got = tt_world_read_positions(w, xy0, N);
        ENSURE(got == N);
        for (int s = 0; s < runs[r]; s++) tt_world_step(w, 1.0 / 60);
        const double moved = max_error(w, xy0, N);
        ENSURE_OK(tt_world_reverse(w));
        for (int s = 0; s < runs[r]; s++) tt_world_step(w, 1.0 / 60);
        ENSURE_OK(tt_world_reverse(w));
        const double err = max_error(w, xy0, N);
        printf("reverse: 1000-particle spring network, %5d steps at 1/60 s forward and back: largest error %.3g m (it moved up to %.3g m)\n",
               runs[r], err, moved);
        ENSURE(moved > 0.1);
        ENSURE(err < 1e-6 * moved); /* rounding, not a wrong reversal (which would be of the order of `moved`) */
        tt_world_destroy(w);
    }
}

TEST(reverse_refuses_every_irreversible_feature_naming_it_and_changes_nothing)
{
    struct { const char *expect; int kind; } cases[] = {
        {"integrator", 0}, {"velocity damping", 1}, {"constraints", 2}, {"collisions", 3}, {"spring damping", 4},
        {"a velocity set since the last step", 5}, {"collisions", 6}, {"collisions", 7},
    };
    for (unsigned k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        tt_world *w = verlet_world((tt_vec2){0, -10});
        tt_particle_def pd = tt_particle_def_default();
        tt_particle a = tt_particle_create(w, &pd);
        pd.position = (tt_vec2){1, 0};
        tt_particle b = tt_particle_create(w, &pd);
        tt_world_step(w, 1.0 / 60);
        switch (cases[k].kind) {
        case 0: tt_world_set_integrator(w, TT_RK4); break;
        case 1: tt_world_set_damping(w, 0.1); break;
        case 2: { tt_distance_def dd = tt_distance_def_default(); dd.a = a; dd.b = b; tt_distance_create(w, &dd); break; }
        case 3: { tt_shape_def sd = tt_shape_def_default(); sd.a = (tt_vec2){-5, -5}; sd.b = (tt_vec2){5, -5}; tt_shape_create(w, &sd); break; }
        case 4: { tt_spring_def sd = tt_spring_def_default(); sd.a = a; sd.b = b; sd.damping = 0.5; tt_spring_create(w, &sd); break; }
        case 5: tt_particle_set_velocity(w, a, (tt_vec2){1, 2}); break;
        case 6: { /* a terrain alone, particle contacts off */
            tt_mask *m = tt_mask_create(8, 8, true);
            tt_terrain_def td = tt_terrain_def_default();
            td.solid = m;
            td.origin = (tt_vec2){-5, -5};
            tt_terrain_create(w, &td);
            tt_mask_destroy(m);
            break;
        }
        case 7: { /* particle contacts, and substeps by speed with them */
            tt_collision_settings cs = tt_collision_settings_default();
            tt_world_set_collision(w, &cs);
            tt_world_set_travel(w, 0.5, 8);
            break;
        }
        }
        const uint64_t h = tt_world_hash(w);
        ENSURE(tt_world_reverse(w) == TT_ESTATE);
        if (!strstr(tt_last_error(w), cases[k].expect))
            tt_test_fail(__FILE__, __LINE__, "'%s' does not name '%s'", tt_last_error(w), cases[k].expect);
        ENSURE(tt_world_hash(w) == h);
        tt_world_destroy(w);
    }
    ENSURE(tt_world_reverse(NULL) == TT_EINVAL);
}
