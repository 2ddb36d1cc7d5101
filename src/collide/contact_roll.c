/* tether — friction at the contact point, for worlds whose particles turn
 * (tt_world_def.spin; core/spin.h). Each particle is a solid disc, I = m r²/2.
 *
 * Without spin a grain's friction can only stop its centre, and bounding it
 * by the load its contact carries stands grains in columns no rolling pile
 * forms (README "Box2D cross-check"); so pair friction is bounded there by
 * the pair's own velocity change, which holds almost nothing at rest. With
 * spin the friction acts where the discs touch: the slip there is
 *   s = (va − vb)·t − ra ωa − rb ωb,     t = (−ny, nx), n from b to a,
 * and a tangential velocity change u (relative, along t; a gets u·wa, b
 * −u·wb, w the inverse-mass shares) turns them by Δωa = −2 u wa / ra,
 * Δωb = −2 u wb / rb (the torque of the impulse about each centre), so the
 * slip changes by 3u: a third of the correction is translation, two thirds
 * spin. Coulomb's bound is on the load: |u| ≤ μ N with N the pair's normal
 * velocity change, at least the normal correction the sweeps accumulated
 * this substep over h (what the pile above presses through the contact).
 * The substep's contacts are listed by the velocity pass (after its normal
 * part) and solved together in rounds, Gauss-Seidel, each contact's
 * accumulated u clamped to ±μs N (static: the slip goes while that holds);
 * a contact still at the bound after the rounds slides, clamped to μk N.
 * A disc of radius 0 does not turn (its share of the factor 3 drops). The
 * velocity change is applied as a move of u·h with the velocity following
 * it (position-based friction, Macklin et al. 2014), as the sticking of
 * particles without spin is. A shape or terrain is a side b that neither
 * moves under the contact nor turns: (ux, uy) its velocity there, wb = 0. */
#include "collide_internal.h"
#include "core/spin.h"

bool tt__roll_room(tt__collide *c)
{
    c->scr.nroll = 0;
    const uint32_t pairs = c->scr.bat.cap > c->scr.paircap ? c->scr.bat.cap : c->scr.paircap; /* batched or not */
    return tt__grow((void **)&c->scr.roll, &c->scr.roll_cap, pairs + c->scr.sccap + 1, sizeof *c->scr.roll);
}

/* One round at one contact: the slip at the contact point removed as far
 * as the accumulated change stays within the static bound. */
static void roll_one(tt_world *w, tt__spin *sp, tt__roll_contact *k, double h)
{
    const uint32_t a = k->a, b = k->b;
    const bool pair = b != UINT32_MAX;
    const double tx = -k->ny, ty = k->nx;
    const double ra = w->radius[a], rb = pair ? w->radius[b] : 0.0;
    const double oa = a < sp->cap ? sp->omega[a] : 0.0, ob = pair && b < sp->cap ? sp->omega[b] : 0.0;
    const tt_vec2 va = tt__velocity(w, a), vb = pair ? tt__velocity(w, b) : (tt_vec2){k->ux, k->uy};
    const double slip = (va.x - vb.x) * tx + (va.y - vb.y) * ty - ra * oa - rb * ob;
    const bool turn_a = ra > 0.0 && a < sp->cap, turn_b = pair && rb > 0.0 && b < sp->cap;
    const double kf = 1.0 + 2.0 * ((turn_a ? k->wa : 0.0) + (turn_b ? k->wb : 0.0)); /* slip per unit u */
    const double lim = k->mus * k->load, old = k->acc;
    double acc = old - slip / kf;
    acc = acc > lim ? lim : acc < -lim ? -lim : acc;
    const double u = acc - old;
    k->acc = acc;
    if (u == 0.0) return;
    tt__contact_shift(w, a, tx * u * k->wa * h, ty * u * k->wa * h, h);
    if (turn_a) sp->omega[a] -= 2.0 * u * k->wa / ra;
    if (pair) {
        tt__contact_shift(w, b, -tx * u * k->wb * h, -ty * u * k->wb * h, h);
        if (turn_b) sp->omega[b] -= 2.0 * u * k->wb / rb;
    }
}

/* As many rounds as the world sweeps its contacts (its iterations): one
 * round leaves a pile's friction far from converged (the quick pour settled
 * at 28.2 m at 1 × 8 with one round, 28.56 with 8; 32 rounds change it no
 * more than the run to run spread of the settings). */
void tt__roll_solve(tt_world *w, tt__collide *c, tt__spin *sp, double h)
{
    const uint32_t rounds = w->iterations;
    for (uint32_t r = 0; r < rounds; r++)
        for (uint32_t k = 0; k < c->scr.nroll; k++) roll_one(w, sp, &c->scr.roll[k], h);
    /* a contact still at its static bound slides: it keeps the kinetic one */
    for (uint32_t k = 0; k < c->scr.nroll; k++) {
        tt__roll_contact *q = &c->scr.roll[k];
        if (q->muk < q->mus && fabs(q->acc) >= 0.999 * q->mus * q->load) {
            q->mus = q->muk;
            roll_one(w, sp, q, h); /* clamps to the kinetic bound */
        }
    }
}
