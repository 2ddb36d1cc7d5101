/* tether — the uniform-grid broadphase for particles. Each build is a
 * counting sort of the live particles into square cells at least one
 * largest diameter (plus the contact margin) wide, so touching particles sit
 * in the same or neighbouring cells. The grid spans the particles' bounding
 * box; when that would need too many cells (a few particles far away), it
 * spans mean ± 4σ instead and particles outside are clamped into the border
 * cells. Clamping keeps neighbours neighbours (it is monotone and moves no
 * pair of cells further apart), so no pair is ever missed, however far.
 * Arrays grow with the particle count and are reused: no per-step malloc. */
#include "collide_internal.h"

#include <stdlib.h>
#include <string.h>

static bool grow_n(tt__grid *g, uint32_t need)
{
    if (need <= g->cap_n) return true;
    uint32_t n = g->cap_n ? g->cap_n : 256;
    while (n < need) n = n > UINT32_MAX / 2 ? need : n * 2;
    void *p;
#define GROW(f, t) if (!(p = realloc(g->f, (size_t)n * sizeof(t)))) return false; g->f = p
    GROW(cell, uint32_t); GROW(idx, uint32_t); GROW(sx, double); GROW(sy, double); GROW(sr, double);
    GROW(bits, uint8_t); GROW(out_list, uint32_t);
#undef GROW
    g->cap_n = n;
    return true;
}

static void fit(tt__grid *g, double lox, double loy, double hix, double hiy)
{
    g->ox = lox;
    g->oy = loy;
    g->inv = 1.0 / g->cs;
    double nx = floor((hix - lox) * g->inv) + 1.0, ny = floor((hiy - loy) * g->inv) + 1.0;
    g->nx = (int32_t)fmin(nx, 1e9);
    g->ny = (int32_t)fmin(ny, 1e9);
}

bool tt__grid_build(tt_world *w, tt__grid *g, double min_cell)
{
    const uint32_t n = w->ppool.count;
    g->epoch = UINT64_MAX;
    if (!grow_n(g, n ? n : 1)) return false;
    double lox = INFINITY, loy = INFINITY, hix = -INFINITY, hiy = -INFINITY, rmax = 0.0;
    uint32_t m = 0;
    uint16_t cat_or = 0, cat_and = 0xFFFF, mask_or = 0, mask_and = 0xFFFF;
    for (uint32_t i = 0; i < n; i++) {
        if (!(w->flags[i] & TT_PF_ALIVE)) continue;
        double x = w->px[i], y = w->py[i];
        double r = w->radius[i];
        cat_or |= w->category[i]; cat_and &= w->category[i];
        mask_or |= w->mask[i]; mask_and &= w->mask[i];
        lox = x < lox ? x : lox; hix = x > hix ? x : hix; /* not fmin/fmax: those are library calls here */
        loy = y < loy ? y : loy; hiy = y > hiy ? y : hiy;
        rmax = r > rmax ? r : rmax;
        m++;
    }
    g->n = m;
    g->nout = 0;
    g->rmax = rmax;
    g->one_layer = cat_or == cat_and && mask_or == mask_and && (cat_and & mask_and);
    if (m == 0) {
        g->nx = g->ny = 0;
        g->ncell = 0;
        return true;
    }
    double ex = hix - lox, ey = hiy - loy;
    double cs = fmax(min_cell, 2.0 * rmax * (1.0 + TT__CONTACT_MARGIN));
    if (!(cs > 0.0)) cs = fmax(sqrt(fmax(ex * ey, ex * ex + ey * ey) / m), 1e-6); /* points only: about one per cell */
    const double limit = 4.0 * m + 1024.0;
    g->cs = cs;
    fit(g, lox, loy, hix, hiy);
    if ((double)g->nx * g->ny > limit) { /* a few particles far away: a second pass for the spread */
        double sx = 0, sy = 0, sxx = 0, syy = 0;
        for (uint32_t i = 0; i < n; i++) {
            if (!(w->flags[i] & TT_PF_ALIVE)) continue;
            double x = w->px[i], y = w->py[i];
            sx += x; sy += y; sxx += x * x; syy += y * y;
        }
        double mx = sx / m, my = sy / m;
        double dx = 4.0 * sqrt(fmax(sxx / m - mx * mx, 0.0)), dy = 4.0 * sqrt(fmax(syy / m - my * my, 0.0));
        double rlx = fmax(lox, mx - dx), rhx = fmin(hix, mx + dx), rly = fmax(loy, my - dy), rhy = fmin(hiy, my + dy);
        fit(g, rlx, rly, rhx, rhy);
        while ((double)g->nx * g->ny > limit) { /* sparse and wide: coarser cells */
            g->cs *= 1.5;
            fit(g, rlx, rly, rhx, rhy);
        }
    }
    const uint32_t ncell = (uint32_t)g->nx * (uint32_t)g->ny;
    if (!tt__grow((void **)&g->start, &g->cap_cells, ncell + 1, sizeof *g->start)) return false;
    g->ncell = ncell;
    memset(g->start, 0, (size_t)(ncell + 1) * sizeof *g->start);
    const double ox = g->ox, oy = g->oy, inv = g->inv;
    const int32_t nx = g->nx, ny = g->ny;
    for (uint32_t i = 0; i < n; i++) {
        if (!(w->flags[i] & TT_PF_ALIVE)) continue;
        int32_t cx = tt__cell_coord(w->px[i], ox, inv), cy = tt__cell_coord(w->py[i], oy, inv);
        bool out = cx < 0 || cy < 0 || cx >= nx || cy >= ny;
        if (TT_UNLIKELY(out)) {
            cx = cx < 0 ? 0 : cx >= nx ? nx - 1 : cx;
            cy = cy < 0 ? 0 : cy >= ny ? ny - 1 : cy;
            g->out_list[g->nout++] = i;
        }
        uint32_t c = (uint32_t)cy * (uint32_t)nx + (uint32_t)cx;
        g->cell[i] = c | (out ? 0x80000000u : 0u);
        g->start[c + 1]++;
    }
    for (uint32_t c = 0; c < ncell; c++) g->start[c + 1] += g->start[c];
    /* scatter in slot order (stable, deterministic); start[c] ends at cell c's end */
    for (uint32_t i = 0; i < n; i++) {
        if (!(w->flags[i] & TT_PF_ALIVE)) continue;
        uint32_t c = g->cell[i] & 0x7FFFFFFFu, k = g->start[c]++;
        g->idx[k] = i;
        g->sx[k] = w->px[i];
        g->sy[k] = w->py[i];
        g->sr[k] = w->radius[i];
        g->bits[k] = (uint8_t)((g->cell[i] >> 31) | (w->inv_mass[i] == 0.0 ? TT__GRID_PINNED : 0));
    }
    for (uint32_t c = ncell; c > 0; c--) g->start[c] = g->start[c - 1];
    g->start[0] = 0;
    return true;
}

static inline bool push_pair(tt__collide *c, uint32_t a, uint32_t b, double rs)
{
    if (TT_UNLIKELY(c->npairs == c->paircap) &&
        !tt__grow((void **)&c->pairs, &c->paircap, c->npairs + 1, sizeof *c->pairs))
        return false;
    tt__pair *p = &c->pairs[c->npairs++];
    p->a = a;
    p->b = b;
    p->rs = (float)rs;
    p->lambda = 0.0f;
    return true;
}

/* Pairs between sorted ranges [k0, k1) and [j0, j1) (same: j from k + 1 to j1).
 * plain: nothing but two pinned particles can exclude a pair (one layer,
 * no exclusions), so the full filter is skipped. */
static inline bool cell_pairs(tt_world *w, tt__collide *c, const tt__grid *g, bool plain, uint32_t k0, uint32_t k1,
                              uint32_t j0, uint32_t j1, bool same)
{
    const double *sx = g->sx, *sy = g->sy, *sr = g->sr;
    const double f = (1.0 + TT__CONTACT_MARGIN) * (1.0 + TT__CONTACT_MARGIN);
    for (uint32_t k = k0; k < k1; k++) {
        const double x = sx[k], y = sy[k], r = sr[k];
        for (uint32_t j = same ? k + 1 : j0; j < j1; j++) {
            double dx = x - sx[j], dy = y - sy[j], rs = r + sr[j];
            if (dx * dx + dy * dy >= rs * rs * f || rs == 0.0) continue;
            uint32_t a = g->idx[k], b = g->idx[j];
            if (plain ? g->bits[k] & g->bits[j] & TT__GRID_PINNED : !tt__pair_filter(w, c, a, b)) continue;
            if (!push_pair(c, a, b, rs)) return false;
        }
    }
    return true;
}

bool tt__grid_pairs(tt_world *w, tt__collide *c)
{
    const tt__grid *g = &c->grid;
    const int32_t nx = g->nx, ny = g->ny;
    const uint32_t *st = g->start;
    const bool plain = g->one_layer && c->nexcl == 0 && !tt__constraint_pairs_any(w);
    for (int32_t y = 0; y < ny; y++) {
        for (int32_t x = 0; x < nx; x++) {
            uint32_t cell = (uint32_t)y * (uint32_t)nx + (uint32_t)x;
            uint32_t k0 = st[cell], k1 = st[cell + 1];
            if (k0 == k1) continue;
            /* forward half of the neighbourhood: the rest of this cell and E (contiguous), then NW, N, NE */
            if (!cell_pairs(w, c, g, plain, k0, k1, 0, x + 1 < nx ? st[cell + 2] : k1, true)) return false;
            if (y + 1 < ny) {
                uint32_t up = cell + (uint32_t)nx;
                uint32_t lo = x > 0 ? up - 1 : up, hi = x + 1 < nx ? up + 1 : up;
                /* the three cells above are contiguous in the sorted order */
                if (!cell_pairs(w, c, g, plain, k0, k1, st[lo], st[hi + 1], false)) return false;
            }
        }
    }
    return true;
}

void tt__grid_free(tt__grid *g)
{
    free(g->start); free(g->cell); free(g->idx);
    free(g->sx); free(g->sy); free(g->sr);
    free(g->bits); free(g->out_list);
    memset(g, 0, sizeof *g);
}

size_t tt__grid_bytes(const tt__grid *g)
{
    return (size_t)g->cap_cells * sizeof(uint32_t) +
           (size_t)g->cap_n * (3 * sizeof(uint32_t) + 3 * sizeof(double) + sizeof(uint8_t));
}
