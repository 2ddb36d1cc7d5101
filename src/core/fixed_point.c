/* tether — fixed-point positions (tt_world_def.fixed_point): every position
 * of such a world is an integer multiple of the quantum q = 2^-k, held in a
 * double. A double holds every m·q with |m| ≤ 2^53 exactly, so sums and
 * differences of such positions are exact while they stay within 2^53·q;
 * positions are kept within 2^51·q (the range), which leaves room for
 * Verlet's 2x − x_old + round(a·h²) to be formed exactly. Verlet is then
 * exactly reversible (Levesque & Verlet 1993, "Molecular dynamics and time
 * reversibility"): x_old = 2x − x_new + round(a(x)·h²) holds bit for bit,
 * because a(x) is evaluated from the very same positions both ways.
 *
 * Rounding is round-half-away-from-zero on m (C's round): exact, and
 * independent of the floating-point rounding mode. */
#include "internal.h"

#include <stdlib.h>

bool tt__fixed_quantum_ok(double q)
{
    if (!(q >= 0x1p-60 && q <= 0x1p-1)) return false;
    int e;
    return frexp(q, &e) == 0.5; /* a power of two */
}

double tt__fixed_range(const tt_world *w) { return w->fixed_point * 0x1p51; }

bool tt__fixed_in_range(const tt_world *w, tt_vec2 p)
{
    if (w->fixed_point == 0.0) return true;
    const double r = tt__fixed_range(w);
    return fabs(p.x) <= r && fabs(p.y) <= r;
}

tt_vec2 tt__fixed_snap_vec(const tt_world *w, tt_vec2 p)
{
    if (w->fixed_point == 0.0) return p;
    return (tt_vec2){tt__fixed_snap(w->fixed_point, p.x), tt__fixed_snap(w->fixed_point, p.y)};
}

tt_result tt__fixed_check(const tt_world *w, tt_vec2 p, const char *fn)
{
    if (tt__fixed_in_range(w, p)) return TT_OK;
    return tt__fail(w, TT_EINVAL, "%s: position (%.17g, %.17g) is outside the fixed-point range |x| <= %g (2^51 quanta of %g m)",
                    fn, p.x, p.y, tt__fixed_range(w), w->fixed_point);
}

/* After the sweeps: constraints and contacts move particles by amounts off
 * the lattice; they are put back on it, and one pushed past the range is
 * stopped where the substep began (bx/by, on the lattice), as the guard
 * stops one past TT_DIVERGED. Only x is snapped: x_old may leave the
 * lattice (contacts' pre-stabilisation moves Verlet's start positions,
 * contact_prestab.c) and that breaks nothing, since the next step rounds
 * x − x_old onto the lattice (integrate.c) and tt_world_reverse, the one
 * use of an exact x_old, refuses worlds with contacts and snaps x_old anyway. */
void tt__fixed_after_solve(tt_world *w)
{
    const double q = w->fixed_point, r = tt__fixed_range(w);
    const uint32_t n = w->ppool.count;
    for (uint32_t i = 0; i < n; i++) {
        if (w->inv_mass[i] == 0.0) continue;
        double x = tt__fixed_snap(q, w->px[i]), y = tt__fixed_snap(q, w->py[i]);
        if (TT_UNLIKELY(!(fabs(x) <= r && fabs(y) <= r))) {
            x = w->qx[i] = w->scr.bx[i];
            y = w->qy[i] = w->scr.by[i];
            w->stats.diverged++;
        }
        w->px[i] = x;
        w->py[i] = y;
    }
}

/* Loaded positions: on the lattice and in range, as every public call keeps them. */
bool tt__fixed_loaded_ok(const tt_world *w)
{
    if (w->fixed_point == 0.0) return true;
    if (w->integrator != TT_VERLET) return false;
    for (uint32_t i = 0; i < w->ppool.count; i++) {
        if (!(w->flags[i] & TT__PF_ALIVE)) continue;
        tt_vec2 p = {w->px[i], w->py[i]};
        if (!tt__fixed_in_range(w, p) || tt__fixed_snap(w->fixed_point, p.x) != p.x ||
            tt__fixed_snap(w->fixed_point, p.y) != p.y)
            return false;
    }
    return true;
}

double tt_world_get_fixed_point(const tt_world *w) { return w ? w->fixed_point : 0.0; }
