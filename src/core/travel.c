/* tether — substeps by speed (tt_world_def.max_travel). A contact is found
 * and solved from where its particles are at the substep's start, so one
 * that crosses half a diameter in a substep meets its neighbours too late:
 * a column landing at 80 m/s, 1.3 m a step with radius 0.5, sinks into
 * itself (the 100 k pour at 1 × 8 collapses: circles on one centre, a mean
 * overlap of 20 % of a radius over the run). Substeps keep each move short,
 * but a fixed count is paid every step, also while the scene rests; this
 * asks for them only in the steps where something is fast. The count is
 * read from the world's state as the step begins (the same state gives the
 * same count, so replays, snapshots and journals step alike) and a larger
 * one is a time-corrected Verlet step like any change of dt. */
#include "core/internal.h"
#include "tether/collide.h"
#include "tether/terrain.h"

#include <math.h>

/* Whether a step can find contacts: particle contacts on, or a shape or a
 * terrain. Substeps by speed is for contacts, so a world without them runs
 * its set substeps however fast it is (and can run backwards). */
bool tt__world_collides(const tt_world *w)
{
    tt_collision_settings cs;
    return tt_world_shape_count(w) > 0 || tt_world_terrain_count(w) > 0 ||
           (tt_world_get_collision(w, &cs) == TT_OK && cs.particles);
}

/* The substeps the step of dt runs: w->substeps, or more where contacts
 * can be found and a movable, awake particle with a radius would travel
 * farther than max_travel radii in one (|v|·dt + |g|·dt²/2 over the step),
 * at most max_substeps. */
uint32_t tt__travel_substeps(const tt_world *w, double dt)
{
    const uint32_t base = w->substeps;
    if (w->max_travel == 0.0 || w->max_substeps <= base || !tt__world_collides(w)) return base;
    const double fall = 0.5 * sqrt(w->gravity.x * w->gravity.x + w->gravity.y * w->gravity.y) * dt * dt;
    double need = 0.0; /* the largest travel over the step, in radii */
    for (uint32_t i = 0; i < w->ppool.count; i++) {
        if (!(w->flags[i] & TT__PF_ALIVE) || w->inv_mass[i] == 0.0 || w->radius[i] <= 0.0f) /* inverse mass 0: pinned or asleep */
            continue;
        const tt_vec2 v = tt__velocity(w, i);
        const double reach = (sqrt(v.x * v.x + v.y * v.y) * dt + fall) / (double)w->radius[i];
        need = reach > need ? reach : need;
    }
    const double n = ceil(need / w->max_travel); /* need ≤ TT_DIVERGED·dt/r: finite, or +inf for r tiny */
    if (!(n < (double)w->max_substeps)) return w->max_substeps;
    return n > (double)base ? (uint32_t)n : base;
}
