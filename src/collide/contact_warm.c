/* tether — warm start of resting particle pairs
 * (tt_collision_settings.warm_start, with anchored friction).
 *
 * A pile at rest is pushed down by gravity every substep, and its weight
 * must be carried up through it again: Gauss-Seidel carries a push a few
 * circles per sweep, so a deep pile rests with the overlap the sweeps could
 * not carry away (the reference pour, stacking 2 and anchored friction at
 * 1 × 12: up to 1.25 % of a radius). Each resting pair's normal correction
 * of the last substep is close to what it must carry in this one, so a
 * share of it is pushed first, all at once, before the first sweep (the
 * position-level form of the warm-started impulses of velocity solvers,
 * Box2D's among them): the sweeps then only correct what changed.
 *
 * Measured on the reference pour (the pour and 10 jittered starts, stacking
 * 2 and anchored friction, docs/collisions.md "Warm start"): the whole
 * correction (share 1) of every pair throws the pile about (KE about 1
 * J/kg at 20 s); 0.75 of it, resting pairs only, rests every start under
 * 1 % at 1 × 4, where 1 × 12 without it reached 1.25 %; 0.85 left one
 * start moving at 1 × 6, 0.95 several at 1 × 4 (jitter).
 * Only pairs slower than the restitution threshold (anchored friction's
 * slow pairs): a landing's corrections are impacts, not weight. Only pairs
 * that overlap now, pushed along their own line as the sweeps push, by the
 * sweeps' weights (stacking's too); a particle leaning on a shape only
 * along it (stacking's hold, lean_push: the shape takes the rest; left
 * out, those entries left the layers by the walls to the sweeps, and two
 * starts of 11 still moved at 20 s at 1 × 6 with 0.85: 1.5e-4, 2.2e-4 J/kg).
 *
 * The corrections are kept in anchored friction's table (contact_anchor.c)
 * only while the setting is on, so a world without it saves, loads and
 * hashes as before. Scalar code for scalar and vector sweeps alike: the
 * same bits. */
#include "collide_internal.h"

#include <math.h>

/* The push along the line from b to a (dx, dy, distance² d2) of size push,
 * split by the weights ia, ib (ws their sum): a's share and b's as the
 * factors of (dx, dy); false where the pair does not overlap (rs: radii sum). */
static inline bool share(double dx, double dy, double rs, double push, double ia, double ib, double *ca, double *cb)
{
    const double d2 = dx * dx + dy * dy, ws = ia + ib;
    if (!(d2 < rs * rs) || d2 == 0.0 || ws == 0.0) return false;
    const double t = push / (ws * sqrt(d2));
    *ca = t * ia;
    *cb = t * ib;
    return true;
}

double tt__contacts_warm(tt_world *w, tt__collide *c, const tt__lay *L, uint32_t u0, uint32_t u1)
{
    const double f = c->set.warm_start, *wl = c->scr.anc.wl;
    /* the slow units with a correction (anchors' begin lists them: a test a unit here went either way
     * unit after unit), ascending */
    const uint32_t *rest = c->scr.anc.resting, nrest = c->scr.anc.nresting;
    double *X = L->x, *Y = L->y, most = 0.0, ca, cb;
    const size_t st = L->st;
    if (c->scr.batched) {
        tt__batches *B = &c->scr.bat;
        for (uint32_t r = 0; r < nrest; r++) {
            const uint32_t k = rest[r];
            if (k < 4 * u0) continue;
            if (k >= 4 * u1) break;
            const uint32_t i = B->a[k], j = B->b[k];
            const size_t a = i * st, b = j * st;
            const double dx = X[a] - X[b], dy = Y[a] - Y[b], push = f * wl[k];
            if (!share(dx, dy, B->rs[k], push, B->ka[k], B->kb[k], &ca, &cb)) continue;
            double ax = dx, ay = dy, bx = -dx, by = -dy;
            if (B->lean) { /* off the shapes a particle leans on */
                (void)tt__batches_held(B, i, &ax, &ay);
                (void)tt__batches_held(B, j, &bx, &by);
            }
            X[a] += ax * ca;
            Y[a] += ay * ca;
            X[b] += bx * cb;
            Y[b] += by * cb;
            B->lam[k] += push;
            most = push > most ? push : most;
        }
        return most;
    }
    for (uint32_t r = 0; r < nrest; r++) {
        const uint32_t k = rest[r];
        if (k < u0) continue;
        if (k >= u1 || k >= c->scr.npairs) break;
        tt__pair *p = &c->scr.pairs[k];
        const double dx = X[p->a * st] - X[p->b * st], dy = Y[p->a * st] - Y[p->b * st], push = f * wl[k];
        if (!share(dx, dy, p->rs, push, w->inv_mass[p->a], w->inv_mass[p->b], &ca, &cb)) continue;
        tt__correct(w, p->a, dx * ca, dy * ca);
        tt__correct(w, p->b, -dx * cb, -dy * cb);
        p->lambda += (float)push;
        most = push > most ? push : most;
    }
    return most;
}
