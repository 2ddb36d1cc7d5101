/* tether — making constraints: the defs' defaults, the checks the creating
 * calls (and the setters of constraint_access.c) share, and one creating
 * call per kind. Every check runs before the world changes, and a call that
 * runs out of memory takes back what it made. */
#include "constraint_internal.h"

#include <stdlib.h>
#include <string.h>

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
tt_result tt__constraint_check_compliance(const tt_world *w, double alpha, const char *fn)
{
    if (alpha == 0.0 || tt__in_range(alpha, TT_MIN_COMPLIANCE, TT_MAX_VALUE)) return TT_OK;
    return tt__fail(w, TT_EINVAL, "%s: compliance must be 0 (rigid) or in [%g, %g] m/N, got %g", fn, TT_MIN_COMPLIANCE,
                    TT_MAX_VALUE, alpha);
}

static tt_result check_soft(const tt_world *w, double k, double alpha, const char *fn)
{
    if (!tt__in_range(k, 0.0, 1.0)) return tt__fail(w, TT_EINVAL, "%s: stiffness must be in [0, 1], got %g", fn, k);
    return tt__constraint_check_compliance(w, alpha, fn);
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
    if (tt__constraint_check_rate(w, d->max_rate, fn) != TT_OK) return NONE;
    const bool had = tt__cgroup_peek(w) != NULL; /* a group made here goes again if this fails */
    tt__cgroup *g = tt__cgroup_make(w);
    if (!g || !tt__cgroup_refs_reserve(w, g) ||
        !tt__grow((void **)&g->dist, &g->dist_cap, g->ndist + 1, sizeof *g->dist) ||
        !tt__grow((void **)&g->dx, &g->dx_cap, g->ndist + 1, sizeof *g->dx))
        goto nomem;
    if (!d->collide && !tt__pair_set_add(&g->pairs, d->a.index, d->b.index)) goto nomem;
    uint32_t slot;
    if (!tt__cgroup_slot_new(g, TT_CONSTRAINT_DISTANCE, g->ndist, &slot)) {
        if (!d->collide) tt__pair_set_remove(&g->pairs, d->a.index, d->b.index);
        goto nomem;
    }
    double len = d->length < 0 ? tt__constraint_dist_of(w, d->a.index, d->b.index) : d->length;
    tt__dist *c = &g->dist[g->ndist];
    c->a = d->a.index;
    c->b = d->b.index;
    c->lo = d->mode == TT_DISTANCE_MAX ? 0.0 : len;
    c->hi = d->mode == TT_DISTANCE_MIN ? INFINITY : len;
    c->k = d->stiffness;
    c->alpha = d->compliance;
    g->dx[g->ndist] = (tt__dist_x){0.0, len, d->break_strain, slot, (uint8_t)d->mode, d->collide};
    g->slots[slot].max_rate = d->max_rate;
    g->ndist++;
    g->scr.plan_ok = false;
    g->refs[c->a]++;
    g->refs[c->b]++;
    tt__sleep_touch(w, c->a); /* a new link changes what rests */
    tt__sleep_touch(w, c->b);
    if (d->break_strain > 0) g->nbreakable++;
    if (d->compliance > 0) g->nxpbd++;
    return tt__cgroup_handle(g, slot);
nomem:
    tt__cgroup_unmake(w, had);
    tt__fail(w, TT_ENOMEM, "%s: out of memory", fn);
    return NONE;
}

/* A generic constraint's record, reserved; NULL on no memory. */
static tt__gcon *gen_new(tt_world *w, uint8_t kind, tt_constraint *h, const char *fn)
{
    const bool had = tt__cgroup_peek(w) != NULL;
    tt__cgroup *g = tt__cgroup_make(w);
    uint32_t slot;
    if (!g || !tt__cgroup_refs_reserve(w, g) ||
        !tt__grow((void **)&g->gen, &g->gen_cap, g->ngen + 1, sizeof *g->gen) ||
        !tt__cgroup_slot_new(g, kind, g->ngen, &slot)) {
        tt__cgroup_unmake(w, had);
        tt__fail(w, TT_ENOMEM, "%s: out of memory", fn);
        return NULL;
    }
    tt__gcon *c = &g->gen[g->ngen++];
    memset(c, 0, sizeof *c);
    c->kind = kind;
    c->slot = slot;
    *h = tt__cgroup_handle(g, slot);
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
    if (tt__constraint_check_rate(w, d->max_rate, fn) != TT_OK) return NONE;
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
    tt__cgroup *g = tt__cgroup_find(w);
    g->slots[c->slot].max_rate = d->max_rate;
    tt__cgroup_gen_refs(g, c, +1);
    return h;
}

tt_result tt__constraint_check_rate(const tt_world *w, double rate, const char *fn)
{
    if (!tt__in_range(rate, 0.0, TT_MAX_VALUE))
        return tt__fail(w, TT_EINVAL, "%s: max_rate must be in [0, %g] m/s (0 = no limit), got %g", fn, TT_MAX_VALUE, rate);
    return TT_OK;
}

tt_result tt__constraint_check_box(const tt_world *w, tt_vec2 lo, tt_vec2 hi, const char *fn)
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
    if (tt__constraint_check_box(w, d->min, d->max, fn) != TT_OK) return NONE;
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
    tt__cgroup_gen_refs(tt__cgroup_find(w), c, +1);
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
    double th = tt__constraint_angle_at(w, c->p[0], c->p[1], c->p[2]);
    c->v[0] = d->use_current ? th : d->min;
    c->v[1] = d->use_current ? th : d->max;
    tt__cgroup_gen_refs(tt__cgroup_find(w), c, +1);
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
    tt__cgroup *g = tt__cgroup_make(w);
    if (!g || !tt__grow((void **)&g->scr.grad, &g->scr.grad_cap, d->count, 2 * sizeof(double))) {
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
    c->v[0] = d->use_current ? tt__constraint_polygon_area(&(tt__lay){w->px, w->py, w->inv_mass, 1}, list, d->count) : d->area;
    c->v[1] = d->pressure;
    tt__cgroup_gen_refs(tt__cgroup_find(w), c, +1);
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
    tt__cgroup_gen_refs(tt__cgroup_find(w), c, +1);
    return h;
}
