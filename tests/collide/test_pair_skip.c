/* Pairs on, none near (contact_skip.c): while no two particles can have
 * come within reach the grid is not built, and the results are those of
 * building it every substep. A cluster converging until it collides, and a
 * particle teleported onto another while the bound holds, against a twin
 * the bound never applies to (one far particle is a bullet: no shape, so
 * the bullet changes nothing else). */
#include "test.h"
#include "alloc_fail.h"
#include "collide/collide_internal.h"

#include <string.h>

enum { SIDE = 8, N = SIDE * SIDE };

static tt_world *cluster(tt_particle *ps, bool bullet)
{
    tt_world_def d = tt_world_def_default();
    tt_world *w = tt_world_create(&d);
    tt_world_set_substeps(w, 2);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.2;
    for (int i = 0; i < N; i++) {
        const double x = i % SIDE, y = i / SIDE;
        pd.position = (tt_vec2){x, y};
        pd.velocity = (tt_vec2){-(x - 3.5) * 0.6, -(y - 3.5) * 0.6}; /* meeting in about a second */
        ps[i] = tt_particle_create(w, &pd);
    }
    pd.position = (tt_vec2){-500.0, 0.0};
    pd.velocity = (tt_vec2){0.0, 0.0};
    ps[N] = tt_particle_create(w, &pd);
    tt_collision_settings cs = tt_collision_settings_default();
    tt_world_set_collision(w, &cs);
    if (bullet) tt_particle_set_bullet(w, ps[N], true);
    return w;
}

/* The twins stepped side by side, checked bit for bit; teleport: the step
 * before which particle 0 is put onto particle 1 (−1: never). Returns the
 * steps after which a's bound held, or −1 on a failed check. */
static int run_twins(int teleport, int *touching, int *after_teleport)
{
    tt_particle pa[N + 1], pb[N + 1];
    tt_world *a = cluster(pa, false), *b = cluster(pb, true);
    int skipping = 0, ok = 1;
    *touching = *after_teleport = 0;
    for (int s = 0; s < 120; s++) {
        if (s == teleport) { /* onto its neighbour while the bound holds */
            ok &= tt__collide_peek(a)->clear_ok;
            tt_vec2 x;
            tt_particle_get_position(a, pa[1], &x);
            tt_particle_set_position(a, pa[0], (tt_vec2){x.x + 0.1, x.y}, TT_MOVE_KEEP_VELOCITY);
            tt_particle_set_position(b, pb[0], (tt_vec2){x.x + 0.1, x.y}, TT_MOVE_KEEP_VELOCITY);
        }
        ok &= tt_world_step(a, 1.0 / 60) == TT_OK && tt_world_step(b, 1.0 / 60) == TT_OK;
        skipping += tt__collide_peek(a)->clear_ok;
        ok &= !tt__collide_peek(b)->clear_ok;
        tt_collision_stats st;
        tt_world_get_collision_stats(a, &st);
        *touching += st.pair_contacts > 0;
        if (s == teleport) *after_teleport = (int)st.pair_contacts;
        double xa[2 * (N + 1)], xb[2 * (N + 1)];
        tt_particles_get_positions(a, pa, N + 1, xa);
        tt_particles_get_positions(b, pb, N + 1, xb);
        ok &= memcmp(xa, xb, sizeof xa) == 0;
    }
    tt_world_destroy(a);
    tt_world_destroy(b);
    return ok ? skipping : -1;
}

TEST(pairs_skipped_while_none_is_near_match_a_grid_built_every_substep)
{
    int touching, after;
    const int skipping = run_twins(-1, &touching, &after);
    ENSURE(skipping >= 5); /* the bound was used, and ran out in time */
    ENSURE(touching > 20); /* the cluster met */
}

TEST(a_particle_teleported_near_another_ends_the_pair_skip_at_once)
{
    int touching, after;
    ENSURE(run_twins(6, &touching, &after) >= 5);
    ENSURE(after > 0); /* the pair was found in the step right after */
}

/* stats.cells counts the grid the last substep found its pairs in, not the
 * probe that found none (it showed the probe's wide cells, or a grid of
 * long ago, after a substep that built no pair grid). */
TEST(cells_stat_counts_the_pair_grid_not_the_probe)
{
    tt_world_def d = tt_world_def_default();
    tt_world *w = tt_world_create(&d);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.2;
    tt_particle p = tt_particle_create(w, &pd);
    pd.position = (tt_vec2){50.0, 0.0};
    tt_particle q = tt_particle_create(w, &pd);
    tt_collision_settings cs = tt_collision_settings_default();
    ENSURE_OK(tt_world_set_collision(w, &cs));
    tt_collision_stats st;
    for (int s = 0; s < 3; s++) ENSURE_OK(tt_world_step(w, 1.0 / 60));
    ENSURE_OK(tt_world_get_collision_stats(w, &st));
    ENSURE(st.pair_contacts == 0 && st.cells == 0); /* apart: no pair grid (a probe, or the bound) */
    tt_vec2 x;
    tt_particle_get_position(w, p, &x);
    ENSURE_OK(tt_particle_set_position(w, q, (tt_vec2){x.x + 0.3, x.y}, TT_MOVE_KEEP_VELOCITY));
    ENSURE_OK(tt_world_step(w, 1.0 / 60));
    ENSURE_OK(tt_world_get_collision_stats(w, &st));
    ENSURE(st.pair_contacts == 1 && st.cells > 0 && st.cells == tt__collide_peek(w)->scr.grid.ncell);
    ENSURE_OK(tt_particle_set_position(w, q, (tt_vec2){x.x + 50.0, x.y}, TT_MOVE_KEEP_VELOCITY));
    for (int s = 0; s < 3; s++) ENSURE_OK(tt_world_step(w, 1.0 / 60));
    ENSURE_OK(tt_world_get_collision_stats(w, &st));
    ENSURE(st.pair_contacts == 0 && st.cells == 0);
    tt_world_destroy(w);
}

/* Out of memory in the very substep whose probe found nothing near
 * (contact_undo.c puts the bound back): two particles on one spot fly apart
 * at 40 m/s. In the step's first substep they touch and are pushed, by the
 * third the probe finds them more than reach + gap apart and the bound
 * starts; in that same substep six particles resting inside a sensor make
 * the 18th event record, past the 16 reserved, whose allocation is refused.
 * The step fails and is put back; a bound kept from it would claim, in the
 * retried step's first substep, that the two touching particles are apart.
 * Each allocation of the step is refused in turn; the retried step and the
 * three after must match a twin that never ran out, bit for bit. */
enum { SENSED = 6, APART = SENSED + 2 };

static tt_world *fly_apart(tt_particle *ps)
{
    tt_world_def d = tt_world_def_default();
    d.substeps = 4;
    tt_world *w = tt_world_create(&d);
    tt_world_set_gravity(w, (tt_vec2){0.0, 0.0});
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.1;
    pd.position = (tt_vec2){0.0, 0.0};
    pd.velocity = (tt_vec2){-20.0, 0.0};
    ps[0] = tt_particle_create(w, &pd);
    pd.position = (tt_vec2){0.02, 0.0};
    pd.velocity = (tt_vec2){20.0, 0.0};
    ps[1] = tt_particle_create(w, &pd);
    pd.velocity = (tt_vec2){0.0, 0.0};
    for (int i = 0; i < SENSED; i++) { /* 1 m apart, far from each other and from the pair */
        pd.position = (tt_vec2){(double)i, 10.0};
        ps[2 + i] = tt_particle_create(w, &pd);
    }
    tt_shape_def sd = tt_shape_def_default();
    sd.type = TT_SHAPE_BOX;
    sd.position = (tt_vec2){2.5, 10.0};
    sd.half_extents = (tt_vec2){4.0, 1.0};
    sd.sensor = true;
    tt_shape_create(w, &sd);
    tt_collision_settings cs = tt_collision_settings_default();
    cs.events = TT_EVENT_BEGIN | TT_EVENT_PERSIST | TT_EVENT_END;
    tt_world_set_collision(w, &cs);
    return w;
}

TEST(a_step_out_of_memory_after_its_probe_found_nothing_keeps_no_pair_bound)
{
    long k = 0;
    bool refused = true;
    for (; refused && k < 1000; k++) {
        tt_particle pa[APART], pb[APART];
        tt_world *a = fly_apart(pa), *b = fly_apart(pb);
        tt_test_alloc_fail_from(k);
        const tt_result r = tt_world_step(a, 1.0 / 60);
        refused = tt_test_alloc_ok();
        if (r != TT_OK) ENSURE_OK(tt_world_step(a, 1.0 / 60)); /* the same step again, with memory */
        ENSURE_OK(tt_world_step(b, 1.0 / 60));
        ENSURE(tt__collide_peek(b)->clear_ok); /* the case: the bound began in that step */
        for (int s = 0; s < 3; s++) {
            ENSURE_OK(tt_world_step(a, 1.0 / 60));
            ENSURE_OK(tt_world_step(b, 1.0 / 60));
        }
        double xa[2 * APART], xb[2 * APART];
        tt_particles_get_positions(a, pa, APART, xa);
        tt_particles_get_positions(b, pb, APART, xb);
        if (memcmp(xa, xb, sizeof xa) != 0) printf("    allocation %ld refused: the particles differ after\n", k);
        ENSURE(memcmp(xa, xb, sizeof xa) == 0);
        ENSURE(tt_world_hash(a) == tt_world_hash(b));
        tt_world_destroy(a);
        tt_world_destroy(b);
    }
    ENSURE(!refused && k > 1);
}
