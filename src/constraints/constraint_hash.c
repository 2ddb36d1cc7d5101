/* tether — the constraints' share of the world hash, which the determinism
 * tests and the demos compare: the links, every other kind and the
 * composites, in storage order. */
#include "constraint_internal.h"

uint64_t tt__cgroup_hash(const tt_world *w, const void *self, uint64_t h)
{
    (void)w;
    const tt__cgroup *g = self;
    h = tt__fnv(h, &g->ndist, sizeof g->ndist);
    for (uint32_t i = 0; i < g->ndist; i++) {
        h = tt__fnv(h, &g->dist[i], sizeof g->dist[i]);
        h = tt__fnv(h, &g->dx[i].slot, sizeof(uint32_t));
        h = tt__fnv(h, &g->dx[i].break_strain, sizeof(double));
        h = tt__fnv(h, &g->dx[i].collide, sizeof(bool));
        const double rate = g->slots[g->dx[i].slot].max_rate;
        if (rate > 0) h = tt__fnv(h, &rate, sizeof rate); /* unset: the hash of before max_rate */
    }
    h = tt__fnv(h, &g->ngen, sizeof g->ngen);
    for (uint32_t i = 0; i < g->ngen; i++) {
        const tt__gcon *c = &g->gen[i];
        h = tt__fnv(h, &c->kind, sizeof c->kind);
        h = tt__fnv(h, &c->slot, sizeof c->slot);
        h = tt__fnv(h, &c->n, sizeof c->n);
        h = tt__fnv(h, c->p, sizeof c->p);
        if (c->list) h = tt__fnv(h, c->list, (size_t)c->n * sizeof *c->list);
        h = tt__fnv(h, &c->k, sizeof c->k);
        h = tt__fnv(h, &c->alpha, sizeof c->alpha);
        h = tt__fnv(h, c->v, sizeof c->v);
        h = tt__fnv(h, &c->friction, sizeof c->friction);
        h = tt__fnv(h, &c->outside, sizeof c->outside);
        if (g->slots[c->slot].max_rate > 0) h = tt__fnv(h, &g->slots[c->slot].max_rate, sizeof(double));
    }
    return tt__composites_hash(g, tt__targets_hash(g, h));
}
