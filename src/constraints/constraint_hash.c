/* tether — the constraints' section of the snapshot stream ("CONS"), and so
 * their share of the world hash: the slots and their pool, the links, every
 * other kind, the targets the script moved, break events of the last step,
 * the composites. Saved field by field in storage order; loaded into a new
 * group with every index and number checked, and what is derived (counts,
 * reference counts, excluded pairs, the vector plan) rebuilt. The XPBD
 * multipliers restart every substep and are not state. */
#include "constraint_internal.h"
#include "core/stream.h"

#include <stdlib.h>
#include <string.h>

static void save_dist(const tt__cgroup *g, tt__sink *s)
{
    tt__put_u32(s, g->ndist);
    for (uint32_t i = 0; i < g->ndist; i++) {
        const tt__dist *d = &g->dist[i];
        const tt__dist_x *x = &g->dx[i];
        tt__put_u32(s, d->a);
        tt__put_u32(s, d->b);
        tt__put_f64(s, d->lo);
        tt__put_f64(s, d->hi);
        tt__put_f64(s, d->k);
        tt__put_f64(s, d->alpha);
        tt__put_f64(s, x->rest);
        tt__put_f64(s, x->break_strain);
        tt__put_u32(s, x->slot);
        tt__put_u8(s, x->mode);
        tt__put_u8(s, x->collide);
    }
}

static void save_gen(const tt__cgroup *g, tt__sink *s)
{
    tt__put_u32(s, g->ngen);
    for (uint32_t i = 0; i < g->ngen; i++) {
        const tt__gcon *c = &g->gen[i];
        tt__put_u8(s, c->kind);
        tt__put_u8(s, c->outside);
        tt__put_u8(s, c->list != NULL);
        tt__put_u32(s, c->slot);
        tt__put_u32(s, c->n);
        if (c->list) tt__put(s, c->list, (size_t)c->n * sizeof *c->list);
        else tt__put(s, c->p, sizeof c->p);
        tt__put_f64(s, c->k);
        tt__put_f64(s, c->alpha);
        tt__put(s, c->v, sizeof c->v);
        tt__put_f64(s, c->friction);
    }
}

static void put_handle(tt__sink *s, uint32_t index, uint32_t gen)
{
    tt__put_u32(s, index);
    tt__put_gen(s, gen);
}

static void save_rest(const tt__cgroup *g, tt__sink *s)
{
    tt__put_u32(s, g->nmoving);
    for (uint32_t k = 0; k < g->nmoving; k++) {
        const tt__mover *m = &g->moving[k];
        tt__put_u32(s, m->slot);
        tt__put(s, m->at, sizeof m->at);
        tt__put(s, m->to, sizeof m->to);
        tt__put(s, m->end, sizeof m->end);
    }
    tt__put_u32(s, g->npub);
    for (uint32_t k = 0; k < g->npub; k++) {
        const tt_break_event *e = &g->ev_pub[k];
        put_handle(s, e->constraint.index, e->constraint.gen);
        put_handle(s, e->a.index, e->a.gen);
        put_handle(s, e->b.index, e->b.gen);
        tt__put_f64(s, e->length);
        tt__put_f64(s, e->strain);
    }
    tt__put_pool(s, &g->cpool);
    const uint32_t nc = g->cpool.count < g->comp_cap ? g->cpool.count : g->comp_cap;
    tt__put_u32(s, nc);
    for (uint32_t i = 0; i < nc; i++) {
        const tt__composite *k = &g->comps[i];
        tt__put_u8(s, k->alive);
        if (!k->alive) continue;
        tt__put_u32(s, k->np);
        tt__put_u32(s, k->nc);
        for (uint32_t j = 0; j < k->np; j++) put_handle(s, k->parts[j].index, k->parts[j].gen);
        for (uint32_t j = 0; j < k->nc; j++) put_handle(s, k->cons[j].index, k->cons[j].gen);
        tt__put(s, k->rest, 2 * (size_t)k->np * sizeof *k->rest);
    }
}

void tt__cgroup_save(const tt_world *w, const void *self, tt__sink *s)
{
    (void)w;
    const tt__cgroup *g = self;
    tt__put_pool(s, &g->pool);
    for (uint32_t i = 0; i < g->pool.count; i++) {
        const tt__cslot *c = &g->slots[i];
        tt__put_u8(s, c->kind);
        tt__put_u32(s, c->kind ? c->dense : 0);
        tt__put_u32(s, c->kind ? c->mover : 0);
        tt__put_f64(s, c->kind ? c->max_rate : 0.0);
    }
    save_dist(g, s);
    save_gen(g, s);
    save_rest(g, s);
}

/* ---- loading ------------------------------------------------------------------- */

static bool alive(const tt_world *w, uint32_t i) { return i < w->ppool.count && (w->flags[i] & TT__PF_ALIVE); }

static bool slot_is(const tt__cgroup *g, uint32_t slot, uint32_t dense, bool dist)
{
    if (slot >= g->pool.count) return false;
    const tt__cslot *c = &g->slots[slot];
    return c->dense == dense && (dist ? c->kind == TT_CONSTRAINT_DISTANCE : c->kind > TT_CONSTRAINT_DISTANCE);
}

static double get_soft(tt__source *s, double *alpha)
{
    double k = tt__get_num(s, 0.0, 1.0, "stiffness");
    *alpha = tt__get_num(s, 0.0, TT_MAX_VALUE, "compliance");
    if (*alpha != 0.0 && *alpha < TT_MIN_COMPLIANCE) tt__src_fail(s, "compliance %g", *alpha);
    return k;
}

static void load_dist(tt_world *w, tt__cgroup *g, tt__source *s)
{
    uint32_t n = tt__get_count(s, 62, "links");
    if (s->failed) return;
    g->dist = malloc((size_t)(n ? n : 1) * sizeof *g->dist);
    g->dx = calloc(n ? n : 1, sizeof *g->dx);
    if (!g->dist || !g->dx) { tt__src_fail(s, "out of memory"); return; }
    g->dist_cap = g->dx_cap = n;
    for (uint32_t i = 0; i < n && !s->failed; i++) {
        tt__dist *d = &g->dist[i];
        tt__dist_x *x = &g->dx[i];
        d->a = tt__get_u32(s);
        d->b = tt__get_u32(s);
        /* lengths taken from positions reach the world's diagonal, 2√2 × TT_MAX_VALUE */
        d->lo = tt__get_num(s, 0.0, 3 * TT_DIVERGED, "link length"); /* between any two positions short of the guard */
        d->hi = tt__get_num(s, 0.0, INFINITY, "link length");
        d->k = get_soft(s, &d->alpha);
        x->rest = tt__get_num(s, 0.0, 3 * TT_DIVERGED, "link rest length");
        x->break_strain = tt__get_num(s, 0.0, TT_MAX_VALUE, "break strain");
        x->slot = tt__get_u32(s);
        x->mode = tt__get_u8(s);
        x->collide = tt__get_bool(s, "link collide");
        g->ndist = i + 1;
        if (s->failed) return;
        if (!alive(w, d->a) || !alive(w, d->b) || d->a == d->b) { tt__src_fail(s, "link %u joins %u and %u", i, d->a, d->b); return; }
        if (x->mode > TT_DISTANCE_MIN || d->lo > d->hi || (x->mode != TT_DISTANCE_MIN && d->hi > 3 * TT_DIVERGED))
            { tt__src_fail(s, "link %u: mode %u, length [%g, %g]", i, x->mode, d->lo, d->hi); return; }
        if (!slot_is(g, x->slot, i, true)) { tt__src_fail(s, "link %u: slot %u", i, x->slot); return; }
        g->refs[d->a]++;
        g->refs[d->b]++;
        if (x->break_strain > 0) g->nbreakable++;
        if (d->alpha > 0) g->nxpbd++;
        if (!x->collide && !tt__pair_set_add(&g->pairs, d->a, d->b)) { tt__src_fail(s, "out of memory"); return; }
    }
}

/* The particles constraint c names, and what its kind asks of its numbers. */
/* The largest |v[k]| a world can hold: a pin's anchor is where its particle
 * was (any position short of the guard), an area's rest area a product of
 * two coordinates, the rest (bounds, angle limits, pressure) what the API
 * takes. */
static double value_limit(const tt__gcon *c, int k)
{
    if (c->kind == TT_CONSTRAINT_AREA && k == 0) return TT_DIVERGED * TT_DIVERGED;
    return c->kind == TT_CONSTRAINT_PIN ? TT_DIVERGED : TT_MAX_VALUE;
}

static bool gen_valid(const tt_world *w, const tt__gcon *c)
{
    const uint32_t *p = c->list ? c->list : c->p;
    for (uint32_t k = 0; k < c->n; k++)
        if (!alive(w, p[k])) return false;
    for (int k = 0; k < 4; k++)
        if (!(fabs(c->v[k]) <= value_limit(c, k))) return false;
    switch (c->kind) {
    case TT_CONSTRAINT_PIN: return c->n == 1 && !c->list;
    case TT_CONSTRAINT_BOUNDS: return (c->n > 0) == (c->list != NULL) && c->v[0] < c->v[2] && c->v[1] < c->v[3];
    case TT_CONSTRAINT_ANGLE:
    case TT_CONSTRAINT_COLLINEAR:
        return c->n == 3 && !c->list && c->p[0] != c->p[1] && c->p[1] != c->p[2] && c->p[0] != c->p[2];
    case TT_CONSTRAINT_AREA: return c->list && c->n >= 3 && c->v[1] > 0;
    default: return false;
    }
}

static void load_gen(tt_world *w, tt__cgroup *g, tt__source *s)
{
    uint32_t n = tt__get_count(s, 63, "constraints");
    if (s->failed) return;
    g->gen = calloc(n ? n : 1, sizeof *g->gen);
    if (!g->gen) { tt__src_fail(s, "out of memory"); return; }
    g->gen_cap = n;
    for (uint32_t i = 0; i < n && !s->failed; i++) {
        tt__gcon *c = &g->gen[i];
        g->ngen = i + 1;
        c->kind = tt__get_u8(s);
        c->outside = tt__get_bool(s, "outside");
        bool has_list = tt__get_bool(s, "list");
        c->slot = tt__get_u32(s);
        c->n = has_list ? tt__get_count(s, 4, "constraint particles") : tt__get_u32(s);
        if (s->failed) return;
        if (has_list) {
            if (!(c->list = malloc((size_t)(c->n ? c->n : 1) * sizeof *c->list))) { tt__src_fail(s, "out of memory"); return; }
            tt__get(s, c->list, (size_t)c->n * sizeof *c->list);
        } else {
            tt__get(s, c->p, sizeof c->p);
        }
        c->k = get_soft(s, &c->alpha);
        for (int k = 0; k < 4; k++) c->v[k] = tt__get_num(s, -value_limit(c, k), value_limit(c, k), "constraint value");
        c->friction = tt__get_num(s, 0.0, 1.0, "bounds friction");
        if (s->failed) return;
        if (!gen_valid(w, c) || !slot_is(g, c->slot, i, false) || g->slots[c->slot].kind != c->kind)
            { tt__src_fail(s, "constraint %u (kind %u) is not valid", i, c->kind); return; }
        tt__cgroup_gen_refs(g, c, +1);
        /* the area sweep's gradients, sized at creation for the largest polygon */
        if (c->kind == TT_CONSTRAINT_AREA && !tt__grow((void **)&g->scr.grad, &g->scr.grad_cap, c->n, 2 * sizeof(double)))
            tt__src_fail(s, "out of memory");
    }
}

static void load_movers(tt__cgroup *g, tt__source *s)
{
    uint32_t n = tt__get_count(s, 52, "moving targets");
    if (s->failed) return;
    g->moving = malloc((size_t)(n ? n : 1) * sizeof *g->moving);
    if (!g->moving) { tt__src_fail(s, "out of memory"); return; }
    g->moving_cap = n;
    for (uint32_t k = 0; k < n && !s->failed; k++) {
        tt__mover *m = &g->moving[k];
        m->slot = tt__get_u32(s);
        /* a moving target starts from the pin's anchor or the link's length: anywhere short of the guard */
        for (int j = 0; j < 2; j++) m->at[j] = tt__get_num(s, -3 * TT_DIVERGED, 3 * TT_DIVERGED, "target");
        for (int j = 0; j < 2; j++) m->to[j] = tt__get_num(s, -3 * TT_DIVERGED, 3 * TT_DIVERGED, "target");
        for (int j = 0; j < 2; j++) m->end[j] = tt__get_num(s, -3 * TT_DIVERGED, 3 * TT_DIVERGED, "target");
        g->nmoving = k + 1;
        if (s->failed) return;
        uint8_t kind = m->slot < g->pool.count ? g->slots[m->slot].kind : 0;
        if ((kind != TT_CONSTRAINT_DISTANCE && kind != TT_CONSTRAINT_PIN) || g->slots[m->slot].mover != k + 1)
            { tt__src_fail(s, "moving target %u: slot %u", k, m->slot); return; }
        /* a distance's target is a length (tt_distance_set_length's range), stepped into the link */
        if (kind == TT_CONSTRAINT_DISTANCE && !(m->at[0] >= 0 && m->to[0] >= 0 && m->end[0] >= 0 && m->at[1] == 0 &&
                                                m->to[1] == 0 && m->end[1] == 0))
            { tt__src_fail(s, "moving target %u: length %g -> %g not in [0, %g]", k, m->at[0], m->to[0], TT_MAX_VALUE); return; }
    }
    for (uint32_t i = 0; i < g->pool.count && !s->failed; i++)
        if (g->slots[i].mover > n || (g->slots[i].mover && g->moving[g->slots[i].mover - 1].slot != i))
            tt__src_fail(s, "constraint %u: mover %u", i, g->slots[i].mover);
}

static void get_handle(tt__source *s, uint32_t *index, uint32_t *gen)
{
    *index = tt__get_u32(s);
    *gen = tt__get_u32(s);
}

static void load_events(tt__cgroup *g, tt__source *s)
{
    uint32_t n = tt__get_count(s, 40, "break events");
    if (s->failed) return;
    g->ev_pub = malloc((size_t)(n ? n : 1) * sizeof *g->ev_pub);
    if (!g->ev_pub) { tt__src_fail(s, "out of memory"); return; }
    g->cap_pub = g->npub = n;
    for (uint32_t k = 0; k < n; k++) {
        tt_break_event *e = &g->ev_pub[k];
        get_handle(s, &e->constraint.index, &e->constraint.gen);
        get_handle(s, &e->a.index, &e->a.gen);
        get_handle(s, &e->b.index, &e->b.gen);
        e->length = tt__get_num(s, 0.0, 1e300, "break length");
        e->strain = tt__get_num(s, -1.0, TT_MAX_VALUE, "break strain");
    }
}

static bool load_composite(tt__composite *k, tt__source *s)
{
    k->np = tt__get_count(s, 8, "composite particles");
    k->nc = tt__get_count(s, 8, "composite constraints");
    if (s->failed) return false;
    k->ccap = k->nc;
    k->parts = malloc((size_t)(k->np ? k->np : 1) * sizeof *k->parts);
    k->cons = malloc((size_t)(k->nc ? k->nc : 1) * sizeof *k->cons);
    k->rest = malloc(2 * (size_t)(k->np ? k->np : 1) * sizeof *k->rest);
    if (!k->parts || !k->cons || !k->rest) return tt__src_fail(s, "out of memory");
    for (uint32_t j = 0; j < k->np; j++) get_handle(s, &k->parts[j].index, &k->parts[j].gen);
    for (uint32_t j = 0; j < k->nc; j++) get_handle(s, &k->cons[j].index, &k->cons[j].gen);
    for (uint32_t j = 0; j < 2 * k->np; j++) k->rest[j] = tt__get_num(s, -TT_DIVERGED, TT_DIVERGED, "rest offset");
    return !s->failed;
}

static void load_composites(tt_world *w, tt__cgroup *g, tt__source *s)
{
    if (!tt__get_pool(s, &g->cpool, UINT32_MAX - 1, w->tag, "composites")) return;
    uint32_t n = tt__get_count(s, 1, "composites");
    if (s->failed) return;
    if (n > g->cpool.count) { tt__src_fail(s, "%u composites in %u slots", n, g->cpool.count); return; }
    g->comps = calloc(n ? n : 1, sizeof *g->comps);
    if (!g->comps) { tt__src_fail(s, "out of memory"); return; }
    g->comp_cap = n;
    for (uint32_t i = 0; i < n && !s->failed; i++) {
        tt__composite *k = &g->comps[i];
        k->alive = tt__get_bool(s, "composite alive");
        if (!k->alive || !load_composite(k, s)) continue;
        g->comps_alive++;
        for (uint32_t j = 0; j < k->np && !s->failed; j++)
            if (k->parts[j].index >= w->ppool.count) tt__src_fail(s, "composite %u names particle %u", i, k->parts[j].index);
    }
    for (uint32_t f = 0; f < g->cpool.free_count && !s->failed; f++) {
        uint32_t i = g->cpool.free_list[f];
        if (i < n && g->comps[i].alive) tt__src_fail(s, "composite %u is alive and free", i);
    }
}

static void load_slots(tt__cgroup *g, tt__source *s)
{
    const uint32_t n = g->pool.count;
    if (n > (s->len - s->at) / 17) { tt__src_fail(s, "constraints: %u slots are more than the stream holds", n); return; }
    g->slots = calloc(n ? n : 1, sizeof *g->slots);
    if (!g->slots) { tt__src_fail(s, "out of memory"); return; }
    g->slot_cap = n;
    for (uint32_t i = 0; i < n && !s->failed; i++) {
        tt__cslot *c = &g->slots[i];
        c->kind = tt__get_u8(s);
        c->dense = tt__get_u32(s);
        c->mover = tt__get_u32(s);
        c->max_rate = tt__get_num(s, 0.0, TT_MAX_VALUE, "max_rate");
        if (c->kind > TT_CONSTRAINT_COLLINEAR) tt__src_fail(s, "constraint %u: kind %u", i, c->kind);
        if (c->kind) g->alive++;
    }
    for (uint32_t f = 0; f < g->pool.free_count && !s->failed; f++)
        if (g->slots[g->pool.free_list[f]].kind) tt__src_fail(s, "constraint %u is alive and free", g->pool.free_list[f]);
}

void *tt__cgroup_load(tt_world *w, tt__source *s)
{
    tt__cgroup *g = calloc(1, sizeof *g);
    if (!g) { tt__src_fail(s, "out of memory"); return NULL; }
    g->pool.tag = g->cpool.tag = w->tag;
    if (tt__get_pool(s, &g->pool, UINT32_MAX - 1, w->tag, "constraints")) {
        load_slots(g, s);
        if (!s->failed && !tt__cgroup_refs_reserve(w, g)) tt__src_fail(s, "out of memory");
        if (!s->failed) load_dist(w, g, s);
        if (!s->failed) load_gen(w, g, s);
        if (!s->failed) load_movers(g, s);
        if (!s->failed) load_events(g, s);
        if (!s->failed) load_composites(w, g, s);
    }
    /* every live slot must have been claimed by its entry */
    if (!s->failed && g->alive != g->ndist + g->ngen) tt__src_fail(s, "%u live constraint slots, %u constraints", g->alive, g->ndist + g->ngen);
    if (!s->failed) return g;
    tt__cgroup_destroy(w, g);
    return NULL;
}
