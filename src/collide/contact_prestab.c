/* tether — pre-stabilisation of particle pairs (Macklin, Müller, Chentanez
 * and Kim 2014, "Unified particle physics for real-time applications",
 * section 4.4).
 *
 * Velocity comes from positions (Verlet's x − x_old; the other integrators
 * add what the sweeps moved), so every push of the sweeps is a velocity.
 * Where a substep begins with two particles overlapping (a pile that the
 * last substep's sweeps could not hold, circles landing at 30 m/s that
 * moved half a diameter into one another), the push that undoes that old
 * overlap became speed too, and the velocity pass could only cap it along
 * the normal the sweeps left: when the sweeps had turned a pair's normal
 * round, the pair seemed to have been parting before them and left at the
 * speed it met with (the reference pour at 1 × 8: a circle from 19 to
 * 41.5 m/s in one step, over the free fall from the top of the box).
 *
 * So before the sweeps the overlap at the start of the substep is undone
 * on the start positions (Verlet's x_old; the other integrators' start
 * copy), with the sweeps' own pair projection and order, and each particle's
 * predicted position is moved by exactly what its start moved: the
 * velocity it had is kept, and the sweeps that follow only undo the
 * penetration this substep's motion makes. Only that becomes velocity, and
 * the velocity pass caps it as before. Only the overlap deeper than
 * TT__PRESTAB_SLOP of the radii sum: a pile at rest stays under it and is
 * solved as before (with no slop, the 600-circle pour of test_energy never
 * came to rest: 0.2 J of kinetic energy from 11 to 15 s, and 1e-5 of its
 * energy gained in a step). Pairs
 * only: a shape's push is capped along a normal that does not turn round
 * (uncross keeps it). */
#include "collide_internal.h"

#include <string.h>

/* The start positions of the substep: Verlet's x_old, or the copy begin made. */
static void starts(tt_world *w, tt__collide *c, double **x, double **y)
{
    const bool verlet = w->integrator == TT_VERLET;
    *x = verlet ? w->qx : c->sx0;
    *y = verlet ? w->qy : c->sy0;
}

/* The sweeps as the relaxation loop runs them, on the start positions
 * (sx, sy) and the radii sums less the slop: batches (the same bits in
 * scalar code and in lanes: the kernels take the world's layout, st = 1, in
 * scalar code) or the pair list; at most w->iterations, until the deepest
 * overlap left is within the tolerance. tt__correct writes through the
 * solver's layout, pointed at the starts while they run (begin is before
 * the sweeps: the solver has set none). The velocity pass then acts only
 * on what the substep's own sweeps push, so the accumulators start at 0. */
static void sweep_pairs(tt_world *w, tt__collide *c, double *sx, double *sy)
{
    tt__batches *B = &c->scr.bat;
    const tt__lay L = {sx, sy, w->inv_mass, 1}, kept = w->scr.lay;
    w->scr.lay = L;
    double *rs = B->rs;
    if (c->scr.batched) B->rs = B->pre; /* the kernels read rs: pointed at the slop's while they run */
    for (uint32_t it = 0; it < w->iterations; it++) {
        const double err = c->scr.batched ? tt__batches_sweep(B, &L, 0, B->n / 4)
                                          : tt__pairs_sweep(w, c, &L, 0, c->scr.npairs, 1.0 - TT__PRESTAB_SLOP);
        if (err <= w->tolerance) break;
    }
    w->scr.lay = kept;
    if (c->scr.batched) {
        B->rs = rs;
        memset(B->lam, 0, (size_t)B->n * sizeof *B->lam);
    } else {
        for (uint32_t k = 0; k < c->scr.npairs; k++) c->scr.pairs[k].lambda = 0.0f;
    }
}

void tt__contacts_prestab(tt_world *w, tt__collide *c, uint32_t n)
{
    /* Jacobi sweeps correct through the solver's accumulators, applied to x alone */
    if (c->scr.npairs == 0 || w->order != TT_GAUSS_SEIDEL || c->scr.pcap < n) return;
    double *sx, *sy;
    starts(w, c, &sx, &sy);
    if (!sx || (w->integrator != TT_VERLET && c->scap < n)) return;
    tt__copy(c->scr.px0, sx, (size_t)n * sizeof *sx);
    tt__copy(c->scr.py0, sy, (size_t)n * sizeof *sy);
    sweep_pairs(w, c, sx, sy);
    double *px = w->px, *py = w->py;
    for (uint32_t i = 0; i < n; i++) {
        /* only where the start moved: x + 0 would turn −0 into +0 */
        const double dx = sx[i] - c->scr.px0[i], dy = sy[i] - c->scr.py0[i];
        if (dx != 0.0) px[i] += dx;
        if (dy != 0.0) py[i] += dy;
    }
}
