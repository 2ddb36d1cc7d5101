/* tether — the N² reference broadphase: every pair of live particles is
 * tested with the same criterion as the grid (gap under the contact margin,
 * same filter), so both give the same pair set. For tests and benchmarks. */
#include "collide_internal.h"

bool tt__brute_pairs(tt_world *w, tt__collide *c)
{
    const uint32_t n = w->ppool.count;
    const double f = (1.0 + TT__CONTACT_MARGIN) * (1.0 + TT__CONTACT_MARGIN);
    for (uint32_t a = 0; a < n; a++) {
        if (!(w->flags[a] & TT__PF_ALIVE)) continue;
        const double x = w->px[a], y = w->py[a], r = w->radius[a];
        for (uint32_t b = a + 1; b < n; b++) {
            if (!(w->flags[b] & TT__PF_ALIVE)) continue;
            double dx = x - w->px[b], dy = y - w->py[b], rs = r + (double)w->radius[b];
            if (dx * dx + dy * dy >= rs * rs * f || rs == 0.0) continue;
            if (!tt__pair_filter(w, c, a, b)) continue;
            if (c->scr.npairs == c->scr.paircap && !tt__grow((void **)&c->scr.pairs, &c->scr.paircap, c->scr.npairs + 1, sizeof *c->scr.pairs))
                return false;
            c->scr.pairs[c->scr.npairs++] = (tt__pair){a, b, (float)rs, 0.0f};
        }
    }
    return true;
}
