/* tether — the pair grid while some particles sleep: built over the awake
 * particles and the sleepers within contact reach of one, so a sleeping
 * pile costs nothing per substep however large it is. Two sleepers make no
 * pair, so the pairs are those of the grid over every particle: an awake
 * one still meets (and wakes) a sleeper it touches. The sleepers within
 * reach come from the sleepers' grid (sleep_grid.c), then the walk's own
 * distance test decides, so which ones are listed depends on positions and
 * radii alone, never on when the sleepers' grid was built; they are merged
 * into the awake ones in slot order, as the build over every particle
 * gathers them. The grid spans only what it holds: pair order differs
 * from the grid over every particle's, deterministically. */
#include "collide_internal.h"

#include <stdlib.h>

typedef struct reach {
    const tt_world *w;
    tt__grid *g;
    uint32_t n;
    bool ok;
} reach;

/* Sleeper j, if it is within awake particle a's contact reach: the walk's
 * test (same operations, so the same answer, NaN included). */
static void within_reach(void *ctx, uint32_t a, uint32_t j)
{
    reach *q = ctx;
    const tt_world *w = q->w;
    const double dx = w->px[a] - w->px[j], dy = w->py[a] - w->py[j], rs = (double)w->radius[a] + (double)w->radius[j];
    if (dx * dx + dy * dy >= rs * rs * TT__MARGIN2 || rs == 0.0) return;
    tt__grid *g = q->g;
    if (q->n == g->cand_cap && !tt__grow((void **)&g->cand, &g->cand_cap, q->n + 1, sizeof *g->cand)) {
        q->ok = false;
        return;
    }
    g->cand[q->n++] = j;
}

static int cmp_u32(const void *a, const void *b)
{
    const uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

/* g->list[0..na) (awake, ascending) merged with the sorted, distinct
 * candidates, from the back so nothing is overwritten before it is read;
 * the count. */
static uint32_t merge(tt__grid *g, uint32_t na, uint32_t nc)
{
    uint32_t i = na, j = nc, k = na + nc;
    while (j > 0) g->list[--k] = i > 0 && g->list[i - 1] > g->cand[j - 1] ? g->list[--i] : g->cand[--j];
    return na + nc;
}

bool tt__grid_detect(tt_world *w, tt__collide *c)
{
    tt__grid *g = &c->scr.grid;
    if (tt__sleep_count(w) == 0) return tt__grid_build(w, g, c->set.cell_size) && tt__grid_pairs(w, c);
    const uint32_t n = w->ppool.count;
    if (!tt__grid_reserve(g, n)) return false;
    uint32_t na = 0;
    for (uint32_t i = 0; i < n; i++)
        if ((w->flags[i] & (TT__PF_ALIVE | TT__PF_ASLEEP)) == TT__PF_ALIVE) g->list[na++] = i;
    reach q = {w, g, 0, true};
    if (!tt__sleep_reach(w, g->list, na, 1.0 + TT__CONTACT_MARGIN, within_reach, &q) || !q.ok) return false;
    uint32_t nc = 0; /* each sleeper once: one may be within reach of several */
    if (q.n > 1) qsort(g->cand, q.n, sizeof *g->cand, cmp_u32); /* (none found: g->cand may be NULL) */
    for (uint32_t k = 0; k < q.n; k++)
        if (nc == 0 || g->cand[k] != g->cand[nc - 1]) g->cand[nc++] = g->cand[k];
    return tt__grid_build_list(w, g, c->set.cell_size, merge(g, na, nc)) && tt__grid_pairs(w, c);
}
