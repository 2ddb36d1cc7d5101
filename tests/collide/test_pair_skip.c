/* Pairs on, none near (contact_skip.c): while no two particles can have
 * come within reach the grid is not built, and the results are those of
 * building it every substep. A cluster converging until it collides, and a
 * particle teleported onto another while the bound holds, against a twin
 * the bound never applies to (one far particle is a bullet: no shape, so
 * the bullet changes nothing else). */
#include "test.h"
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
    ENSURE(st.pair_contacts == 1 && st.cells > 0 && st.cells == tt__collide_peek(w)->grid.ncell);
    ENSURE_OK(tt_particle_set_position(w, q, (tt_vec2){x.x + 50.0, x.y}, TT_MOVE_KEEP_VELOCITY));
    for (int s = 0; s < 3; s++) ENSURE_OK(tt_world_step(w, 1.0 / 60));
    ENSURE_OK(tt_world_get_collision_stats(w, &st));
    ENSURE(st.pair_contacts == 0 && st.cells == 0);
    tt_world_destroy(w);
}
