/* tether — time reversal. Position Verlet, x⁺ = 2x − x⁻ + a(x)·h², is
 * symmetric in time: swap x and x⁻ and the same steps run the motion
 * backwards. That holds while nothing depends on velocity or takes energy
 * out (damping, spring damping, constraints' velocity fix-ups, contacts,
 * friction), so the call refuses any world that has such a thing, naming
 * it. In floating point each step rounds, and backwards steps round
 * differently: the round trip comes back close, not bit for bit (the test
 * measures how close). */
#include "core/internal.h"
#include "core/spin.h"
#include "tether/constraint.h"

/* What of w stops its motion from running backwards, or NULL. */
static const char *irreversible(const tt_world *w)
{
    if (w->integrator != TT_VERLET) return "the integrator (only 'verlet' keeps the previous position; this world uses another)";
    if (w->damping != 0.0) return "velocity damping (damping > 0)";
    if (tt_world_constraint_count(w) > 0) return "constraints (position corrections are not symmetric in time)";
    /* substeps by speed acts only here too (a step backwards would start from other speeds, so run another count) */
    if (tt__world_collides(w)) return "collisions (shapes, terrain or particle contacts)";
    for (uint32_t i = 0; i < w->spool.count; i++)
        if (w->springs[i].alive && w->springs[i].c != 0.0) return "spring damping (a spring with damping > 0)";
    for (uint32_t k = 0; k < w->fresh_count; k++)
        if (w->flags[w->fresh[k]] & TT__PF_FRESH) return "a velocity set since the last step (step once first)";
    return NULL;
}

tt_result tt_world_reverse(tt_world *w)
{
    TT_CHECK_WORLD(w, "tt_world_reverse");
    const char *why = irreversible(w);
    if (why) return tt__fail(w, TT_ESTATE, "tt_world_reverse: cannot run backwards: %s", why);
    const uint32_t n = w->ppool.count;
    const double q = w->fixed_point;
    for (uint32_t i = 0; i < n; i++) {
        if (!(w->flags[i] & TT__PF_ALIVE)) continue;
        double x = w->px[i], y = w->py[i];
        /* in the worlds accepted here (no contacts, so no
         * pre-stabilisation, which moves x_old) x_old is on the fixed-point
         * lattice after every step, but an impulse since may have moved it
         * off; positions never leave it, so the swap snaps */
        w->px[i] = q != 0.0 ? tt__fixed_snap(q, w->qx[i]) : w->qx[i];
        w->py[i] = q != 0.0 ? tt__fixed_snap(q, w->qy[i]) : w->qy[i];
        w->qx[i] = x;
        w->qy[i] = y;
    }
    tt__spin *sp = tt__spin_peek(w); /* particles that turn turn back (nothing here changes their spin) */
    for (uint32_t i = 0; sp && i < n && i < sp->cap; i++) sp->omega[i] = 0.0 - sp->omega[i]; /* 0 stays +0 */
    w->epoch++;
    return TT_OK;
}
