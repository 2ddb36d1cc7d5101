/* tether — the constraints group's storage: its slots and handles, the
 * particle reference counts, removal (with the pairs it switched off and
 * the targets it was moving), composites' storage, the memory count and
 * destruction; and the pairs its links keep from colliding (a counted set,
 * core/pair_set.h), which the collision stage asks. Every file of the
 * feature uses this one; it uses none of them. */
#include "constraint_internal.h"

#include <stdlib.h>
#include <string.h>

void tt__cgroup_unmake(tt_world *w, bool had)
{
    if (!had) tt__group_remove_id(w, TT__CONS_ID);
}

/* ---- slots -------------------------------------------------------------- */

bool tt__cgroup_slot_new(tt__cgroup *g, uint8_t kind, uint32_t dense, uint32_t *out)
{
    /* room first: freeing a slot taken in vain would age its generation */
    uint32_t need = g->pool.free_count ? g->pool.count : g->pool.count + 1;
    if (!tt__grow((void **)&g->slots, &g->slot_cap, need, sizeof *g->slots)) return false;
    bool grew;
    uint32_t s = tt__pool_alloc(&g->pool, UINT32_MAX - 1, &grew);
    if (s == UINT32_MAX) return false;
    g->slots[s] = (tt__cslot){kind, dense, 0, 0.0};
    g->alive++;
    *out = s;
    return true;
}

/* ---- particle reference counts --------------------------------------------- */

bool tt__cgroup_refs_reserve(const tt_world *w, tt__cgroup *g)
{
    if (g->refs_cap >= w->pcap) return true;
    uint32_t *r = realloc(g->refs, (size_t)w->pcap * sizeof *r);
    if (!r) return false;
    memset(r + g->refs_cap, 0, (size_t)(w->pcap - g->refs_cap) * sizeof *r);
    g->refs = r;
    g->refs_cap = w->pcap;
    return true;
}

void tt__cgroup_gen_refs(tt__cgroup *g, const tt__gcon *c, int delta)
{
    const uint32_t *p = c->list ? c->list : c->p;
    for (uint32_t k = 0; k < c->n; k++) g->refs[p[k]] += (uint32_t)delta;
}

/* ---- removal ------------------------------------------------------------- */

void tt__cgroup_dist_remove(tt__cgroup *g, uint32_t d)
{
    tt__dist *c = &g->dist[d];
    tt__dist_x *x = &g->dx[d];
    if (!x->collide) tt__pair_set_remove(&g->pairs, c->a, c->b);
    g->refs[c->a]--;
    g->refs[c->b]--;
    if (x->break_strain > 0) g->nbreakable--;
    if (c->alpha > 0) g->nxpbd--;
    tt__target_forget(g, x->slot);
    g->slots[x->slot].kind = 0;
    tt__pool_free(&g->pool, x->slot);
    g->alive--;
    g->scr.plan_ok = false;
    uint32_t last = --g->ndist;
    if (d != last) {
        g->dist[d] = g->dist[last];
        g->dx[d] = g->dx[last];
        g->slots[g->dx[d].slot].dense = d;
    }
}

static void gen_remove(tt__cgroup *g, uint32_t d)
{
    tt__gcon *c = &g->gen[d];
    tt__cgroup_gen_refs(g, c, -1);
    free(c->list);
    tt__target_forget(g, c->slot);
    g->slots[c->slot].kind = 0;
    tt__pool_free(&g->pool, c->slot);
    g->alive--;
    uint32_t last = --g->ngen;
    if (d != last) {
        g->gen[d] = g->gen[last];
        g->slots[g->gen[d].slot].dense = d;
    }
}

void tt__cgroup_slot_remove(tt__cgroup *g, uint32_t s)
{
    if (g->slots[s].kind == TT_CONSTRAINT_DISTANCE)
        tt__cgroup_dist_remove(g, g->slots[s].dense);
    else
        gen_remove(g, g->slots[s].dense);
}

/* ---- the hooks that walk the storage --------------------------------------- */

void tt__cgroup_particle_removed(tt_world *w, void *self, uint32_t index)
{
    (void)w;
    tt__cgroup *g = self;
    if (index >= g->refs_cap || g->refs[index] == 0) return; /* named by no constraint: nothing to scan */
    for (uint32_t i = g->ndist; i-- > 0;)
        if (g->dist[i].a == index || g->dist[i].b == index) tt__cgroup_dist_remove(g, i);
    for (uint32_t i = g->ngen; i-- > 0;) {
        tt__gcon *c = &g->gen[i];
        if (c->list) {
            uint32_t k = 0, m = 0;
            for (; k < c->n; k++)
                if (c->list[k] != index) c->list[m++] = c->list[k];
            if (m == c->n) continue;
            g->refs[index] -= c->n - m; /* the entries dropped from the list */
            c->n = m;
            if (c->kind == TT_CONSTRAINT_AREA || m == 0) gen_remove(g, i); /* a broken polygon; an emptied bounds */
        } else if (c->kind != TT_CONSTRAINT_BOUNDS) {
            for (uint32_t k = 0; k < c->n; k++)
                if (c->p[k] == index) {
                    gen_remove(g, i);
                    break;
                }
        }
    }
}

size_t tt__cgroup_memory(const tt_world *w, const void *self)
{
    (void)w;
    const tt__cgroup *g = self;
    size_t b = sizeof *g + tt__pool_bytes(&g->pool) + (size_t)g->slot_cap * sizeof(tt__cslot);
    b += (size_t)g->dist_cap * sizeof(tt__dist) + (size_t)g->dx_cap * sizeof(tt__dist_x);
    b += (size_t)g->gen_cap * sizeof(tt__gcon);
    for (uint32_t i = 0; i < g->ngen; i++)
        if (g->gen[i].list) b += (size_t)g->gen[i].n * sizeof(uint32_t);
    b += tt__pair_set_bytes(&g->pairs);
    b += (size_t)(g->scr.cap_new + g->cap_pub) * sizeof(tt_break_event);
    b += (size_t)g->scr.grad_cap * 2 * sizeof(double) + (size_t)g->refs_cap * sizeof(uint32_t);
    b += ((size_t)g->scr.plan_cap + g->scr.stamp_cap) * sizeof(uint32_t);
    b += (size_t)g->scr.hot_cap * (4 * sizeof(double) + 2 * sizeof(uint32_t));
    b += (size_t)g->moving_cap * sizeof(tt__mover);
    return b + tt__composites_memory(g) + tt__cgroup_undo_bytes(g);
}

void tt__cgroup_scratch_free(tt_world *w, void *self)
{
    (void)w;
    tt__cgroup *g = self;
    tt__cscratch *s = &g->scr;
    free(s->plan); free(s->stamp); free(s->h_lo); /* h_lo: the hot copies' one block */
    free(s->grad);
    free(s->ev_new);
    tt__cgroup_undo_free(g);
    *s = (tt__cscratch){0};
}

void tt__cgroup_destroy(tt_world *w, void *self)
{
    (void)w;
    tt__cgroup *g = self;
    for (uint32_t i = 0; i < g->ngen; i++) free(g->gen[i].list);
    free(g->gen);
    free(g->dist);
    free(g->dx);
    free(g->slots);
    tt__pair_set_free(&g->pairs);
    free(g->ev_pub);
    free(g->moving);
    free(g->refs);
    tt__cgroup_scratch_free(w, g);
    tt__pool_destroy(&g->pool);
    tt__composites_free(g);
    free(g);
}

/* ---- a removed constraint's moving target ------------------------------------ */

static void drop_mover(tt__cgroup *g, uint32_t k)
{
    g->slots[g->moving[k].slot].mover = 0;
    uint32_t last = --g->nmoving;
    if (k != last) {
        g->moving[k] = g->moving[last];
        g->slots[g->moving[k].slot].mover = k + 1;
    }
}

void tt__target_forget(tt__cgroup *g, uint32_t slot)
{
    if (g->slots[slot].mover) drop_mover(g, g->slots[slot].mover - 1);
}

/* ---- composites' storage ------------------------------------------------------ */

void tt__composites_free(tt__cgroup *g)
{
    for (uint32_t i = 0; i < tt__comp_slots(g); i++) {
        free(g->comps[i].parts);
        free(g->comps[i].cons);
        free(g->comps[i].rest);
    }
    free(g->comps);
    tt__pool_destroy(&g->cpool);
}

size_t tt__composites_memory(const tt__cgroup *g)
{
    size_t b = (size_t)g->comp_cap * sizeof(tt__composite) + tt__pool_bytes(&g->cpool);
    for (uint32_t i = 0; i < tt__comp_slots(g); i++) {
        const tt__composite *k = &g->comps[i];
        if (!k->alive) continue;
        b += (size_t)k->np * (sizeof(tt_particle) + 2 * sizeof(double)) + (size_t)k->ccap * sizeof(tt_constraint);
    }
    return b;
}

/* ---- pairs kept from colliding ---------------------------------------------- */

bool tt__constraint_pair_excluded(const tt_world *w, uint32_t a, uint32_t b)
{
    const tt__cgroup *g = tt__cgroup_peek(w);
    return g && tt__pair_set_has(&g->pairs, a, b);
}

bool tt__constraint_pairs_any(const tt_world *w)
{
    const tt__cgroup *g = tt__cgroup_peek(w);
    return g && g->pairs.used;
}

/* Room for the gradients of the largest area constraint (constraint_relax.c). */
bool tt__cgroup_grad_reserve(tt__cgroup *g)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < g->ngen; i++)
        if (g->gen[i].kind == TT_CONSTRAINT_AREA && g->gen[i].n > n) n = g->gen[i].n;
    return !n || tt__grow((void **)&g->scr.grad, &g->scr.grad_cap, n, 2 * sizeof(double));
}
