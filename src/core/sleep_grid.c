/* tether — where the sleepers lie: a grid of the sleeping particles, so
 * that waking a box (terrain carved, a moved shape's path, an explosion)
 * costs in proportion to the sleepers near it, not to the world. Sleepers
 * do not move, so the grid holds until the next one falls asleep (or a
 * step is undone, or a stream loaded): then the first query builds it
 * again, one counting sort of the sleepers into about one cell each. A
 * woken particle may stay listed: the query skips what no longer sleeps,
 * and its slot reused by a new particle is awake. Which islands wake does
 * not depend on the order the candidates are found in (the wake list is
 * sorted), so results are those of the pass over every particle. */
#include "sleep_internal.h"
#include "collide/collide_internal.h"

#include <stdlib.h>

/* Most cells a grid of m sleepers may have: a handful far off the rest
 * widen the cells rather than multiply them. */
static double max_cells(uint32_t m) { return 4.0 * m + 64.0; }

static uint32_t cell_of(const tt__sleep_grid *g, double x, double y)
{
    int32_t cx = tt__cell_coord(x, g->ox, g->inv), cy = tt__cell_coord(y, g->oy, g->inv);
    cx = cx < 0 ? 0 : cx >= g->nx ? g->nx - 1 : cx;
    cy = cy < 0 ? 0 : cy >= g->ny ? g->ny - 1 : cy;
    return (uint32_t)cy * (uint32_t)g->nx + (uint32_t)cx;
}

static bool build(const tt_world *w, tt__sleep *s)
{
    tt__sleep_grid *g = &s->grid;
    const uint32_t n = tt__sleep_covered(w, s);
    double lox = INFINITY, loy = INFINITY, hix = -INFINITY, hiy = -INFINITY, rmax = 0.0;
    uint32_t m = 0;
    for (uint32_t i = 0; i < n; i++) {
        if (!s->island[i]) continue;
        lox = fmin(lox, w->px[i]), hix = fmax(hix, w->px[i]);
        loy = fmin(loy, w->py[i]), hiy = fmax(hiy, w->py[i]);
        rmax = fmax(rmax, w->radius[i]);
        m++;
    }
    g->m = m;
    g->rmax = rmax;
    g->nx = g->ny = 0;
    if (m == 0) return g->built = true;
    double cs = fmax(sqrt((hix - lox) * (hiy - loy) / m), 2.0 * rmax);
    if (!(cs > 0.0)) cs = 1.0;
    while ((floor((hix - lox) / cs) + 1.0) * (floor((hiy - loy) / cs) + 1.0) > max_cells(m)) cs *= 2.0;
    g->ox = lox, g->oy = loy, g->hx = hix, g->hy = hiy, g->inv = 1.0 / cs;
    g->nx = (int32_t)floor((hix - lox) * g->inv) + 1;
    g->ny = (int32_t)floor((hiy - loy) * g->inv) + 1;
    const uint32_t ncell = (uint32_t)g->nx * (uint32_t)g->ny;
    if (!tt__grow((void **)&g->start, &g->cap_cells, ncell + 1, sizeof *g->start) ||
        !tt__grow((void **)&g->idx, &g->cap, m, sizeof *g->idx)) {
        g->nx = g->ny = 0;
        return false;
    }
    for (uint32_t c = 0; c <= ncell; c++) g->start[c] = 0;
    for (uint32_t i = 0; i < n; i++)
        if (s->island[i]) g->start[cell_of(g, w->px[i], w->py[i])]++;
    uint32_t sum = 0; /* start[c] becomes the end of cell c, then its beginning as the scatter fills it */
    for (uint32_t c = 0; c < ncell; c++) g->start[c] = sum += g->start[c];
    g->start[ncell] = m;
    for (uint32_t i = n; i-- > 0;)
        if (s->island[i]) g->idx[--g->start[cell_of(g, w->px[i], w->py[i])]] = i;
    return g->built = true;
}

bool tt__sleep_grid_visit(const tt_world *w, tt__sleep *s, double lox, double loy, double hix, double hiy,
                          void (*visit)(void *ctx, uint32_t i), void *ctx)
{
    tt__sleep_grid *g = &s->grid;
    if (!g->built && !build(w, s)) return false;
    if (g->m == 0) return true;
    const double r = g->rmax; /* a sleeper's centre lies in its cell: one within r of the box touches it */
    const double e = r + 1.0 / g->inv; /* a cell more: no rounding can make it the test's edge */
    if (lox - e > g->hx || hix + e < g->ox || loy - e > g->hy || hiy + e < g->oy) return true; /* off every sleeper */
    const uint32_t a = cell_of(g, lox - r, loy - r), b = cell_of(g, hix + r, hiy + r);
    const uint32_t x0 = a % (uint32_t)g->nx, x1 = b % (uint32_t)g->nx, y0 = a / (uint32_t)g->nx, y1 = b / (uint32_t)g->nx;
    const uint32_t n = tt__sleep_covered(w, s);
    for (uint32_t y = y0; y <= y1; y++) /* a row's cells are one run of idx */
        for (uint32_t k = g->start[y * (uint32_t)g->nx + x0]; k < g->start[y * (uint32_t)g->nx + x1 + 1]; k++) {
            const uint32_t i = g->idx[k];
            if (i < n && s->island[i]) visit(ctx, i);
        }
    return true;
}

typedef struct reach_ctx {
    void (*visit)(void *ctx, uint32_t a, uint32_t j);
    void *ctx;
    uint32_t a;
} reach_ctx;

static void reach_one(void *ctx, uint32_t j)
{
    const reach_ctx *q = ctx;
    q->visit(q->ctx, q->a, j);
}

bool tt__sleep_grid_reach(const tt_world *w, tt__sleep *s, const uint32_t *list, uint32_t n, double f,
                          void (*visit)(void *ctx, uint32_t a, uint32_t j), void *ctx)
{
    if (!s->grid.built && !build(w, s)) return false;
    if (s->grid.m == 0) return true;
    const double r = s->grid.rmax;
    reach_ctx q = {visit, ctx, 0};
    for (uint32_t k = 0; k < n; k++) {
        const uint32_t a = list[k];
        if (w->inv_mass[a] == 0.0) continue; /* pinned: it makes no pair with a sleeper */
        const double x = w->px[a], y = w->py[a];
        /* the reach with room for the rounding of the test and of the box's
         * corners (visit adds r itself) */
        const double h = ((double)w->radius[a] + r) * f * (1.0 + 1e-9) - r + 1e-14 * (fabs(x) + fabs(y));
        q.a = a;
        tt__sleep_grid_visit(w, s, x - h, y - h, x + h, y + h, reach_one, &q);
    }
    return true;
}
