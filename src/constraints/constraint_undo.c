/* tether — the constraints' part of the step's undo (core/step_undo.c): a
 * step that runs out of memory (for its contacts) is put back as it began.
 * A step changes two things here besides scratch: the targets the script
 * moved advance (and leave the moving list when they arrive), and links
 * stretched past their strain break. The moving list is small and copied
 * at the step's start; the links, with their slots, handles, excluded
 * pairs and reference counts, are copied raw at the step's first break, so
 * that only a step that breaks something pays for the copy. Room for both
 * is made before the step. */
#include "constraint_internal.h"

#include <stdlib.h>

#define GROW(arr, cap, n) tt__grow((void **)&u->arr, &u->cap, (n), sizeof *u->arr)

bool tt__cgroup_undo_reserve(tt_world *w, void *self)
{
    tt__cgroup *g = self;
    tt__cundo *u = &g->scr.undo;
    if (g->nmoving && !(GROW(moving, moving_cap, g->nmoving) && GROW(eff, eff_cap, 2 * g->nmoving))) return false;
    if (!g->nbreakable) return true;
    return GROW(dist, dist_cap, g->ndist) && GROW(dx, dx_cap, g->ndist) && GROW(slots, slot_cap, g->pool.count) &&
           GROW(gen, gen_cap, g->pool.count) && GROW(free_list, free_cap, g->pool.free_count) &&
           GROW(refs, refs_cap, w->ppool.count) && GROW(pair_key, key_cap, g->pairs.cap) &&
           GROW(pair_n, n_cap, g->pairs.cap);
}

/* The reference counts a break can change: of the particles named so far. */
static uint32_t refs_count(const tt_world *w, const tt__cgroup *g)
{
    return g->refs_cap < w->ppool.count ? g->refs_cap : w->ppool.count;
}

void tt__cgroup_undo_mark(tt_world *w, void *self)
{
    (void)w;
    tt__cgroup *g = self;
    tt__cundo *u = &g->scr.undo;
    u->broke = false;
    u->nnew = g->scr.nnew;
    u->nmoving = g->nmoving;
    tt__copy(u->moving, g->moving, (size_t)g->nmoving * sizeof *u->moving);
    for (uint32_t k = 0; k < g->nmoving; k++) { /* where each target is in effect (the sweeps read it there) */
        const tt__cslot *sl = &g->slots[g->moving[k].slot];
        const bool dist = sl->kind == TT_CONSTRAINT_DISTANCE;
        u->eff[2 * k] = dist ? g->dist[sl->dense].lo : g->gen[sl->dense].v[0];
        u->eff[2 * k + 1] = dist ? g->dist[sl->dense].hi : g->gen[sl->dense].v[1];
    }
}

void tt__cgroup_undo_links(tt_world *w, tt__cgroup *g)
{
    tt__cundo *u = &g->scr.undo;
    u->broke = true;
    u->ndist = g->ndist;
    u->nbreakable = g->nbreakable;
    u->nxpbd = g->nxpbd;
    u->alive = g->alive;
    u->free_count = g->pool.free_count;
    u->pair_used = g->pairs.used;
    u->pair_cap = g->pairs.cap;
    tt__copy(u->dist, g->dist, (size_t)g->ndist * sizeof *u->dist);
    tt__copy(u->dx, g->dx, (size_t)g->ndist * sizeof *u->dx);
    tt__copy(u->slots, g->slots, (size_t)g->pool.count * sizeof *u->slots);
    tt__copy(u->gen, g->pool.gen, (size_t)g->pool.count * sizeof *u->gen);
    tt__copy(u->free_list, g->pool.free_list, (size_t)g->pool.free_count * sizeof *u->free_list);
    tt__copy(u->refs, g->refs, (size_t)refs_count(w, g) * sizeof *u->refs);
    tt__copy(u->pair_key, g->pairs.key, (size_t)g->pairs.cap * sizeof *u->pair_key);
    tt__copy(u->pair_n, g->pairs.n, (size_t)g->pairs.cap * sizeof *u->pair_n);
}

static void restore_links(tt_world *w, tt__cgroup *g)
{
    const tt__cundo *u = &g->scr.undo;
    g->ndist = u->ndist;
    g->nbreakable = u->nbreakable;
    g->nxpbd = u->nxpbd;
    g->alive = u->alive;
    g->pool.free_count = u->free_count;
    g->pool.changes++; /* the slots hold what they did: caches of them (sleep_rest.c) are rebuilt */
    g->pairs.used = u->pair_used;
    tt__copy(g->dist, u->dist, (size_t)g->ndist * sizeof *g->dist);
    tt__copy(g->dx, u->dx, (size_t)g->ndist * sizeof *g->dx);
    tt__copy(g->slots, u->slots, (size_t)g->pool.count * sizeof *g->slots);
    tt__copy(g->pool.gen, u->gen, (size_t)g->pool.count * sizeof *g->pool.gen);
    tt__copy(g->pool.free_list, u->free_list, (size_t)g->pool.free_count * sizeof *g->pool.free_list);
    tt__copy(g->refs, u->refs, (size_t)refs_count(w, g) * sizeof *g->refs);
    tt__copy(g->pairs.key, u->pair_key, (size_t)g->pairs.cap * sizeof *g->pairs.key);
    tt__copy(g->pairs.n, u->pair_n, (size_t)g->pairs.cap * sizeof *g->pairs.n);
    g->scr.plan_ok = false; /* the sweep's plan and hot copies are rebuilt from the links */
}

void tt__cgroup_undo(tt_world *w, void *self)
{
    tt__cgroup *g = self;
    tt__cundo *u = &g->scr.undo;
    if (u->broke) restore_links(w, g);
    u->broke = false;
    g->scr.nnew = u->nnew;
    /* the moving targets as the step began, each effective where it then was */
    g->nmoving = u->nmoving;
    tt__copy(g->moving, u->moving, (size_t)g->nmoving * sizeof *g->moving);
    for (uint32_t k = 0; k < g->nmoving; k++) {
        tt__cslot *sl = &g->slots[g->moving[k].slot];
        sl->mover = k + 1;
        if (sl->kind == TT_CONSTRAINT_DISTANCE) {
            g->dist[sl->dense].lo = u->eff[2 * k];
            g->dist[sl->dense].hi = u->eff[2 * k + 1];
            g->scr.plan_ok = false; /* the sweep's copies of the links follow */
        } else {
            g->gen[sl->dense].v[0] = u->eff[2 * k];
            g->gen[sl->dense].v[1] = u->eff[2 * k + 1];
        }
    }
}

void tt__cgroup_undo_free(tt__cgroup *g)
{
    tt__cundo *u = &g->scr.undo;
    free(u->moving); free(u->eff); free(u->dist); free(u->dx); free(u->slots); free(u->gen);
    free(u->free_list); free(u->refs); free(u->pair_key); free(u->pair_n);
    *u = (tt__cundo){0};
}

size_t tt__cgroup_undo_bytes(const tt__cgroup *g)
{
    const tt__cundo *u = &g->scr.undo;
    return (size_t)u->moving_cap * sizeof *u->moving + (size_t)u->eff_cap * sizeof(double) + (size_t)u->dist_cap * sizeof *u->dist +
           (size_t)u->dx_cap * sizeof *u->dx + (size_t)u->slot_cap * sizeof *u->slots +
           ((size_t)u->gen_cap + u->free_cap + u->refs_cap + u->n_cap) * sizeof(uint32_t) +
           (size_t)u->key_cap * sizeof(uint64_t);
}
