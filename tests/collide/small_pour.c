/* tether — the small pour (small_pour.h). */
#include "small_pour.h"
#include "scenes/scene.h"

#include <stdio.h>
#include <stdlib.h>

bool small_pour(uint64_t seed, bool anchored, uint32_t iterations, double warm, double *deepest_at_end, double *ke)
{
    ts_scene sc;
    ts_scene_pour(&sc, 1000, 20.0);
    ts_tether_settings set = ts_tether_settings_default();
    set.substeps = 1;
    set.iterations = iterations;
    ts_tether t;
    const char *why = NULL;
    bool ok = ts_tether_build(&sc, &set, &t, &why) == TT_OK && ts_tether_jitter(&t, seed, 0.05) == TT_OK;
    tt_collision_settings cs;
    tt_world_get_collision(t.world, &cs);
    cs.anchored_friction = anchored;
    cs.stacking = 2.0;
    cs.warm_start = warm;
    ok = ok && tt_world_set_collision(t.world, &cs) == TT_OK;
    for (int s = 0; ok && s < 900; s++) ok = tt_world_step(t.world, sc.dt) == TT_OK;
    double *xy = malloc(2 * sizeof *xy * t.circle_count), r = 0.0;
    ok = ok && xy && tt_particles_get_positions(t.world, t.circles, t.circle_count, xy) == TT_OK &&
         tt_particle_get_radius(t.world, t.circles[0], &r) == TT_OK;
    if (ok) {
        ts_pile p;
        ts_pile_measure(xy, t.circle_count, r, &p);
        *deepest_at_end = p.max_overlap;
        *ke = ts_tether_kinetic_per_kg(&t);
        printf("    start %d, 1 x %u%s", (int)seed, iterations, anchored ? ", anchored friction" : "");
        if (warm > 0.0) printf(", warm start %.2f", warm);
        printf(": deepest overlap %.2f %% of a radius, mean %.3f %%; KE %.1e J/kg at 15 s\n", 100 * p.max_overlap,
               100 * p.mean_overlap, *ke);
    }
    free(xy);
    ts_tether_free(&t);
    ts_scene_free(&sc);
    return ok;
}
