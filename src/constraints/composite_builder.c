/* tether — the builder every composite is made with (the contract is with
 * tt__builder in constraint_internal.h): it places the particles, checks
 * them, makes them and then the constraints, and on any failure leaves the
 * world as it found it. */
#include "constraint_internal.h"

#include <stdlib.h>
#include <string.h>

#define NONE ((tt_composite){0, 0})

static void release(tt__builder *b)
{
    free(b->spots);
    free(b->c.parts);
    free(b->c.cons);
    free(b->c.rest);
}

/* The builder's own memory; the world is not touched yet. */
bool tt__builder_begin(tt__builder *b, tt_world *w, const tt_composite_common *k, uint32_t particles, const char *fn)
{
    memset(b, 0, sizeof *b);
    b->w = w;
    b->fn = fn;
    b->k = *k;
    b->spots = malloc((size_t)particles * sizeof *b->spots);
    b->c.parts = malloc((size_t)particles * sizeof *b->c.parts);
    b->c.rest = malloc((size_t)particles * 2 * sizeof(double));
    if (!b->spots || !b->c.parts || !b->c.rest) {
        release(b);
        tt__fail(w, TT_ENOMEM, "%s: out of memory", fn);
        return false;
    }
    return true;
}

void tt__builder_place(tt__builder *b, double x, double y, bool pinned)
{
    b->spots[b->nspots++] = (tt__spot){{x, y}, pinned};
}

/* Undoes everything made since spawn began changing the world. */
static void undo(tt__builder *b)
{
    tt_world *w = b->w;
    for (uint32_t i = 0; i < b->c.nc; i++)
        if (tt_constraint_is_valid(w, b->c.cons[i])) tt_constraint_destroy(w, b->c.cons[i]);
    for (uint32_t i = 0; i < b->c.np; i++) tt_particle_destroy(w, b->c.parts[i]);
    /* removal bumped generations and reordered free lists: put both back */
    tt__cgroup *g = tt__cgroup_find(w);
    if (g) {
        for (uint32_t i = 0; i < b->c.nc; i++) tt__pool_unalloc(&g->pool, b->cmark, i, b->c.cons[i].index, b->c.cons[i].gen);
        tt__pool_rewind(&g->pool, b->cmark);
    }
    for (uint32_t i = 0; i < b->c.np; i++) tt__pool_unalloc(&w->ppool, b->pmark, i, b->c.parts[i].index, b->c.parts[i].gen);
    tt__pool_rewind(&w->ppool, b->pmark);
    w->fresh_count = b->fresh_count;
    w->epoch = b->epoch; /* the particles are as they were, so is what was computed from them */
    tt__cgroup_unmake(w, b->had_group);
    release(b);
}

/* Room for the composite's record, made before anything else so it cannot fail last. */
static bool reserve_record(tt__cgroup *g)
{
    uint32_t need = g->cpool.free_count ? g->cpool.count : g->cpool.count + 1;
    if (need <= g->comp_cap) return true;
    uint32_t cap = g->comp_cap ? g->comp_cap * 2 : 16;
    tt__composite *q = realloc(g->comps, (size_t)cap * sizeof *q);
    if (!q) return false;
    g->comps = q;
    g->comp_cap = cap;
    return true;
}

/* Checks every placed particle, then makes them all; false (and nothing left
 * behind) when one is out of range, they do not fit, or memory runs out. */
bool tt__builder_spawn(tt__builder *b)
{
    tt_world *w = b->w;
    for (uint32_t i = 0; i < b->nspots; i++)
        if (!tt__vec_ok(b->spots[i].at)) {
            tt__fail(w, TT_EINVAL, "%s: particle %u would be at (%.17g, %.17g), past the largest coordinate %g", b->fn, i,
                     b->spots[i].at.x, b->spots[i].at.y, TT_MAX_VALUE);
            release(b);
            return false;
        } else if (tt__fixed_check(w, b->spots[i].at, b->fn) != TT_OK) {
            release(b);
            return false;
        }
    if (b->nspots > tt__particle_room(w)) {
        tt__fail(w, TT_ENOMEM, "%s: the world is full (max_particles %u)", b->fn, w->max_particles);
        release(b);
        return false;
    }
    b->pmark = tt__pool_mark_now(&w->ppool);
    b->fresh_count = w->fresh_count;
    b->epoch = w->epoch;
    b->had_group = tt__cgroup_peek(w) != NULL;
    tt__cgroup *g = tt__cgroup_make(w); /* made here, it starts empty: a mark like any other */
    if (g) b->cmark = tt__pool_mark_now(&g->pool);
    if (!g || !reserve_record(g)) {
        tt__fail(w, TT_ENOMEM, "%s: out of memory", b->fn);
        undo(b);
        return false;
    }
    tt_particle_def pd = tt_particle_def_default();
    pd.mass = b->k.mass;
    pd.radius = b->k.radius;
    for (uint32_t i = 0; i < b->nspots; i++) {
        pd.position = b->spots[i].at;
        pd.pinned = b->spots[i].pinned;
        tt_particle p = tt_particle_create(w, &pd);
        if (p.gen == 0) { /* out of memory: tt_particle_create said so */
            undo(b);
            return false;
        }
        b->c.parts[b->c.np++] = p;
    }
    return true;
}

/* Room for one more constraint handle, made before the constraint so every
 * constraint made is on the list undo walks. */
bool tt__builder_con_room(tt__builder *b)
{
    if (b->failed) return false;
    if (b->c.nc < b->c.ccap) return true;
    uint32_t cap = b->c.ccap ? b->c.ccap * 2 : 32;
    tt_constraint *q = realloc(b->c.cons, (size_t)cap * sizeof *q);
    if (!q) {
        tt__fail(b->w, TT_ENOMEM, "%s: out of memory", b->fn);
        b->failed = true;
        return false;
    }
    b->c.cons = q;
    b->c.ccap = cap;
    return true;
}

void tt__builder_add_constraint(tt__builder *b, tt_constraint h)
{
    if (h.gen == 0) b->failed = true; /* out of memory: the create call said so */
    else b->c.cons[b->c.nc++] = h;
}

/* A distance link between builder particles i and j. */
void tt__builder_link(tt__builder *b, uint32_t i, uint32_t j, double stiffness, tt_distance_mode mode, double break_strain)
{
    if (!tt__builder_con_room(b)) return;
    tt_distance_def d = tt_distance_def_default();
    d.a = b->c.parts[i];
    d.b = b->c.parts[j];
    d.mode = mode;
    d.stiffness = stiffness;
    d.compliance = b->k.compliance;
    d.collide = b->k.collide;
    d.break_strain = break_strain;
    tt__builder_add_constraint(b, tt_distance_create(b->w, &d));
}

void tt__builder_limit(tt__builder *b, uint32_t i, uint32_t j, uint32_t k, double lo, double hi, double stiffness)
{
    if (!tt__builder_con_room(b)) return;
    tt_angle_def d = tt_angle_def_default();
    d.a = b->c.parts[i];
    d.b = b->c.parts[j];
    d.c = b->c.parts[k];
    d.use_current = false;
    d.min = lo;
    d.max = hi;
    d.stiffness = stiffness;
    tt__builder_add_constraint(b, tt_angle_create(b->w, &d));
}

/* Stores the composite (or undoes everything when a step failed). */
tt_composite tt__builder_finish(tt__builder *b)
{
    tt_world *w = b->w;
    tt__cgroup *g = tt__cgroup_find(w);
    bool grew;
    uint32_t s = b->failed ? UINT32_MAX : tt__pool_alloc(&g->cpool, UINT32_MAX - 1, &grew);
    if (s == UINT32_MAX) {
        if (!b->failed) tt__fail(w, TT_ENOMEM, "%s: out of memory", b->fn);
        undo(b);
        return NONE;
    }
    /* rest shape: offsets from the centre of mass as made */
    double m = 0, cx = 0, cy = 0;
    for (uint32_t i = 0; i < b->c.np; i++) {
        uint32_t p = b->c.parts[i].index;
        m += w->mass[p];
        cx += w->mass[p] * w->px[p];
        cy += w->mass[p] * w->py[p];
    }
    cx /= m;
    cy /= m;
    for (uint32_t i = 0; i < b->c.np; i++) {
        uint32_t p = b->c.parts[i].index;
        b->c.rest[2 * i] = w->px[p] - cx;
        b->c.rest[2 * i + 1] = w->py[p] - cy;
    }
    free(b->spots);
    b->c.alive = true;
    g->comps[s] = b->c;
    g->comps_alive++;
    return (tt_composite){s, g->cpool.gen[s]};
}
