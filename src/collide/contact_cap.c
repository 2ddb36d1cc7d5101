/* tether — the end of the velocity pass: no particle leaves a substep's
 * particle contacts faster than the fastest of itself and what it touched
 * was before the sweeps (issue 21: energy is never created).
 *
 * Velocity comes from positions (Verlet's x − x_old; the other integrators
 * add what the sweeps moved), so the sweeps' pushes are velocities, and the
 * pair pass and the bottom-up pass (contact_lift.c) only cap them along each
 * pair's normal. Two things got past them, traced in the pours of
 * tests/collide/test_energy.c at 1 substep:
 * - the pair pass is one Gauss–Seidel pass: a pair is brought to rest
 *   against its partner's velocity as the sweeps left it, and the partner's
 *   other pairs then take most of that away. A circle falling at 27 m/s
 *   was given 20 m/s sideways by a neighbour moving at 12 m/s that the
 *   sweeps had pushed to 16 m/s (3 000 circles, box 30 wide, 1 × 32:
 *   1.14 × the speed of a fall from the highest start);
 * - a circle squeezed between two others whose small overlaps (under the
 *   pre-stabilisation's slop) the sweeps undo every step slides out of the
 *   wedge along the tangent of one contact, where no normal cap reaches,
 *   faster each step (3.4 → 6.0 → 7.7 m/s), and what leaves a pile that
 *   way throws clusters up (the 1 000-circle pour into a box 10 wide gained
 *   2.5e-4 of its total energy in a step).
 * In a contact without bounce the normal velocities are mixed by the
 * masses and the tangential ones only lose to friction, so what leaves it
 * is no faster than the faster of the two came in (a glancing blow onto a
 * sliding circle can make it a little faster than either; the cap takes
 * that too, which only removes energy). So each particle in a touched pair
 * is slowed, along its own velocity, to the largest pre-sweep speed among
 * itself and its touched partners. It only ever slows a particle: it
 * removes energy and never adds it. Left out: pairs with restitution (a
 * light particle struck by a heavy one rightly leaves faster than either),
 * and particles touching a shape (a kinematic shape's push is not in any
 * pre-sweep speed), which are left as the passes before left them.
 *
 * Scratch: the pre-stabilisation's start copy (px0, one per particle,
 * reserved with the pairs), which is free by the end of the substep. */
#include "collide_internal.h"

static inline double speed2(const tt__collide *c, uint32_t i) { return c->scr.vx0[i] * c->scr.vx0[i] + c->scr.vy0[i] * c->scr.vy0[i]; }

/* Particle i slowed along its velocity to speed² at most lim. */
static void slow_to(tt_world *w, uint32_t i, double lim)
{
    if (w->inv_mass[i] == 0.0 || !(lim < INFINITY)) return;
    const tt_vec2 v = tt__velocity(w, i);
    const double v2 = v.x * v.x + v.y * v.y;
    if (!(v2 > lim)) return;
    const double f = sqrt(lim / v2) - 1.0;
    tt__add_velocity(w, i, v.x * f, v.y * f);
}

/* The bounds by the touched pairs, then each particle slowed to its own,
 * once (each reads and writes only its own velocity, so the order changes
 * nothing). Where the touched pairs are many for the particles, particle
 * by particle in slot order: visiting each from its pairs went to every
 * particle about seven times, at random. Where they are few (a large world
 * with a few contacts awake), from the pairs, each particle marked done:
 * a walk over every particle would make such a world pay for all of them. */
void tt__contacts_cap(tt_world *w, tt__collide *c)
{
    const uint32_t m = c->scr.ntouch, *touch = c->scr.touch, n = w->ppool.count;
    if (m == 0 || c->scr.pcap < n) return;
    const bool dense = 2 * (uint64_t)m >= n;
    double *top = c->scr.px0; /* each touched particle's bound, speed² (dense: ∞ where it touched nothing) */
    uint32_t a, b;
    double lam;
    if (dense)
        for (uint32_t i = 0; i < n; i++) top[i] = INFINITY;
    for (uint32_t t = 0; t < m; t++) {
        (void)tt__anc_unit(c, touch[t], &a, &b, &lam);
        top[a] = top[b] = 0.0;
    }
    for (uint32_t t = 0; t < m; t++) {
        (void)tt__anc_unit(c, touch[t], &a, &b, &lam);
        const double ea = tt__mat(c, a, 0), eb = tt__mat(c, b, 0);
        const double sa = speed2(c, a), sb = speed2(c, b);
        const double s = ea > 0.0 || eb > 0.0 ? INFINITY : sa > sb ? sa : sb;
        top[a] = s > top[a] ? s : top[a]; /* a max of two variables: no branch */
        top[b] = s > top[b] ? s : top[b];
    }
    for (uint32_t k = 0; k < c->scr.nsc; k++)
        if (c->scr.sc[k].lambda > 0.0 || c->scr.sc[k].ccd) top[c->scr.sc[k].a] = INFINITY;
    if (dense) {
        for (uint32_t i = 0; i < n; i++) slow_to(w, i, top[i]);
        return;
    }
    for (uint32_t t = 0; t < m; t++) {
        (void)tt__anc_unit(c, touch[t], &a, &b, &lam);
        slow_to(w, a, top[a]);
        top[a] = INFINITY; /* done */
        slow_to(w, b, top[b]);
        top[b] = INFINITY;
    }
}
