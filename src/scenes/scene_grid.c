/* tether — particles on a square lattice: the free-falling, packed and
 * drawn crowds the benchmarks measure (collisions, pay-only, rendering),
 * placed by one rule so a figure's scene is the one its caption names. */
#include "scene.h"

ts_grid ts_grid_default(void)
{
    ts_grid g = {0, 1, {0, 0}, 1, 0.5, 0.5, 0};
    return g;
}

uint32_t ts_grid_add(tt_world *w, const ts_grid *g)
{
    if (!w || !g || g->columns == 0) return 0;
    tt_particle_def pd = tt_particle_def_default();
    uint32_t made = 0;
    for (uint32_t i = 0; i < g->count; i++) {
        const bool big = g->big_every && i % g->big_every == 0;
        pd.radius = big ? g->big_radius : g->radius;
        pd.position = (tt_vec2){g->corner.x + g->spacing * (0.5 + i % g->columns),
                                g->corner.y + g->spacing * (0.5 + i / g->columns)};
        if (tt_particle_create(w, &pd).gen == 0) break;
        made++;
    }
    return made;
}
