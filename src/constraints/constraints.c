/* tether — position constraints: storage, public API, and the relaxation
 * group the solver sweeps (solver.c owns the loop; this file only says how
 * one sweep corrects positions, through tt__correct so Jacobi works too). */
#include "constraint_internal.h"

#include <stdlib.h>
#include <string.h>

static const double TT_PI = 3.14159265358979323846;

/* ---- group registration ------------------------------------------------ */

static void group_begin(tt_world *w, void *self, double h);
static double group_relax(tt_world *w, void *self, double h);
static void group_sweeps_done(tt_world *w, void *self);
static void group_end(tt_world *w, void *self, double h);
static void group_after_step(tt_world *w, void *self);
static void group_particle_removed(tt_world *w, void *self, uint32_t index);
static uint64_t group_hash(const tt_world *w, const void *self, uint64_t h);
static size_t group_memory(const tt_world *w, const void *self);
static void group_destroy(tt_world *w, void *self);

static const tt__group_ops constraint_ops = {
    .name = "constraints", .rank = TT__RANK_CONSTRAINTS,
    .begin_stage = TT_STAGE_SOLVE,
    .begin = group_begin,
    .relax = group_relax,
    .sweeps_done = group_sweeps_done,
    .end = group_end,
    .after_step = group_after_step,
    .particle_removed = group_particle_removed,
    .hash = group_hash,
    .memory = group_memory,
    .destroy = group_destroy,
};

const tt__cgroup *tt__cgroup_peek(const tt_world *w)
{
    return w ? (const tt__cgroup *)tt__group_find(w, &constraint_ops) : NULL;
}

tt__cgroup *tt__cgroup_get(tt_world *w, bool create)
{
    tt__cgroup *g = tt__group_find(w, &constraint_ops);
    if (g || !create) return g;
    g = calloc(1, sizeof *g);
    if (!g) return NULL;
    g->pool.tag = g->cpool.tag = w->tag; /* handles carry the world's tag */
    if (tt__group_add(w, &constraint_ops, g) < 0) {
        free(g);
        return NULL;
    }
    return g;
}

void tt__cgroup_unmake(tt_world *w, bool had)
{
    if (!had) tt__group_remove(w, &constraint_ops);
}

static bool grow(void **p, size_t elem, uint32_t *cap, uint32_t need)
{
    if (need <= *cap) return true;
    uint32_t c = *cap ? *cap : 64;
    while (c < need) c = c > UINT32_MAX / 2 ? need : c * 2;
    void *q = realloc(*p, elem * c);
    if (!q) return false;
    *p = q;
    *cap = c;
    return true;
}

/* ---- excluded collision pairs: open addressing, linear probing ---------- */

static inline uint64_t pair_key(uint32_t a, uint32_t b)
{
    uint32_t lo = a < b ? a : b, hi = a < b ? b : a;
    return (((uint64_t)lo << 32) | hi) + 1; /* never 0: 0 marks an empty slot */
}

static inline uint32_t pair_hash(uint64_t k, uint32_t mask)
{
    k ^= k >> 33;
    k *= 0xff51afd7ed558ccdull;
    k ^= k >> 33;
    return (uint32_t)k & mask;
}

static bool pairs_rehash(tt__cgroup *g, uint32_t cap)
{
    uint64_t *keys = calloc(cap, sizeof *keys);
    uint32_t *ns = calloc(cap, sizeof *ns);
    if (!keys || !ns) {
        free(keys);
        free(ns);
        return false;
    }
    for (uint32_t i = 0; i < g->pair_cap; i++) {
        if (!g->pair_key[i]) continue;
        uint32_t j = pair_hash(g->pair_key[i], cap - 1);
        while (keys[j]) j = (j + 1) & (cap - 1);
        keys[j] = g->pair_key[i];
        ns[j] = g->pair_n[i];
    }
    free(g->pair_key);
    free(g->pair_n);
    g->pair_key = keys;
    g->pair_n = ns;
    g->pair_cap = cap;
    return true;
}

static bool pair_add(tt__cgroup *g, uint32_t a, uint32_t b)
{
    if ((g->pair_used + 1) * 2 > g->pair_cap && !pairs_rehash(g, g->pair_cap ? g->pair_cap * 2 : 64)) return false;
    uint64_t k = pair_key(a, b);
    uint32_t m = g->pair_cap - 1, j = pair_hash(k, m);
    while (g->pair_key[j] && g->pair_key[j] != k) j = (j + 1) & m;
    if (!g->pair_key[j]) {
        g->pair_key[j] = k;
        g->pair_used++;
    }
    g->pair_n[j]++;
    return true;
}

static void pair_remove(tt__cgroup *g, uint32_t a, uint32_t b)
{
    if (!g->pair_cap) return;
    uint64_t k = pair_key(a, b);
    uint32_t m = g->pair_cap - 1, j = pair_hash(k, m);
    while (g->pair_key[j] && g->pair_key[j] != k) j = (j + 1) & m;
    if (!g->pair_key[j] || --g->pair_n[j] > 0) return;
    /* backward-shift deletion keeps every probe chain unbroken */
    g->pair_key[j] = 0;
    g->pair_n[j] = 0;
    g->pair_used--;
    uint32_t i = j;
    for (;;) {
        i = (i + 1) & m;
        if (!g->pair_key[i]) break;
        uint32_t home = pair_hash(g->pair_key[i], m);
        /* move i into the hole j if its home is not cyclically in (j, i] */
        bool move = j <= i ? (home <= j || home > i) : (home <= j && home > i);
        if (move) {
            g->pair_key[j] = g->pair_key[i];
            g->pair_n[j] = g->pair_n[i];
            g->pair_key[i] = 0;
            g->pair_n[i] = 0;
            j = i;
        }
    }
}

bool tt__constraint_pair_excluded(const tt_world *w, uint32_t a, uint32_t b)
{
    const tt__cgroup *g = tt__cgroup_peek(w);
    if (!g || !g->pair_used) return false;
    uint64_t k = pair_key(a, b);
    uint32_t m = g->pair_cap - 1, j = pair_hash(k, m);
    while (g->pair_key[j]) {
        if (g->pair_key[j] == k) return true;
        j = (j + 1) & m;
    }
    return false;
}

bool tt__constraint_pairs_any(const tt_world *w)
{
    const tt__cgroup *g = tt__cgroup_peek(w);
    return g && g->pair_used;
}

/* ---- slots and handles -------------------------------------------------- */

static bool slot_new(tt__cgroup *g, uint8_t kind, uint32_t dense, uint32_t *out)
{
    /* room first: freeing a slot taken in vain would age its generation */
    uint32_t need = g->pool.free_count ? g->pool.count : g->pool.count + 1;
    if (!grow((void **)&g->slots, sizeof *g->slots, &g->slot_cap, need)) return false;
    bool grew;
    uint32_t s = tt_pool_alloc(&g->pool, UINT32_MAX - 1, &grew);
    if (s == UINT32_MAX) return false;
    g->slots[s] = (tt__cslot){kind, dense};
    g->alive++;
    *out = s;
    return true;
}

static bool con_ok(const tt__cgroup *g, tt_constraint c)
{
    return g && c.gen != 0 && c.index < g->pool.count && g->pool.gen[c.index] == c.gen && g->slots[c.index].kind != 0;
}

static tt_result con_check(const tt_world *w, tt_constraint c, const char *fn, const tt__cgroup **out)
{
    if (!w) return tt__fail(NULL, TT_EINVAL, "%s: world is NULL", fn);
    const tt__cgroup *g = tt__cgroup_peek(w);
    if (!con_ok(g, c))
        return tt__fail(w, TT_ESTALE, "%s: stale constraint handle (index %u, generation %u)", fn, c.index, c.gen);
    *out = g;
    return TT_OK;
}

static tt_constraint handle_of(const tt__cgroup *g, uint32_t slot) { return (tt_constraint){slot, g->pool.gen[slot]}; }
static tt_particle particle_of(const tt_world *w, uint32_t i) { return (tt_particle){i, w->ppool.gen[i]}; }

/* ---- particle reference counts --------------------------------------------- */

static bool refs_reserve(const tt_world *w, tt__cgroup *g)
{
    if (g->refs_cap >= w->pcap) return true;
    uint32_t *r = realloc(g->refs, (size_t)w->pcap * sizeof *r);
    if (!r) return false;
    memset(r + g->refs_cap, 0, (size_t)(w->pcap - g->refs_cap) * sizeof *r);
    g->refs = r;
    g->refs_cap = w->pcap;
    return true;
}

static void gen_refs(tt__cgroup *g, const tt__gcon *c, int delta)
{
    const uint32_t *p = c->list ? c->list : c->p;
    for (uint32_t k = 0; k < c->n; k++) g->refs[p[k]] += (uint32_t)delta;
}

/* Link i's lo, hi, k or alpha changed: its copy follows (a stale plan is rebuilt whole). */
static void hot_sync(tt__cgroup *g, uint32_t i)
{
    if (!g->plan_ok) return;
    g->h_lo[i] = g->dist[i].lo;
    g->h_hi[i] = g->dist[i].hi;
    g->h_k[i] = g->dist[i].k;
    g->h_alpha[i] = g->dist[i].alpha;
}

/* ---- removal ------------------------------------------------------------- */

static void dist_remove(tt__cgroup *g, uint32_t d)
{
    tt__dist *c = &g->dist[d];
    tt__dist_x *x = &g->dx[d];
    if (!x->collide) pair_remove(g, c->a, c->b);
    g->refs[c->a]--;
    g->refs[c->b]--;
    if (x->break_strain > 0) g->nbreakable--;
    if (c->alpha > 0) g->nxpbd--;
    g->slots[x->slot].kind = 0;
    tt_pool_free(&g->pool, x->slot);
    g->alive--;
    g->plan_ok = false;
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
    gen_refs(g, c, -1);
    free(c->list);
    g->slots[c->slot].kind = 0;
    tt_pool_free(&g->pool, c->slot);
    g->alive--;
    uint32_t last = --g->ngen;
    if (d != last) {
        g->gen[d] = g->gen[last];
        g->slots[g->gen[d].slot].dense = d;
    }
}

static void slot_remove(tt__cgroup *g, uint32_t s)
{
    if (g->slots[s].kind == TT_CONSTRAINT_DISTANCE)
        dist_remove(g, g->slots[s].dense);
    else
        gen_remove(g, g->slots[s].dense);
}

/* ---- defaults and validation --------------------------------------------- */

tt_distance_def tt_distance_def_default(void)
{
    tt_distance_def d;
    memset(&d, 0, sizeof d);
    d.mode = TT_DISTANCE_RIGID;
    d.length = -1.0;
    d.stiffness = 1.0;
    return d;
}

tt_pin_def tt_pin_def_default(void)
{
    tt_pin_def d;
    memset(&d, 0, sizeof d);
    d.anchor_here = true;
    d.stiffness = 1.0;
    return d;
}

tt_bounds_def tt_bounds_def_default(void)
{
    tt_bounds_def d;
    memset(&d, 0, sizeof d);
    d.min = (tt_vec2){-10, -10};
    d.max = (tt_vec2){10, 10};
    return d;
}

tt_angle_def tt_angle_def_default(void)
{
    tt_angle_def d;
    memset(&d, 0, sizeof d);
    d.min = -TT_PI;
    d.max = TT_PI;
    d.use_current = true;
    d.stiffness = 1.0;
    return d;
}

tt_area_def tt_area_def_default(void)
{
    tt_area_def d;
    memset(&d, 0, sizeof d);
    d.use_current = true;
    d.pressure = 1.0;
    d.stiffness = 1.0;
    return d;
}

tt_collinear_def tt_collinear_def_default(void)
{
    tt_collinear_def d;
    memset(&d, 0, sizeof d);
    d.stiffness = 1.0;
    return d;
}

/* Compliances under TT_MIN_COMPLIANCE are refused, not rounded to 0: the
 * energy ½C²/α of a denormal α is Inf. */
static tt_result check_compliance(const tt_world *w, double alpha, const char *fn)
{
    if (alpha == 0.0 || tt__in_range(alpha, TT_MIN_COMPLIANCE, TT_MAX_VALUE)) return TT_OK;
    return tt__fail(w, TT_EINVAL, "%s: compliance must be 0 (rigid) or in [%g, %g] m/N, got %g", fn, TT_MIN_COMPLIANCE,
                    TT_MAX_VALUE, alpha);
}

static tt_result check_soft(const tt_world *w, double k, double alpha, const char *fn)
{
    if (!tt__in_range(k, 0.0, 1.0)) return tt__fail(w, TT_EINVAL, "%s: stiffness must be in [0, 1], got %g", fn, k);
    return check_compliance(w, alpha, fn);
}

static tt_result check_distinct(const tt_world *w, const tt_particle *p, int n, const char *fn)
{
    for (int i = 0; i < n; i++) {
        tt_result r = tt__particle_check(w, p[i], fn);
        if (r != TT_OK) return r;
        for (int j = 0; j < i; j++)
            if (p[i].index == p[j].index) return tt__fail(w, TT_EINVAL, "%s: the particles must be distinct", fn);
    }
    return TT_OK;
}

#define NONE ((tt_constraint){0, 0})

/* ---- geometry ------------------------------------------------------------- */

static inline double dist_of(const tt_world *w, uint32_t a, uint32_t b)
{
    double dx = w->px[b] - w->px[a], dy = w->py[b] - w->py[a];
    return sqrt(dx * dx + dy * dy);
}

static double wrap_angle(double a)
{
    while (a > TT_PI) a -= 2 * TT_PI;
    while (a <= -TT_PI) a += 2 * TT_PI;
    return a;
}

static double angle_at(const tt_world *w, uint32_t a, uint32_t b, uint32_t c)
{
    double ux = w->px[a] - w->px[b], uy = w->py[a] - w->py[b];
    double vx = w->px[c] - w->px[b], vy = w->py[c] - w->py[b];
    return atan2(ux * vy - uy * vx, ux * vx + uy * vy);
}

/* Signed angle error: 0 inside [lo, hi], else the way back to the nearer bound. */
static double angle_error(double th, double lo, double hi)
{
    if (lo <= hi ? (th >= lo && th <= hi) : (th >= lo || th <= hi)) return 0.0; /* lo > hi: wraps through ±π */
    double el = wrap_angle(th - lo), eh = wrap_angle(th - hi);
    return fabs(el) < fabs(eh) ? el : eh;
}

static double polygon_area(const tt_world *w, const uint32_t *p, uint32_t n)
{
    double a = 0.0;
    for (uint32_t i = 0; i < n; i++) {
        uint32_t j = i + 1 == n ? 0 : i + 1;
        a += w->px[p[i]] * w->py[p[j]] - w->px[p[j]] * w->py[p[i]];
    }
    return 0.5 * a;
}

/* ---- creation ------------------------------------------------------------- */

tt_constraint tt_distance_create(tt_world *w, const tt_distance_def *d)
{
    const char *fn = "tt_distance_create";
    if (!w) { tt__fail(NULL, TT_EINVAL, "%s: world is NULL", fn); return NONE; }
    if (!d) { tt__fail(w, TT_EINVAL, "%s: def is NULL", fn); return NONE; }
    tt_particle ab[2] = {d->a, d->b};
    if (check_distinct(w, ab, 2, fn) != TT_OK) return NONE;
    if (d->mode != TT_DISTANCE_RIGID && d->mode != TT_DISTANCE_MAX && d->mode != TT_DISTANCE_MIN) {
        tt__fail(w, TT_EINVAL, "%s: unknown mode %d", fn, (int)d->mode);
        return NONE;
    }
    if (!(d->length == -1.0 || tt__in_range(d->length, 0.0, TT_MAX_VALUE))) {
        tt__fail(w, TT_EINVAL, "%s: length must be -1 (current distance) or in [0, %g], got %g", fn, TT_MAX_VALUE, d->length);
        return NONE;
    }
    if (check_soft(w, d->stiffness, d->compliance, fn) != TT_OK) return NONE;
    if (!tt__in_range(d->break_strain, 0.0, TT_MAX_VALUE)) {
        tt__fail(w, TT_EINVAL, "%s: break_strain must be in [0, %g] (0 = never), got %g", fn, TT_MAX_VALUE, d->break_strain);
        return NONE;
    }
    const bool had = tt__cgroup_peek(w) != NULL; /* a group made here goes again if this fails */
    tt__cgroup *g = tt__cgroup_get(w, true);
    if (!g || !refs_reserve(w, g) || !grow((void **)&g->dist, sizeof *g->dist, &g->dist_cap, g->ndist + 1) ||
        !grow((void **)&g->dx, sizeof *g->dx, &g->dx_cap, g->ndist + 1))
        goto nomem;
    if (!d->collide && !pair_add(g, d->a.index, d->b.index)) goto nomem;
    uint32_t slot;
    if (!slot_new(g, TT_CONSTRAINT_DISTANCE, g->ndist, &slot)) {
        if (!d->collide) pair_remove(g, d->a.index, d->b.index);
        goto nomem;
    }
    double len = d->length < 0 ? dist_of(w, d->a.index, d->b.index) : d->length;
    tt__dist *c = &g->dist[g->ndist];
    c->a = d->a.index;
    c->b = d->b.index;
    c->lo = d->mode == TT_DISTANCE_MAX ? 0.0 : len;
    c->hi = d->mode == TT_DISTANCE_MIN ? INFINITY : len;
    c->k = d->stiffness;
    c->alpha = d->compliance;
    g->dx[g->ndist] = (tt__dist_x){0.0, len, d->break_strain, slot, (uint8_t)d->mode, d->collide};
    g->ndist++;
    g->plan_ok = false;
    g->refs[c->a]++;
    g->refs[c->b]++;
    if (d->break_strain > 0) g->nbreakable++;
    if (d->compliance > 0) g->nxpbd++;
    return handle_of(g, slot);
nomem:
    tt__cgroup_unmake(w, had);
    tt__fail(w, TT_ENOMEM, "%s: out of memory", fn);
    return NONE;
}

/* A generic constraint's record, reserved; NULL on no memory. */
static tt__gcon *gen_new(tt_world *w, uint8_t kind, tt_constraint *h, const char *fn)
{
    const bool had = tt__cgroup_peek(w) != NULL;
    tt__cgroup *g = tt__cgroup_get(w, true);
    uint32_t slot;
    if (!g || !refs_reserve(w, g) || !grow((void **)&g->gen, sizeof *g->gen, &g->gen_cap, g->ngen + 1) ||
        !slot_new(g, kind, g->ngen, &slot)) {
        tt__cgroup_unmake(w, had);
        tt__fail(w, TT_ENOMEM, "%s: out of memory", fn);
        return NULL;
    }
    tt__gcon *c = &g->gen[g->ngen++];
    memset(c, 0, sizeof *c);
    c->kind = kind;
    c->slot = slot;
    *h = handle_of(g, slot);
    return c;
}

tt_constraint tt_pin_create(tt_world *w, const tt_pin_def *d)
{
    const char *fn = "tt_pin_create";
    if (!w) { tt__fail(NULL, TT_EINVAL, "%s: world is NULL", fn); return NONE; }
    if (!d) { tt__fail(w, TT_EINVAL, "%s: def is NULL", fn); return NONE; }
    if (tt__particle_check(w, d->particle, fn) != TT_OK) return NONE;
    if (!d->anchor_here && !tt__vec_ok(d->anchor)) {
        tt__fail(w, TT_EINVAL, "%s: anchor must be finite, |x| <= %g", fn, TT_MAX_VALUE);
        return NONE;
    }
    if (check_soft(w, d->stiffness, d->compliance, fn) != TT_OK) return NONE;
    tt_constraint h;
    tt__gcon *c = gen_new(w, TT_CONSTRAINT_PIN, &h, fn);
    if (!c) return NONE;
    uint32_t i = d->particle.index;
    c->n = 1;
    c->p[0] = i;
    c->k = d->stiffness;
    c->alpha = d->compliance;
    c->v[0] = d->anchor_here ? w->px[i] : d->anchor.x;
    c->v[1] = d->anchor_here ? w->py[i] : d->anchor.y;
    gen_refs(tt__cgroup_get(w, false), c, +1);
    return h;
}

static tt_result check_box(const tt_world *w, tt_vec2 lo, tt_vec2 hi, const char *fn)
{
    if (!tt__vec_ok(lo) || !tt__vec_ok(hi))
        return tt__fail(w, TT_EINVAL, "%s: box corners must be finite, |x| <= %g", fn, TT_MAX_VALUE);
    if (!(lo.x < hi.x && lo.y < hi.y)) return tt__fail(w, TT_EINVAL, "%s: need min < max on both axes", fn);
    return TT_OK;
}

static uint32_t *copy_list(tt_world *w, const tt_particle *ps, uint32_t n, bool distinct, const char *fn)
{
    for (uint32_t i = 0; i < n; i++)
        if (tt__particle_check(w, ps[i], fn) != TT_OK) return NULL;
    uint32_t *list = malloc((size_t)n * sizeof *list);
    if (!list) {
        tt__fail(w, TT_ENOMEM, "%s: out of memory", fn);
        return NULL;
    }
    for (uint32_t i = 0; i < n; i++) list[i] = ps[i].index;
    if (distinct) { /* O(n) with a mark in the flags would touch shared state; polygons are small */
        for (uint32_t i = 0; i < n; i++)
            for (uint32_t j = 0; j < i; j++)
                if (list[i] == list[j]) {
                    free(list);
                    tt__fail(w, TT_EINVAL, "%s: the particles must be distinct", fn);
                    return NULL;
                }
    }
    return list;
}

tt_constraint tt_bounds_create(tt_world *w, const tt_bounds_def *d)
{
    const char *fn = "tt_bounds_create";
    if (!w) { tt__fail(NULL, TT_EINVAL, "%s: world is NULL", fn); return NONE; }
    if (!d) { tt__fail(w, TT_EINVAL, "%s: def is NULL", fn); return NONE; }
    if (check_box(w, d->min, d->max, fn) != TT_OK) return NONE;
    if (!tt__in_range(d->friction, 0.0, 1.0)) {
        tt__fail(w, TT_EINVAL, "%s: friction must be in [0, 1], got %g", fn, d->friction);
        return NONE;
    }
    if (d->count && !d->particles) { tt__fail(w, TT_EINVAL, "%s: particles is NULL with count %u", fn, d->count); return NONE; }
    uint32_t *list = NULL;
    if (d->count && !(list = copy_list(w, d->particles, d->count, false, fn))) return NONE;
    tt_constraint h;
    tt__gcon *c = gen_new(w, TT_CONSTRAINT_BOUNDS, &h, fn);
    if (!c) {
        free(list);
        return NONE;
    }
    c->n = d->count;
    c->list = list;
    c->outside = d->outside;
    c->friction = d->friction;
    c->k = 1.0;
    c->v[0] = d->min.x;
    c->v[1] = d->min.y;
    c->v[2] = d->max.x;
    c->v[3] = d->max.y;
    gen_refs(tt__cgroup_get(w, false), c, +1);
    return h;
}

/* A constraint on three particles (angle, collinear), made after its def was checked. */
static tt__gcon *gen_new_triple(tt_world *w, uint8_t kind, const tt_particle abc[3], double k, double alpha,
                                tt_constraint *h, const char *fn)
{
    tt__gcon *c = gen_new(w, kind, h, fn);
    if (!c) return NULL;
    c->n = 3;
    for (int i = 0; i < 3; i++) c->p[i] = abc[i].index;
    c->k = k;
    c->alpha = alpha;
    return c;
}

tt_constraint tt_angle_create(tt_world *w, const tt_angle_def *d)
{
    const char *fn = "tt_angle_create";
    if (!w) { tt__fail(NULL, TT_EINVAL, "%s: world is NULL", fn); return NONE; }
    if (!d) { tt__fail(w, TT_EINVAL, "%s: def is NULL", fn); return NONE; }
    tt_particle abc[3] = {d->a, d->b, d->c};
    if (check_distinct(w, abc, 3, fn) != TT_OK) return NONE;
    if (!d->use_current && !(tt__in_range(d->min, -TT_PI, TT_PI) && tt__in_range(d->max, -TT_PI, TT_PI))) {
        tt__fail(w, TT_EINVAL, "%s: min and max must be in [-pi, pi], got [%g, %g]", fn, d->min, d->max);
        return NONE;
    }
    if (check_soft(w, d->stiffness, d->compliance, fn) != TT_OK) return NONE;
    tt_constraint h;
    tt__gcon *c = gen_new_triple(w, TT_CONSTRAINT_ANGLE, abc, d->stiffness, d->compliance, &h, fn);
    if (!c) return NONE;
    double th = angle_at(w, c->p[0], c->p[1], c->p[2]);
    c->v[0] = d->use_current ? th : d->min;
    c->v[1] = d->use_current ? th : d->max;
    gen_refs(tt__cgroup_get(w, false), c, +1);
    return h;
}

tt_constraint tt_area_create(tt_world *w, const tt_area_def *d)
{
    const char *fn = "tt_area_create";
    if (!w) { tt__fail(NULL, TT_EINVAL, "%s: world is NULL", fn); return NONE; }
    if (!d) { tt__fail(w, TT_EINVAL, "%s: def is NULL", fn); return NONE; }
    if (d->count < 3 || d->count > 65536 || !d->particles) {
        tt__fail(w, TT_EINVAL, "%s: need 3 … 65536 particles, got %u%s", fn, d->count, d->particles ? "" : " (NULL)");
        return NONE;
    }
    if (!d->use_current && !tt__in_range(d->area, -TT_MAX_VALUE, TT_MAX_VALUE)) {
        tt__fail(w, TT_EINVAL, "%s: area must be finite, |a| <= %g", fn, TT_MAX_VALUE);
        return NONE;
    }
    if (!(d->pressure > 0 && d->pressure <= TT_MAX_VALUE)) {
        tt__fail(w, TT_EINVAL, "%s: pressure must be in (0, %g], got %g", fn, TT_MAX_VALUE, d->pressure);
        return NONE;
    }
    if (check_soft(w, d->stiffness, d->compliance, fn) != TT_OK) return NONE;
    uint32_t *list = copy_list(w, d->particles, d->count, true, fn);
    if (!list) return NONE;
    const bool had = tt__cgroup_peek(w) != NULL;
    tt__cgroup *g = tt__cgroup_get(w, true);
    if (!g || !grow((void **)&g->grad, 2 * sizeof(double), &g->grad_cap, d->count)) {
        free(list);
        tt__cgroup_unmake(w, had);
        tt__fail(w, TT_ENOMEM, "%s: out of memory", fn);
        return NONE;
    }
    tt_constraint h;
    tt__gcon *c = gen_new(w, TT_CONSTRAINT_AREA, &h, fn);
    if (!c) {
        free(list);
        tt__cgroup_unmake(w, had);
        return NONE;
    }
    c->n = d->count;
    c->list = list;
    c->k = d->stiffness;
    c->alpha = d->compliance;
    c->v[0] = d->use_current ? polygon_area(w, list, d->count) : d->area;
    c->v[1] = d->pressure;
    gen_refs(tt__cgroup_get(w, false), c, +1);
    return h;
}

tt_constraint tt_collinear_create(tt_world *w, const tt_collinear_def *d)
{
    const char *fn = "tt_collinear_create";
    if (!w) { tt__fail(NULL, TT_EINVAL, "%s: world is NULL", fn); return NONE; }
    if (!d) { tt__fail(w, TT_EINVAL, "%s: def is NULL", fn); return NONE; }
    tt_particle abc[3] = {d->a, d->b, d->c};
    if (check_distinct(w, abc, 3, fn) != TT_OK) return NONE;
    if (check_soft(w, d->stiffness, d->compliance, fn) != TT_OK) return NONE;
    tt_constraint h;
    tt__gcon *c = gen_new_triple(w, TT_CONSTRAINT_COLLINEAR, abc, d->stiffness, d->compliance, &h, fn);
    if (!c) return NONE;
    gen_refs(tt__cgroup_get(w, false), c, +1);
    return h;
}

/* ---- per-constraint reads and writes ---------------------------------------- */

tt_result tt_constraint_destroy(tt_world *w, tt_constraint c)
{
    const tt__cgroup *g;
    tt_result r = con_check(w, c, "tt_constraint_destroy", &g);
    if (r != TT_OK) return r;
    slot_remove((tt__cgroup *)g, c.index);
    return TT_OK;
}

bool tt_constraint_is_valid(const tt_world *w, tt_constraint c) { return con_ok(tt__cgroup_peek(w), c); }

tt_result tt_constraint_get_kind(const tt_world *w, tt_constraint c, tt_constraint_kind *out)
{
    const tt__cgroup *g;
    tt_result r = con_check(w, c, "tt_constraint_get_kind", &g);
    if (r != TT_OK) return r;
    if (!out) return tt__fail(w, TT_EINVAL, "tt_constraint_get_kind: out is NULL");
    *out = (tt_constraint_kind)g->slots[c.index].kind;
    return TT_OK;
}

static double bounds_violation(const tt_world *w, const tt__gcon *c, uint32_t i, double *dx, double *dy)
{
    double r = w->radius[i], x = w->px[i], y = w->py[i];
    double x0 = c->v[0] + r, y0 = c->v[1] + r, x1 = c->v[2] - r, y1 = c->v[3] - r;
    *dx = *dy = 0.0;
    if (!c->outside) {
        if (x0 > x1) x0 = x1 = 0.5 * (c->v[0] + c->v[2]); /* a disc wider than the box: keep its centre in the middle */
        if (y0 > y1) y0 = y1 = 0.5 * (c->v[1] + c->v[3]);
        if (x < x0) *dx = x0 - x; else if (x > x1) *dx = x1 - x;
        if (y < y0) *dy = y0 - y; else if (y > y1) *dy = y1 - y;
        return fmax(fabs(*dx), fabs(*dy));
    }
    double ex0 = c->v[0] - r, ey0 = c->v[1] - r, ex1 = c->v[2] + r, ey1 = c->v[3] + r;
    if (!(x > ex0 && x < ex1 && y > ey0 && y < ey1)) return 0.0;
    double l = x - ex0, rr = ex1 - x, b = y - ey0, t = ey1 - y; /* push out through the nearest side */
    double m = fmin(fmin(l, rr), fmin(b, t));
    if (m == t) *dy = t;
    else if (m == b) *dy = -b;
    else if (m == l) *dx = -l;
    else *dx = rr;
    return m;
}

static double gen_error(const tt_world *w, const tt__gcon *c)
{
    switch (c->kind) {
    case TT_CONSTRAINT_PIN: return hypot(w->px[c->p[0]] - c->v[0], w->py[c->p[0]] - c->v[1]);
    case TT_CONSTRAINT_BOUNDS: {
        double e = 0.0, dx, dy;
        if (c->n) {
            for (uint32_t k = 0; k < c->n; k++) e = fmax(e, bounds_violation(w, c, c->list[k], &dx, &dy));
        } else {
            for (uint32_t i = 0; i < w->ppool.count; i++)
                if (w->flags[i] & TT_PF_ALIVE) e = fmax(e, bounds_violation(w, c, i, &dx, &dy));
        }
        return e;
    }
    case TT_CONSTRAINT_ANGLE: return fabs(angle_error(angle_at(w, c->p[0], c->p[1], c->p[2]), c->v[0], c->v[1]));
    case TT_CONSTRAINT_AREA: return fabs(polygon_area(w, c->list, c->n) - c->v[0] * c->v[1]);
    case TT_CONSTRAINT_COLLINEAR: {
        uint32_t a = c->p[0], b = c->p[1], cc = c->p[2];
        double ex = w->px[cc] - w->px[a], ey = w->py[cc] - w->py[a], L = hypot(ex, ey);
        double bx = w->px[b] - w->px[a], by = w->py[b] - w->py[a];
        return L > 0 ? fabs(bx * ey - by * ex) / L : hypot(bx, by);
    }
    }
    return 0.0;
}

/* Energy stored by compliant constraints, Σ ½ C²/α, C as the solver sees it. */
double tt__constraints_energy(const tt_world *w)
{
    const tt__cgroup *g = tt__cgroup_peek(w);
    if (!g) return 0.0;
    double e = 0.0;
    for (uint32_t i = 0; i < g->ndist; i++) {
        const tt__dist *d = &g->dist[i];
        if (!(d->alpha > 0.0)) continue;
        const double len = dist_of(w, d->a, d->b), C = len < d->lo ? d->lo - len : len > d->hi ? len - d->hi : 0.0;
        e += 0.5 * C * C / d->alpha;
    }
    for (uint32_t i = 0; i < g->ngen; i++) {
        const tt__gcon *c = &g->gen[i];
        if (!(c->alpha > 0.0)) continue;
        double C = gen_error(w, c);
        if (c->kind == TT_CONSTRAINT_COLLINEAR) { /* the solver's C is the cross product, not the distance */
            const uint32_t a = c->p[0], b = c->p[1], cc = c->p[2];
            C = (w->px[b] - w->px[a]) * (w->py[cc] - w->py[a]) - (w->py[b] - w->py[a]) * (w->px[cc] - w->px[a]);
        }
        e += 0.5 * C * C / c->alpha;
    }
    return e;
}

tt_result tt_constraint_get_error(const tt_world *w, tt_constraint c, double *out)
{
    const tt__cgroup *g;
    tt_result r = con_check(w, c, "tt_constraint_get_error", &g);
    if (r != TT_OK) return r;
    if (!out) return tt__fail(w, TT_EINVAL, "tt_constraint_get_error: out is NULL");
    const tt__cslot *s = &g->slots[c.index];
    if (s->kind == TT_CONSTRAINT_DISTANCE) {
        const tt__dist *d = &g->dist[s->dense];
        double len = dist_of(w, d->a, d->b);
        *out = len < d->lo ? d->lo - len : len > d->hi ? len - d->hi : 0.0;
    } else {
        *out = gen_error(w, &g->gen[s->dense]);
    }
    return TT_OK;
}

tt_result tt_constraint_get_particles(const tt_world *w, tt_constraint c, tt_particle *out, uint32_t cap, uint32_t *count)
{
    const tt__cgroup *g;
    tt_result r = con_check(w, c, "tt_constraint_get_particles", &g);
    if (r != TT_OK) return r;
    const tt__cslot *s = &g->slots[c.index];
    uint32_t n;
    if (s->kind == TT_CONSTRAINT_DISTANCE) {
        const tt__dist *d = &g->dist[s->dense];
        n = 2;
        if (out && cap > 0) out[0] = particle_of(w, d->a);
        if (out && cap > 1) out[1] = particle_of(w, d->b);
    } else {
        const tt__gcon *gc = &g->gen[s->dense];
        n = gc->n;
        for (uint32_t k = 0; out && k < n && k < cap; k++) out[k] = particle_of(w, gc->list ? gc->list[k] : gc->p[k]);
    }
    if (count) *count = n;
    return TT_OK;
}

tt_result tt_constraint_set_stiffness(tt_world *w, tt_constraint c, double k)
{
    const char *fn = "tt_constraint_set_stiffness";
    const tt__cgroup *cg;
    tt_result r = con_check(w, c, fn, &cg);
    if (r != TT_OK) return r;
    tt__cgroup *g = (tt__cgroup *)cg;
    if (!tt__in_range(k, 0.0, 1.0)) return tt__fail(w, TT_EINVAL, "%s: stiffness must be in [0, 1], got %g", fn, k);
    tt__cslot *s = &g->slots[c.index];
    if (s->kind == TT_CONSTRAINT_BOUNDS) return tt__fail(w, TT_ESTATE, "%s: bounds are always stiff", fn);
    if (s->kind == TT_CONSTRAINT_DISTANCE) {
        g->dist[s->dense].k = k;
        hot_sync(g, s->dense);
    } else {
        g->gen[s->dense].k = k;
    }
    return TT_OK;
}

tt_result tt_constraint_set_compliance(tt_world *w, tt_constraint c, double alpha)
{
    const char *fn = "tt_constraint_set_compliance";
    const tt__cgroup *cg;
    tt_result r = con_check(w, c, fn, &cg);
    if (r != TT_OK) return r;
    tt__cgroup *g = (tt__cgroup *)cg;
    if ((r = check_compliance(w, alpha, fn)) != TT_OK) return r;
    tt__cslot *s = &g->slots[c.index];
    if (s->kind == TT_CONSTRAINT_BOUNDS) return tt__fail(w, TT_ESTATE, "%s: bounds are always stiff", fn);
    if (s->kind == TT_CONSTRAINT_DISTANCE) {
        tt__dist *d = &g->dist[s->dense];
        g->nxpbd += (alpha > 0) - (d->alpha > 0);
        d->alpha = alpha;
        hot_sync(g, s->dense);
    } else {
        g->gen[s->dense].alpha = alpha;
    }
    return TT_OK;
}

static tt_result kind_check(const tt_world *w, tt_constraint c, uint8_t kind, const char *fn, const tt__cgroup **g)
{
    tt_result r = con_check(w, c, fn, g);
    if (r != TT_OK) return r;
    if ((*g)->slots[c.index].kind != kind) return tt__fail(w, TT_EINVAL, "%s: wrong kind of constraint", fn);
    return TT_OK;
}

tt_result tt_distance_set_length(tt_world *w, tt_constraint c, double length)
{
    const char *fn = "tt_distance_set_length";
    const tt__cgroup *cg;
    tt_result r = kind_check(w, c, TT_CONSTRAINT_DISTANCE, fn, &cg);
    if (r != TT_OK) return r;
    if (!tt__in_range(length, 0.0, TT_MAX_VALUE))
        return tt__fail(w, TT_EINVAL, "%s: length must be in [0, %g], got %g", fn, TT_MAX_VALUE, length);
    tt__cgroup *g = (tt__cgroup *)cg;
    uint32_t d = g->slots[c.index].dense;
    g->dx[d].rest = length;
    g->dist[d].lo = g->dx[d].mode == TT_DISTANCE_MAX ? 0.0 : length;
    g->dist[d].hi = g->dx[d].mode == TT_DISTANCE_MIN ? INFINITY : length;
    hot_sync(g, d);
    return TT_OK;
}

tt_result tt_distance_get_length(const tt_world *w, tt_constraint c, double *out)
{
    const char *fn = "tt_distance_get_length";
    const tt__cgroup *g;
    tt_result r = kind_check(w, c, TT_CONSTRAINT_DISTANCE, fn, &g);
    if (r != TT_OK) return r;
    if (!out) return tt__fail(w, TT_EINVAL, "%s: out is NULL", fn);
    *out = g->dx[g->slots[c.index].dense].rest;
    return TT_OK;
}

tt_result tt_pin_set_anchor(tt_world *w, tt_constraint c, tt_vec2 anchor)
{
    const char *fn = "tt_pin_set_anchor";
    const tt__cgroup *g;
    tt_result r = kind_check(w, c, TT_CONSTRAINT_PIN, fn, &g);
    if (r != TT_OK) return r;
    if (!tt__vec_ok(anchor)) return tt__fail(w, TT_EINVAL, "%s: anchor must be finite, |x| <= %g", fn, TT_MAX_VALUE);
    tt__gcon *p = &((tt__cgroup *)g)->gen[g->slots[c.index].dense];
    p->v[0] = anchor.x;
    p->v[1] = anchor.y;
    return TT_OK;
}

tt_result tt_pin_get_anchor(const tt_world *w, tt_constraint c, tt_vec2 *out)
{
    const char *fn = "tt_pin_get_anchor";
    const tt__cgroup *g;
    tt_result r = kind_check(w, c, TT_CONSTRAINT_PIN, fn, &g);
    if (r != TT_OK) return r;
    if (!out) return tt__fail(w, TT_EINVAL, "%s: out is NULL", fn);
    const tt__gcon *p = &g->gen[g->slots[c.index].dense];
    *out = (tt_vec2){p->v[0], p->v[1]};
    return TT_OK;
}

tt_result tt_bounds_set_box(tt_world *w, tt_constraint c, tt_vec2 lo, tt_vec2 hi)
{
    const char *fn = "tt_bounds_set_box";
    const tt__cgroup *g;
    tt_result r = kind_check(w, c, TT_CONSTRAINT_BOUNDS, fn, &g);
    if (r != TT_OK) return r;
    if ((r = check_box(w, lo, hi, fn)) != TT_OK) return r;
    tt__gcon *b = &((tt__cgroup *)g)->gen[g->slots[c.index].dense];
    b->v[0] = lo.x;
    b->v[1] = lo.y;
    b->v[2] = hi.x;
    b->v[3] = hi.y;
    return TT_OK;
}

uint32_t tt_world_constraint_count(const tt_world *w)
{
    const tt__cgroup *g = tt__cgroup_peek(w);
    return g ? g->alive : 0;
}

uint32_t tt_world_read_constraint_lines(const tt_world *w, double *xy, uint32_t cap)
{
    const tt__cgroup *g = tt__cgroup_peek(w);
    if (!g) return 0;
    uint32_t n = 0;
    for (uint32_t i = 0; i < g->ndist; i++, n++) {
        if (!xy || n >= cap) continue;
        const tt__dist *d = &g->dist[i];
        double *o = xy + 4 * (size_t)n;
        o[0] = w->px[d->a];
        o[1] = w->py[d->a];
        o[2] = w->px[d->b];
        o[3] = w->py[d->b];
    }
    for (uint32_t i = 0; i < g->ngen; i++) {
        const tt__gcon *c = &g->gen[i];
        if (c->kind != TT_CONSTRAINT_PIN) continue;
        if (xy && n < cap) {
            double *o = xy + 4 * (size_t)n;
            o[0] = w->px[c->p[0]];
            o[1] = w->py[c->p[0]];
            o[2] = c->v[0];
            o[3] = c->v[1];
        }
        n++;
    }
    return n;
}

tt_result tt_world_get_break_events(const tt_world *w, const tt_break_event **events, uint32_t *count)
{
    TT_CHECK_WORLD(w, "tt_world_get_break_events");
    if (!events || !count) return tt__fail(w, TT_EINVAL, "tt_world_get_break_events: NULL argument");
    const tt__cgroup *g = tt__cgroup_peek(w);
    *events = g ? g->ev_pub : NULL;
    *count = g ? g->npub : 0;
    return TT_OK;
}

/* ---- the relaxation group -------------------------------------------------- */

static void group_begin(tt_world *w, void *self, double h)
{
    (void)w;
    (void)h;
    tt__cgroup *g = self;
    if (g->nxpbd)
        for (uint32_t i = 0; i < g->ndist; i++) g->dx[i].lambda = 0.0;
    for (uint32_t i = 0; i < g->ngen; i++) g->gen[i].lambda = 0.0;
    g->first_sweep = true;
}

/* Part of a sweep over the distance constraints: links [i, n), err the
 * largest error so far. Particle k is at px[k·st], py[k·st], im[k·st] (st = 1:
 * the world's arrays; 4: the vector sweep's packed copy). `jacobi` and `st`
 * are constants at each call site, so each gets a lean loop. */
static inline __attribute__((always_inline)) double sweep_distance(tt_world *w, tt__cgroup *g, double h, bool jacobi,
                                                                   double *px, double *py, const double *im, size_t st,
                                                                   uint32_t i, uint32_t n, double err)
{
    const double inv_h2 = 1.0 / (h * h);
    const tt__dist *dist = g->dist;
    for (; i < n; i++) {
        const tt__dist *d = &dist[i];
        const uint32_t a = d->a, b = d->b;
        const size_t ia = a * st, ib = b * st;
        const double wa = im[ia], wb = im[ib], ws = wa + wb;
        if (ws == 0.0) continue;
        double dx = px[ib] - px[ia], dy = py[ib] - py[ia];
        double len = sqrt(dx * dx + dy * dy);
        double c = len < d->lo ? len - d->lo : len > d->hi ? len - d->hi : 0.0;
        if (c == 0.0) continue;
        double ac = fabs(c);
        if (ac > err) err = ac;
        if (len == 0.0) { /* one spot: no direction */
            /* Brought together by other constraints during the sweeps, they
             * get one from those; still together when the substep's sweeps
             * begin, they may never get one (two particles at rest), so b
             * parts to +x of a. */
            if (!g->first_sweep) continue;
            dx = 1.0;
            dy = 0.0;
            len = 1.0;
        }
        double s;
        if (d->alpha > 0.0) {
            double at = d->alpha * inv_h2, *lam = &g->dx[i].lambda;
            double dl = (-c - at * *lam) / (ws + at);
            *lam += dl;
            s = -dl / len;
        } else {
            s = d->k * c / (ws * len);
        }
        /* a moves toward b when stretched (c > 0), b toward a */
        double cx = s * dx, cy = s * dy;
        if (jacobi) {
            if (wa > 0.0) tt__correct(w, a, wa * cx, wa * cy);
            if (wb > 0.0) tt__correct(w, b, -wb * cx, -wb * cy);
        } else {
            px[ia] += wa * cx;
            py[ia] += wa * cy;
            px[ib] -= wb * cx;
            py[ib] -= wb * cy;
        }
    }
    return err;
}

/* ---- Gauss-Seidel in SIMD lanes -------------------------------------------
 * Consecutive links that share no particle commute, so a block of them solved
 * side by side gives the sequential loop's result bit for bit, as long as each
 * lane does the scalar arithmetic: the same IEEE operations in the same order
 * (these functions enable no FMA, and the build has -ffp-contract=off) with
 * every branch turned into a mask. The sweep works on a packed copy of x, y
 * and inverse mass (one 32-byte row per particle) so a particle is one load
 * and one store, and reads the links' hot fields from arrays (h_*) so a
 * block's parameters are one vector load each. Measured on a 128² cloth at 10
 * sweeps (Zen 4, make bench, median of 5): the scalar loop 6.2 ms a step,
 * this 1.97 ms. */

bool tt__constraints_set_simd(tt_world *w, tt__simd_mode mode)
{
    if (mode != TT__SIMD_AUTO && mode != TT__SIMD_SCALAR && tt__simd_kind((uint8_t)mode) == TT__SIMD_SCALAR) return false;
    tt__cgroup *g = tt__cgroup_get(w, true);
    if (!g) return false;
    g->simd = (uint8_t)mode;
    return true;
}

/* Room for the plan of n links over particles [0, np). */
static bool plan_reserve(tt__cgroup *g, uint32_t n, uint32_t np, uint32_t W)
{
    if (!grow((void **)&g->stamp, sizeof *g->stamp, &g->stamp_cap, np) ||
        !grow((void **)&g->plan, sizeof *g->plan, &g->plan_cap, 2 * (n / W + 1)))
        return false;
    if (!tt__rows_reserve(&g->pk, &g->pk_cap, np)) return false;
    if (n > g->hot_cap) { /* one block: four double arrays, then two uint32 ones */
        uint32_t cap = n > UINT32_MAX / 2 ? n : n + n / 2;
        double *h = malloc((size_t)cap * (4 * sizeof(double) + 2 * sizeof(uint32_t)));
        if (!h) return false;
        free(g->h_lo);
        g->h_lo = h;
        g->h_hi = h + cap;
        g->h_k = h + 2 * (size_t)cap;
        g->h_alpha = h + 3 * (size_t)cap;
        g->h_ra = (uint32_t *)(h + 4 * (size_t)cap);
        g->h_rb = g->h_ra + cap;
        g->hot_cap = cap;
    }
    return true;
}

/* In a plan's block count: the run's links are all rigid. */
#define PLAN_RIGID 0x80000000u

/* Greedy in one pass. A block gathers consecutive links until W share no
 * particle, and a run of blocks (one plan segment) goes on while each block
 * also shares none with the D − 1 before it, so a kernel may load a block
 * before it stores the previous ones. A link naming a particle of link k:
 * k in the block: the links up to k go to a scalar run, a new run starts
 * after k; k in an earlier block: a new run starts with this block. */
static bool plan_build(tt__cgroup *g, uint32_t W, uint32_t D)
{
    const uint32_t n = g->ndist;
    uint32_t np = 0;
    for (uint32_t i = 0; i < n; i++) {
        uint32_t m = g->dist[i].a > g->dist[i].b ? g->dist[i].a : g->dist[i].b;
        if (m >= np) np = m + 1;
    }
    if (!plan_reserve(g, n, np, W)) return false;
    /* stamp[p]: 1 + the last link naming p; done: links planned; r, s: first link of the run, of the block */
    uint32_t *stamp = g->stamp, *plan = g->plan, m = 0, done = 0, r = 0, s = 0;
    memset(stamp, 0, (size_t)np * sizeof *stamp);
    for (uint32_t j = 0; j < n; j++) {
        const tt__dist *d = &g->dist[j];
        const uint32_t a = d->a, b = d->b;
        g->h_lo[j] = d->lo;
        g->h_hi[j] = d->hi;
        g->h_k[j] = d->k;
        g->h_alpha[j] = d->alpha;
        g->h_ra[j] = 4 * a; /* indices < 2^30 (max_particles): no overflow */
        g->h_rb[j] = 4 * b;
        const uint32_t lim = s - r >= (D - 1) * W ? s - (D - 1) * W : r; /* j must share no particle with [lim, j) */
        uint32_t k1 = stamp[a] > stamp[b] ? stamp[a] : stamp[b];
        if (a == b) k1 = j + 1; /* never made, but then no lane may hold it */
        if (k1 > lim) r = k1 > s ? (s = k1) : s;
        stamp[a] = stamp[b] = j + 1;
        if (j + 1 - s < W) continue;
        uint32_t rigid = PLAN_RIGID; /* a run is all rigid links (lo = hi for good) or not */
        for (uint32_t q = s; q <= j; q++)
            if (g->dx[q].mode != TT_DISTANCE_RIGID) rigid = 0;
        if (s == done && r < s && m > 0 && (plan[m - 1] & PLAN_RIGID) == rigid) {
            plan[m - 1]++; /* the run goes on */
        } else {
            plan[m++] = s - done;
            plan[m++] = 1 | rigid;
        }
        done = s = j + 1;
    }
    if (done < n) {
        plan[m++] = n - done;
        plan[m++] = 0;
    }
    g->nplan = m;
    g->plan_w = W;
    g->plan_np = np;
    g->plan_ok = true;
    return true;
}

#ifdef TT_SIMD_X86
static double max_lanes(const double *e, int n)
{
    double r = 0.0;
    for (int j = 0; j < n; j++)
        if (e[j] > r) r = e[j];
    return r;
}

/* What a kernel reads: the rows, the hot arrays and the cold halves, all
 * from the run's first link on. */
typedef struct kern_in {
    double *pk;
    const double *lo, *hi, *k, *alpha;
    const uint32_t *ra, *rb;
    tt__dist_x *x;
    double inv_h2;
    bool apart; /* the substep's first sweep: links of length 0 part their particles */
} kern_in;

/* Four links a block, in "pair form": a ymm holds (x, y) of two particles,
 * those of links 0, 2 or of links 1, 3, and another their (w, w), from two
 * rows with two permutes; the lengths, c and s come out in link order with one
 * unpack, and go back to pairs with another (fewer shuffles than transposing
 * rows into x, y, w vectors). Two stages, software-pipelined: stage 1 of
 * block t (loads up to the sqrt) is issued before stage 2 of block t − 1 (the
 * rest, ending in the stores), which the plan allows by keeping adjacent
 * blocks apart, so the processor's window need not hold a block's whole
 * load → sqrt → division → store chain. On a 128² cloth: 3.0 ms a step with
 * transposed lanes in a plain loop (AVX2), 2.3 / 2.5 ms like this (AVX-512VL /
 * AVX2 builds; before rigid runs and rows kept across sweeps). */
typedef struct stage1 {
    __m256d pa02, pa13, pb02, pb13, wa02, wa13, wb02, wb13, d02, d13, len;
} stage1;

TT_AVX2 TT_INLINE void stage1_run(stage1 *o, const kern_in *in, uint32_t i)
{
    const double *pk = in->pk;
    const uint32_t *ra = in->ra + i, *rb = in->rb + i;
    tt__rows_load2(pk, ra[0], ra[2], &o->pa02, &o->wa02);
    tt__rows_load2(pk, ra[1], ra[3], &o->pa13, &o->wa13);
    tt__rows_load2(pk, rb[0], rb[2], &o->pb02, &o->wb02);
    tt__rows_load2(pk, rb[1], rb[3], &o->pb13, &o->wb13);
    o->d02 = _mm256_sub_pd(o->pb02, o->pa02); /* dx0 dy0 dx2 dy2 */
    o->d13 = _mm256_sub_pd(o->pb13, o->pa13);
    const __m256d q02 = _mm256_mul_pd(o->d02, o->d02), q13 = _mm256_mul_pd(o->d13, o->d13);
    /* unpacklo: dx² of links 0 1 2 3, unpackhi: dy²; then dx² + dy² as the scalar adds them */
    o->len = _mm256_sqrt_pd(_mm256_add_pd(_mm256_unpacklo_pd(q02, q13), _mm256_unpackhi_pd(q02, q13)));
}

TT_AVX2 TT_INLINE __m256d stage2_run(const stage1 *o, const kern_in *in, uint32_t i, __m256d err, bool xpbd, bool rigid)
{
    const __m256d zero = _mm256_setzero_pd(), sign = _mm256_set1_pd(-0.0);
    double *pk = in->pk;
    const uint32_t *ra = in->ra + i, *rb = in->rb + i;
    const __m256d wa02 = o->wa02, wa13 = o->wa13, wb02 = o->wb02, wb13 = o->wb13;
    const __m256d ws = _mm256_add_pd(_mm256_blend_pd(wa02, wa13, 0xA), _mm256_blend_pd(wb02, wb13, 0xA));
    /* c = min(len − lo, 0) + max(len − hi, 0) is the scalar's three cases bit
     * for bit: lo <= hi, so one term is +0, and min/max give the 0 for NaN.
     * Rigid (lo = hi): len − lo, NaN for NaN, which the ordered c != 0 below
     * turns off as the scalar's c = 0 would. */
    const __m256d c = rigid ? _mm256_sub_pd(o->len, _mm256_loadu_pd(in->lo + i))
                            : _mm256_add_pd(_mm256_min_pd(_mm256_sub_pd(o->len, _mm256_loadu_pd(in->lo + i)), zero),
                                            _mm256_max_pd(_mm256_sub_pd(o->len, _mm256_loadu_pd(in->hi + i)), zero));
    /* as the scalar loop skips: ws == 0, c == 0 (no error) */
    const __m256d act = _mm256_and_pd(_mm256_cmp_pd(ws, zero, _CMP_NEQ_UQ), _mm256_cmp_pd(c, zero, _CMP_NEQ_OQ));
    err = _mm256_max_pd(err, _mm256_and_pd(_mm256_andnot_pd(sign, c), act)); /* |c| of an active lane: >= 0, not NaN */
    __m256d len = o->len, d02 = o->d02, d13 = o->d13; /* the divisor and direction below */
    const __m256d one = _mm256_and_pd(act, _mm256_cmp_pd(len, zero, _CMP_EQ_OQ));
    if (TT_UNLIKELY(in->apart && _mm256_movemask_pd(one))) { /* the scalar's direction for two particles on one spot */
        const __m256d unit = _mm256_setr_pd(1.0, 0.0, 1.0, 0.0);
        len = _mm256_blendv_pd(len, _mm256_set1_pd(1.0), one);
        d02 = _mm256_blendv_pd(d02, unit, _mm256_unpacklo_pd(one, one));
        d13 = _mm256_blendv_pd(d13, unit, _mm256_unpackhi_pd(one, one));
    }
    /* length 0 left (not the first sweep): error, no move */
    const __m256d upd = _mm256_and_pd(act, _mm256_cmp_pd(len, zero, _CMP_NEQ_UQ));
    __m256d s = _mm256_div_pd(_mm256_mul_pd(_mm256_loadu_pd(in->k + i), c), _mm256_mul_pd(ws, len));
    if (xpbd) {
        const __m256d alpha = _mm256_loadu_pd(in->alpha + i);
        const __m256d xp = _mm256_and_pd(upd, _mm256_cmp_pd(alpha, zero, _CMP_GT_OQ));
        if (_mm256_movemask_pd(xp)) {
            tt__dist_x *x = in->x + i;
            __m256d lam = _mm256_set_pd(x[3].lambda, x[2].lambda, x[1].lambda, x[0].lambda);
            const __m256d at = _mm256_mul_pd(alpha, _mm256_set1_pd(in->inv_h2));
            const __m256d dl = _mm256_div_pd(_mm256_sub_pd(_mm256_xor_pd(c, sign), _mm256_mul_pd(at, lam)), _mm256_add_pd(ws, at));
            lam = _mm256_blendv_pd(lam, _mm256_add_pd(lam, dl), xp);
            const __m128d l01 = _mm256_castpd256_pd128(lam), l23 = _mm256_extractf128_pd(lam, 1);
            _mm_storel_pd(&x[0].lambda, l01);
            _mm_storeh_pd(&x[1].lambda, l01);
            _mm_storel_pd(&x[2].lambda, l23);
            _mm_storeh_pd(&x[3].lambda, l23);
            s = _mm256_blendv_pd(s, _mm256_div_pd(_mm256_xor_pd(dl, sign), len), xp); /* −v: the sign bit */
        }
    }
    /* back to pairs: (s·dx, s·dy) as the scalar's cx, cy; x + w·cx, as it adds */
    const __m256d c02 = _mm256_mul_pd(_mm256_unpacklo_pd(s, s), d02), c13 = _mm256_mul_pd(_mm256_unpackhi_pd(s, s), d13);
    __m256d na02 = _mm256_add_pd(o->pa02, _mm256_mul_pd(wa02, c02)), na13 = _mm256_add_pd(o->pa13, _mm256_mul_pd(wa13, c13));
    __m256d nb02 = _mm256_sub_pd(o->pb02, _mm256_mul_pd(wb02, c02)), nb13 = _mm256_sub_pd(o->pb13, _mm256_mul_pd(wb13, c13));
    if (_mm256_movemask_pd(upd) != 15) { /* a lane that must not move keeps its old value (old + 0 could turn −0 into +0) */
        const __m256d u02 = _mm256_unpacklo_pd(upd, upd), u13 = _mm256_unpackhi_pd(upd, upd);
        na02 = _mm256_blendv_pd(o->pa02, na02, u02);
        na13 = _mm256_blendv_pd(o->pa13, na13, u13);
        nb02 = _mm256_blendv_pd(o->pb02, nb02, u02);
        nb13 = _mm256_blendv_pd(o->pb13, nb13, u13);
    }
    tt__rows_store2(pk, ra[0], ra[2], na02);
    tt__rows_store2(pk, ra[1], ra[3], na13);
    tt__rows_store2(pk, rb[0], rb[2], nb02);
    tt__rows_store2(pk, rb[1], rb[3], nb13);
    return err;
}

/* A run of nb blocks, each apart from the one before; returns the largest error. */
TT_AVX2 TT_INLINE double run_pairs(const kern_in *in_, uint32_t nb, bool xpbd, bool rigid)
{
    const kern_in local = *in_, *in = &local; /* fields stay in registers: no store can reach them */
    __m256d err = _mm256_setzero_pd();
    stage1 A, B; /* unrolled by two so both stay in registers */
    stage1_run(&A, in, 0);
    uint32_t t = 1;
    for (; t + 1 < nb; t += 2) {
        stage1_run(&B, in, 4 * t);
        err = stage2_run(&A, in, 4 * t - 4, err, xpbd, rigid);
        stage1_run(&A, in, 4 * t + 4);
        err = stage2_run(&B, in, 4 * t, err, xpbd, rigid);
    }
    if (t < nb) {
        stage1_run(&B, in, 4 * t);
        err = stage2_run(&A, in, 4 * t - 4, err, xpbd, rigid);
        err = stage2_run(&B, in, 4 * t, err, xpbd, rigid);
    } else {
        err = stage2_run(&A, in, 4 * t - 4, err, xpbd, rigid);
    }
    double e[4];
    _mm256_storeu_pd(e, err);
    return max_lanes(e, 4);
}

/* The same code for AVX2, and with AVX-512VL for its 32 registers (fewer
 * spills); each with and without the XPBD branch, for rigid runs or not. */
typedef double (*run_fn)(const kern_in *, uint32_t);
#define TT_RUNS(T, name)                                                                             \
    T static double name##_gg(const kern_in *in, uint32_t nb) { return run_pairs(in, nb, false, false); } \
    T static double name##_gr(const kern_in *in, uint32_t nb) { return run_pairs(in, nb, false, true); }  \
    T static double name##_xg(const kern_in *in, uint32_t nb) { return run_pairs(in, nb, true, false); }  \
    T static double name##_xr(const kern_in *in, uint32_t nb) { return run_pairs(in, nb, true, true); }
TT_RUNS(TT_AVX2, run_avx2)
TT_RUNS(TT_AVX512, run_avx512)
#undef TT_RUNS
static const run_fn runs_avx2[4] = {run_avx2_gg, run_avx2_gr, run_avx2_xg, run_avx2_xr};
static const run_fn runs_avx512[4] = {run_avx512_gg, run_avx512_gr, run_avx512_xg, run_avx512_xr};

/* The plan's scalar runs (on the rows, through the scalar loop itself) and
 * vector runs; runs[2·xpbd + rigid]. The rows are made from w->px, py and
 * inv_mass unless they already hold the positions (pk_live), and written back
 * unless `keep`: the solver sweeps nothing else between these sweeps, so they
 * stay live until sweeps_done (saves ~8 % of a 128² cloth step). */
TT_AVX2 static double sweep_planned(tt_world *w, tt__cgroup *g, double h, const run_fn *runs, bool keep)
{
    double *pk = g->pk;
    if (!g->pk_live) tt__rows_pack(pk, w->px, w->py, w->inv_mass, g->plan_np);
    const int xpbd = g->nxpbd > 0; /* else no lane has alpha > 0: the kernels without that branch */
    double err = 0.0;
    uint32_t i = 0;
    for (uint32_t k = 0; k < g->nplan; k += 2) {
        const uint32_t ns = g->plan[k], nb = g->plan[k + 1] & ~PLAN_RIGID;
        err = sweep_distance(w, g, h, false, pk, pk + 1, pk + 2, 4, i, i + ns, err);
        i += ns;
        if (!nb) continue;
        const kern_in in = {pk, g->h_lo + i, g->h_hi + i, g->h_k + i, g->h_alpha + i, g->h_ra + i, g->h_rb + i,
                            g->dx + i, 1.0 / (h * h), g->first_sweep};
        double e = runs[2 * xpbd + (g->plan[k + 1] >= PLAN_RIGID)](&in, nb);
        if (e > err) err = e; /* a max: the order it is taken in does not matter */
        i += 4 * nb;
    }
    g->pk_live = keep;
    if (!keep) tt__rows_unpack(pk, w->px, w->py, g->plan_np);
    return err;
}
#endif

/* The rows back into w->px, py if they hold the positions. */
static void rows_release(tt_world *w, tt__cgroup *g)
{
#ifdef TT_SIMD_X86
    if (g->pk_live) tt__rows_unpack(g->pk, w->px, w->py, g->plan_np);
#else
    (void)w;
#endif
    g->pk_live = false;
}

static void group_sweeps_done(tt_world *w, void *self) { rows_release(w, self); }

static double sweep_distance_gs(tt_world *w, tt__cgroup *g, double h)
{
    uint8_t kind = tt__simd_kind(g->simd);
    if (kind != TT__SIMD_SCALAR && g->ndist >= 8 && !(g->plan_ok && g->plan_w == 4)) {
        rows_release(w, g); /* a new plan may move the rows */
        if (!plan_build(g, 4, 2)) kind = TT__SIMD_SCALAR;
    }
    if (kind == TT__SIMD_SCALAR || g->ndist < 8) {
        rows_release(w, g);
        return sweep_distance(w, g, h, false, w->px, w->py, w->inv_mass, 1, 0, g->ndist, 0.0);
    }
#ifdef TT_SIMD_X86
    /* keep the rows only while this sweep is all the solver does to positions */
    const bool keep = g->ngen == 0 && w->group_count == 1;
    return sweep_planned(w, g, h, kind == TT__SIMD_AVX512 ? runs_avx512 : runs_avx2, keep);
#else
    return 0.0;
#endif
}

static double sweep_distance_jacobi(tt_world *w, tt__cgroup *g, double h)
{
    return sweep_distance(w, g, h, true, w->px, w->py, w->inv_mass, 1, 0, g->ndist, 0.0);
}

/* PBD / XPBD step of a scalar constraint C with gradients grad[2k] over particles idx[k]. */
static void solve_scalar(tt_world *w, tt__gcon *c, const uint32_t *idx, uint32_t n, const double *grad, double C, double h)
{
    double denom = 0.0;
    for (uint32_t k = 0; k < n; k++)
        denom += w->inv_mass[idx[k]] * (grad[2 * k] * grad[2 * k] + grad[2 * k + 1] * grad[2 * k + 1]);
    if (!(denom > 1e-300)) return;
    double dl;
    if (c->alpha > 0.0) {
        double at = c->alpha / (h * h);
        dl = (-C - at * c->lambda) / (denom + at);
        c->lambda += dl;
    } else {
        dl = -c->k * C / denom;
    }
    for (uint32_t k = 0; k < n; k++) {
        double m = w->inv_mass[idx[k]];
        if (m > 0.0) tt__correct(w, idx[k], m * grad[2 * k] * dl, m * grad[2 * k + 1] * dl);
    }
}

static double relax_pin(tt_world *w, tt__gcon *c, double h)
{
    uint32_t i = c->p[0];
    double dx = w->px[i] - c->v[0], dy = w->py[i] - c->v[1], len = sqrt(dx * dx + dy * dy);
    if (len == 0.0) return 0.0;
    double g[2] = {dx / len, dy / len};
    if (w->inv_mass[i] > 0.0) solve_scalar(w, c, &i, 1, g, len, h);
    return len;
}

static double relax_bounds_one(tt_world *w, const tt__gcon *c, uint32_t i)
{
    if (w->inv_mass[i] == 0.0) return 0.0;
    double dx, dy, e = bounds_violation(w, c, i, &dx, &dy);
    if (e > 0.0) tt__correct(w, i, dx, dy);
    return e;
}

static double relax_bounds(tt_world *w, const tt__gcon *c)
{
    double e = 0.0;
    if (c->n) {
        for (uint32_t k = 0; k < c->n; k++) e = fmax(e, relax_bounds_one(w, c, c->list[k]));
    } else {
        for (uint32_t i = 0; i < w->ppool.count; i++) e = fmax(e, relax_bounds_one(w, c, i));
    }
    return e;
}

static double relax_angle(tt_world *w, tt__gcon *c, double h)
{
    uint32_t a = c->p[0], b = c->p[1], cc = c->p[2];
    double ux = w->px[a] - w->px[b], uy = w->py[a] - w->py[b];
    double vx = w->px[cc] - w->px[b], vy = w->py[cc] - w->py[b];
    double uu = ux * ux + uy * uy, vv = vx * vx + vy * vy;
    if (uu == 0.0 || vv == 0.0) return 0.0;
    double C = angle_error(atan2(ux * vy - uy * vx, ux * vx + uy * vy), c->v[0], c->v[1]);
    if (C == 0.0) return 0.0;
    /* θ = φ(v) − φ(u): ∂θ/∂a = (u_y, −u_x)/|u|², ∂θ/∂c = (−v_y, v_x)/|v|², ∂θ/∂b = −(both) */
    double ga[2] = {uy / uu, -ux / uu}, gc[2] = {-vy / vv, vx / vv};
    double grad[6] = {ga[0], ga[1], -ga[0] - gc[0], -ga[1] - gc[1], gc[0], gc[1]};
    solve_scalar(w, c, c->p, 3, grad, C, h);
    return fabs(C) * sqrt(fmax(uu, vv)); /* as an arc length, m */
}

static double relax_area(tt_world *w, tt__cgroup *g, tt__gcon *c, double h)
{
    const uint32_t n = c->n, *p = c->list;
    double *grad = g->grad, perim = 0.0;
    for (uint32_t k = 0; k < n; k++) {
        uint32_t prev = p[k == 0 ? n - 1 : k - 1], next = p[k + 1 == n ? 0 : k + 1];
        grad[2 * k] = 0.5 * (w->py[next] - w->py[prev]);
        grad[2 * k + 1] = 0.5 * (w->px[prev] - w->px[next]);
        perim += dist_of(w, p[k], next);
    }
    double C = polygon_area(w, p, n) - c->v[0] * c->v[1];
    if (C == 0.0) return 0.0;
    solve_scalar(w, c, p, n, grad, C, h);
    return perim > 0.0 ? fabs(C) / perim : fabs(C); /* the mean normal move that fixes it, m */
}

static double relax_collinear(tt_world *w, tt__gcon *c, double h)
{
    uint32_t a = c->p[0], b = c->p[1], cc = c->p[2];
    double d1x = w->px[b] - w->px[a], d1y = w->py[b] - w->py[a];
    double d2x = w->px[cc] - w->px[a], d2y = w->py[cc] - w->py[a];
    double C = d1x * d2y - d1y * d2x, L = sqrt(d2x * d2x + d2y * d2y);
    if (C == 0.0) return 0.0;
    double gb[2] = {d2y, -d2x}, gcc[2] = {-d1y, d1x};
    double grad[6] = {-gb[0] - gcc[0], -gb[1] - gcc[1], gb[0], gb[1], gcc[0], gcc[1]};
    solve_scalar(w, c, c->p, 3, grad, C, h);
    return L > 0.0 ? fabs(C) / L : fabs(C);
}

static double group_relax(tt_world *w, void *self, double h)
{
    tt__cgroup *g = self;
    bool jacobi = w->jn && w->order == TT_JACOBI;
    double err = jacobi ? sweep_distance_jacobi(w, g, h) : sweep_distance_gs(w, g, h);
    g->first_sweep = false;
    for (uint32_t i = 0; i < g->ngen; i++) {
        tt__gcon *c = &g->gen[i];
        double e = 0.0;
        switch (c->kind) {
        case TT_CONSTRAINT_PIN: e = relax_pin(w, c, h); break;
        case TT_CONSTRAINT_BOUNDS: e = relax_bounds(w, c); break;
        case TT_CONSTRAINT_ANGLE: e = relax_angle(w, c, h); break;
        case TT_CONSTRAINT_AREA: e = relax_area(w, g, c, h); break;
        case TT_CONSTRAINT_COLLINEAR: e = relax_collinear(w, c, h); break;
        }
        if (e > err) err = e;
    }
    return err;
}

/* Friction of one particle touching a bounds wall: the tangential part of its
 * velocity (Verlet: of x − x_old) shrinks by the friction fraction. */
static void bounds_friction(tt_world *w, const tt__gcon *c, uint32_t i)
{
    if (w->inv_mass[i] == 0.0) return;
    const double eps = 1e-9 * (1.0 + fabs(w->px[i]) + fabs(w->py[i]));
    double r = w->radius[i], x = w->px[i], y = w->py[i];
    bool on_x, on_y; /* touching a wall normal to x (so sliding along y), or normal to y */
    if (!c->outside) {
        on_x = x <= c->v[0] + r + eps || x >= c->v[2] - r - eps;
        on_y = y <= c->v[1] + r + eps || y >= c->v[3] - r - eps;
    } else {
        bool in_x = x >= c->v[0] - r - eps && x <= c->v[2] + r + eps;
        bool in_y = y >= c->v[1] - r - eps && y <= c->v[3] + r + eps;
        if (!in_x || !in_y) return;
        on_x = fabs(x - (c->v[0] - r)) <= eps || fabs(x - (c->v[2] + r)) <= eps;
        on_y = fabs(y - (c->v[1] - r)) <= eps || fabs(y - (c->v[3] + r)) <= eps;
    }
    double keep = 1.0 - c->friction;
    bool verlet = w->integrator == TT_VERLET;
    if (on_y) { /* sliding along x */
        if (verlet) w->qx[i] = x - (x - w->qx[i]) * keep;
        else w->qx[i] *= keep;
    }
    if (on_x) {
        if (verlet) w->qy[i] = y - (y - w->qy[i]) * keep;
        else w->qy[i] *= keep;
    }
}

static bool event_push(tt__cgroup *g, tt_break_event e)
{
    if (!grow((void **)&g->ev_new, sizeof *g->ev_new, &g->cap_new, g->nnew + 1)) return false;
    g->ev_new[g->nnew++] = e;
    return true;
}

static void group_end(tt_world *w, void *self, double h)
{
    (void)h;
    tt__cgroup *g = self;
    for (uint32_t i = 0; i < g->ngen; i++) {
        const tt__gcon *c = &g->gen[i];
        if (c->kind != TT_CONSTRAINT_BOUNDS || c->friction == 0.0) continue;
        if (c->n) {
            for (uint32_t k = 0; k < c->n; k++) bounds_friction(w, c, c->list[k]);
        } else {
            for (uint32_t p = 0; p < w->ppool.count; p++) bounds_friction(w, c, p);
        }
    }
    if (!g->nbreakable) return;
    /* Backwards, so the element swapped into a removed place was already checked. */
    for (uint32_t i = g->ndist; i-- > 0;) {
        const tt__dist *d = &g->dist[i];
        const tt__dist_x *x = &g->dx[i];
        if (x->break_strain <= 0.0) continue;
        double len = dist_of(w, d->a, d->b), rest = x->mode == TT_DISTANCE_MIN ? d->lo : d->hi;
        if (!(len > rest * (1.0 + x->break_strain))) continue;
        tt_break_event e = {handle_of(g, x->slot), particle_of(w, d->a), particle_of(w, d->b), len,
                            rest > 0.0 ? len / rest - 1.0 : TT_MAX_VALUE};
        event_push(g, e); /* no memory: the constraint still breaks, the event is lost */
        dist_remove(g, i);
    }
}

static void group_after_step(tt_world *w, void *self)
{
    (void)w;
    tt__cgroup *g = self;
    /* publish: the gathered list becomes the readable one, the old one is reused */
    tt_break_event *e = g->ev_pub;
    uint32_t cap = g->cap_pub;
    g->ev_pub = g->ev_new;
    g->cap_pub = g->cap_new;
    g->npub = g->nnew;
    g->ev_new = e;
    g->cap_new = cap;
    g->nnew = 0;
}

static void group_particle_removed(tt_world *w, void *self, uint32_t index)
{
    (void)w;
    tt__cgroup *g = self;
    if (index >= g->refs_cap || g->refs[index] == 0) return; /* named by no constraint: nothing to scan */
    for (uint32_t i = g->ndist; i-- > 0;)
        if (g->dist[i].a == index || g->dist[i].b == index) dist_remove(g, i);
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

static uint64_t group_hash(const tt_world *w, const void *self, uint64_t h)
{
    (void)w;
    const tt__cgroup *g = self;
    h = tt__fnv(h, &g->ndist, sizeof g->ndist);
    for (uint32_t i = 0; i < g->ndist; i++) {
        h = tt__fnv(h, &g->dist[i], sizeof g->dist[i]);
        h = tt__fnv(h, &g->dx[i].slot, sizeof(uint32_t));
        h = tt__fnv(h, &g->dx[i].break_strain, sizeof(double));
        h = tt__fnv(h, &g->dx[i].collide, sizeof(bool));
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
    }
    return tt__composites_hash(g, h);
}

static size_t group_memory(const tt_world *w, const void *self)
{
    (void)w;
    const tt__cgroup *g = self;
    size_t b = sizeof *g + tt_pool_bytes(&g->pool) + (size_t)g->slot_cap * sizeof(tt__cslot);
    b += (size_t)g->dist_cap * sizeof(tt__dist) + (size_t)g->dx_cap * sizeof(tt__dist_x);
    b += (size_t)g->gen_cap * sizeof(tt__gcon);
    for (uint32_t i = 0; i < g->ngen; i++)
        if (g->gen[i].list) b += (size_t)g->gen[i].n * sizeof(uint32_t);
    b += (size_t)g->pair_cap * (sizeof(uint64_t) + sizeof(uint32_t));
    b += (size_t)(g->cap_new + g->cap_pub) * sizeof(tt_break_event);
    b += (size_t)g->grad_cap * 2 * sizeof(double) + (size_t)g->refs_cap * sizeof(uint32_t);
    b += ((size_t)g->plan_cap + g->stamp_cap) * sizeof(uint32_t) + (size_t)g->pk_cap * 4 * sizeof(double);
    b += (size_t)g->hot_cap * (4 * sizeof(double) + 2 * sizeof(uint32_t));
    return b + tt__composites_memory(g);
}

static void group_destroy(tt_world *w, void *self)
{
    (void)w;
    tt__cgroup *g = self;
    for (uint32_t i = 0; i < g->ngen; i++) free(g->gen[i].list);
    free(g->gen);
    free(g->dist);
    free(g->dx);
    free(g->slots);
    free(g->pair_key);
    free(g->pair_n);
    free(g->ev_new);
    free(g->ev_pub);
    free(g->grad);
    free(g->refs);
    free(g->plan);
    free(g->stamp);
    free(g->pk);
    free(g->h_lo);
    tt_pool_destroy(&g->pool);
    tt__composites_free(g);
    free(g);
}
