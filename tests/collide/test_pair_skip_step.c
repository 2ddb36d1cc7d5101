/* Pairs on, none near, planned before the step (contact_skip.c,
 * tt__pairs_plan_step): a step the skip's bound holds through measures
 * nothing and keeps no undo copy, and its results are those of a twin that
 * builds the grid every substep (one far particle is a bullet: no shape, so
 * the bullet changes nothing else). Four substeps a step, so that pairs
 * come within reach inside a step after a quiet start; far from the origin
 * (rounding of x + d) and fast (large displacements), with gravity. */
#include "test.h"
#include "alloc_fail.h"
#include "collide/collide_internal.h"

#include <string.h>

enum { SIDE = 6, N = SIDE * SIDE, STEPS = 150 };

typedef struct scene {
    double ox, oy;  /* where the lattice is (1 m apart, radius 0.2) */
    double vx, vy;  /* the velocity every particle shares */
    double close;   /* particle 0's extra speed towards particle 1, m/s */
    double pin_below; /* > 0: a pinned particle this far under column 2 (gravity brings the lattice onto it) */
    double gravity;   /* downwards, m/s² */
    int drop_at;      /* the step before which gravity is switched on (at rest before, as one) */
} scene;

static tt_world *make(const scene *sc, tt_particle *ps, bool bullet)
{
    tt_world_def d = tt_world_def_default();
    d.substeps = 4;
    tt_world *w = tt_world_create(&d);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.2;
    for (int i = 0; i < N; i++) {
        pd.position = (tt_vec2){sc->ox + i % SIDE, sc->oy + i / SIDE};
        pd.velocity = (tt_vec2){sc->vx + (i == 0 ? sc->close : 0.0), sc->vy};
        ps[i] = tt_particle_create(w, &pd);
    }
    pd.position = (tt_vec2){sc->ox - 500.0, sc->oy};
    pd.velocity = (tt_vec2){sc->vx, sc->vy};
    ps[N] = tt_particle_create(w, &pd);
    if (sc->pin_below > 0.0) {
        pd.position = (tt_vec2){sc->ox + 2.0, sc->oy - sc->pin_below};
        pd.pinned = true;
        ps[N + 1] = tt_particle_create(w, &pd);
    }
    tt_collision_settings cs = tt_collision_settings_default();
    tt_world_set_collision(w, &cs);
    if (bullet) tt_particle_set_bullet(w, ps[N], true);
    tt_world_set_gravity(w, (tt_vec2){0.0, sc->drop_at ? 0.0 : -sc->gravity});
    return w;
}

/* Whether the step just taken was planned clear (then it kept no copy). */
static bool planned(const tt_world *w)
{
    const tt__collide *c = tt__collide_peek(w);
    tt_stats st;
    tt_world_get_stats(w, &st);
    return c->step_clear && c->step_at + 1 == st.steps && c->scr.bounded;
}

/* The twins stepped side by side, bit for bit; the steps planned clear,
 * and the steps that had a pair contact, or −1 on a failed check. */
static int run_twins(const scene *sc, int *touching)
{
    tt_particle pa[N + 2], pb[N + 2];
    tt_world *a = make(sc, pa, false), *b = make(sc, pb, true);
    const uint32_t n = N + 1 + (sc->pin_below > 0.0);
    int clear = 0, ok = 1;
    *touching = 0;
    for (int s = 0; s < STEPS && ok; s++) {
        if (s == sc->drop_at) { /* the epoch stays: the plan sees the lattice at rest, about to fall */
            tt_world_set_gravity(a, (tt_vec2){0.0, -sc->gravity});
            tt_world_set_gravity(b, (tt_vec2){0.0, -sc->gravity});
        }
        ok &= tt_world_step(a, 1.0 / 60) == TT_OK && tt_world_step(b, 1.0 / 60) == TT_OK;
        clear += planned(a);
        ok &= !tt__collide_peek(b)->step_clear;
        tt_collision_stats sa, sb;
        tt_world_get_collision_stats(a, &sa);
        tt_world_get_collision_stats(b, &sb);
        ok &= sa.pair_contacts == sb.pair_contacts;
        *touching += sa.pair_contacts > 0;
        double xa[2 * (N + 2)], xb[2 * (N + 2)];
        tt_particles_get_positions(a, pa, n, xa);
        tt_particles_get_positions(b, pb, n, xb);
        ok &= memcmp(xa, xb, 2 * n * sizeof *xa) == 0;
        if (!ok) printf("    twins differ after step %d\n", s);
    }
    tt_world_destroy(a);
    tt_world_destroy(b);
    printf("    %d steps planned clear, %d with pair contacts\n", clear, *touching);
    return ok ? clear : -1;
}

/* Particle 0 closes on particle 1 at 0.9 m/s: they meet inside a step, some
 * steps after the last one planned clear. */
TEST(steps_planned_clear_match_a_grid_built_every_substep)
{
    const scene sc = {0.0, 0.0, 0.0, 0.0, 0.9, 0.0, 9.81, 0};
    int touching;
    const int clear = run_twins(&sc, &touching);
    ENSURE(clear >= 10);
    ENSURE(touching > 0);
}

TEST(steps_planned_clear_match_far_from_the_origin_and_fast)
{
    const scene far = {1e6, -1e6, 0.0, 0.0, 0.9, 0.0, 9.81, 0}, fast = {1e6, 1e6, 400.0, -250.0, 0.9, 0.0, 9.81, 0};
    int touching;
    ENSURE(run_twins(&far, &touching) >= 10);
    ENSURE(touching > 0);
    ENSURE(run_twins(&fast, &touching) >= 10);
    ENSURE(touching > 0);
}

/* A pinned particle does not fall with the rest: a lattice at rest above
 * it, gravity switched on, closes on it by g·h² more each substep while
 * the displacements as the step begins are all 0; it meets the particle
 * when the twin does. */
TEST(a_pinned_particle_the_lattice_falls_onto_is_met_as_by_the_grid)
{
    const scene sc = {1e6, 0.0, 0.0, 0.0, 0.0, 1.5, 20000.0, 10};
    int touching;
    ENSURE(run_twins(&sc, &touching) >= 5);
    ENSURE(touching > 0);
}

/* Every step first tried with every allocation refused: one planned clear
 * makes none (it keeps no copy, so none may fail inside it), any other
 * fails whole, the world as it was, or makes none either; retried, the
 * world goes on as its twin that never ran out, through the steps where
 * pairs first appear after the planned ones. */
TEST(out_of_memory_around_steps_planned_clear_leaves_the_world_as_it_was)
{
    const scene sc = {1e6, -1e6, 0.0, 0.0, 0.9, 0.0, 9.81, 0};
    tt_particle pa[N + 2], pb[N + 2];
    tt_world *a = make(&sc, pa, false), *b = make(&sc, pb, false);
    int clear = 0, failed = 0, touching = 0;
    for (int s = 0; s < 80; s++) {
        const uint64_t h0 = tt_world_hash(a);
        tt_test_alloc_fail_from(0);
        const tt_result r = tt_world_step(a, 1.0 / 60);
        const bool refused = tt_test_alloc_ok();
        if (planned(a)) {
            ENSURE(r == TT_OK && !refused);
            clear++;
        } else if (r != TT_OK) {
            ENSURE(r == TT_ENOMEM && refused && tt_world_hash(a) == h0);
            ENSURE_OK(tt_world_step(a, 1.0 / 60));
            failed++;
        }
        ENSURE_OK(tt_world_step(b, 1.0 / 60));
        ENSURE(tt_world_hash(a) == tt_world_hash(b));
        tt_collision_stats st;
        tt_world_get_collision_stats(a, &st);
        touching += st.pair_contacts > 0;
    }
    ENSURE(clear >= 10 && failed > 0 && touching > 0);
    tt_world_destroy(a);
    tt_world_destroy(b);
}
