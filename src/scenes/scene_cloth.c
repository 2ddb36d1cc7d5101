/* tether — the hung cloth of issue 21: the scene the cloth strain bench,
 * the constraint solver bench and the cloth tests all measure, built in one
 * place so their figures are about the same cloth; and the cloth catching
 * balls that the solver's layout is measured and tested on (issue 12). */
#include "scene.h"

ts_hung_cloth ts_hung_cloth_default(void)
{
    ts_hung_cloth d = {128, TT_GAUSS_SEIDEL, 1, 10, true, false};
    return d;
}

tt_world *ts_hung_cloth_build(const ts_hung_cloth *d, tt_composite *cloth)
{
    tt_world_def wd = tt_world_def_default();
    wd.order = d->order;
    wd.substeps = d->substeps;
    wd.iterations = d->iterations;
    wd.tolerance = 0; /* the whole budget every step: fixed work */
    wd.capacity = d->n * d->n;
    wd.sleep = false; /* issue 21 measures awake: a cloth come to rest would sleep and hide its cost */
    tt_world *w = tt_world_create(&wd);
    if (!w) return NULL;
    tt_cloth_def cd = tt_cloth_def_default();
    cd.columns = cd.rows = d->n;
    cd.width = cd.height = 0.02 * (d->n - 1); /* 2 cm between particles */
    cd.common.mass = 0.001;
    cd.pin_top_row = d->top_row;
    cd.long_range = d->long_range;
    const tt_composite c = tt_cloth_create(w, &cd);
    if (c.gen == 0) {
        tt_world_destroy(w);
        return NULL;
    }
    if (cloth) *cloth = c;
    return w;
}

tt_world *ts_cloth_catch_build(const ts_cloth_catch *d, tt_composite *cloth)
{
    if (d->n < 2) return NULL;
    tt_world_def wd = tt_world_def_default();
    wd.iterations = d->iterations;
    wd.tolerance = 0; /* the whole budget every step: fixed work */
    wd.capacity = d->n * d->n + d->balls;
    tt_world *w = tt_world_create(&wd);
    if (!w) return NULL;
    const tt_collision_settings cs = tt_collision_settings_default();
    tt_cloth_def cd = tt_cloth_def_default();
    cd.columns = cd.rows = d->n;
    cd.width = cd.height = 0.02 * (d->n - 1);
    cd.common.mass = 0.001;
    cd.common.radius = 0.01;
    const tt_composite c = tt_world_set_collision(w, &cs) == TT_OK ? tt_cloth_create(w, &cd) : (tt_composite){0};
    bool ok = c.gen != 0;
    if (cloth) *cloth = c;
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.02;
    pd.mass = 0.01;
    const uint32_t per_row = (uint32_t)(cd.width / 0.05) + 1;
    for (uint32_t i = 0; ok && i < d->balls; i++) {
        const uint32_t row = i / per_row;
        pd.position = (tt_vec2){0.05 * (i % per_row) + 0.025 * (row % 2), 0.1 + 0.05 * row};
        ok = tt_particle_create(w, &pd).gen != 0;
    }
    if (!ok) {
        tt_world_destroy(w);
        return NULL;
    }
    return w;
}
