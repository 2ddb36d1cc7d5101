/* tether — one constraint through its handle: destroy, kind, error,
 * particles, stiffness and compliance, and each kind's own settings; and the
 * reads over all of them (count, the lines a renderer draws, the energy). */
#include "constraint_internal.h"

/* ---- handles ------------------------------------------------------------- */

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

/* ---- per-constraint reads and writes ---------------------------------------- */

tt_result tt_constraint_destroy(tt_world *w, tt_constraint c)
{
    const tt__cgroup *g;
    tt_result r = con_check(w, c, "tt_constraint_destroy", &g);
    if (r != TT_OK) return r;
    tt__cgroup_slot_remove((tt__cgroup *)g, c.index);
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

static double gen_error(const tt_world *w, const tt__gcon *c)
{
    switch (c->kind) {
    case TT_CONSTRAINT_PIN: return hypot(w->px[c->p[0]] - c->v[0], w->py[c->p[0]] - c->v[1]);
    case TT_CONSTRAINT_BOUNDS: {
        double e = 0.0, dx, dy;
        if (c->n) {
            for (uint32_t k = 0; k < c->n; k++) {
                const uint32_t i = c->list[k];
                e = fmax(e, tt__constraint_bounds_violation(w, c, i, w->px[i], w->py[i], &dx, &dy));
            }
        } else {
            for (uint32_t i = 0; i < w->ppool.count; i++)
                if (w->flags[i] & TT__PF_ALIVE) e = fmax(e, tt__constraint_bounds_violation(w, c, i, w->px[i], w->py[i], &dx, &dy));
        }
        return e;
    }
    case TT_CONSTRAINT_ANGLE:
        return fabs(tt__constraint_angle_error(tt__constraint_angle_at(w, c->p[0], c->p[1], c->p[2]), c->v[0], c->v[1]));
    case TT_CONSTRAINT_AREA:
        return fabs(tt__constraint_polygon_area(&(tt__lay){w->px, w->py, w->inv_mass, 1}, c->list, c->n) - c->v[0] * c->v[1]);
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
        const double len = tt__constraint_dist_of(w, d->a, d->b), C = len < d->lo ? d->lo - len : len > d->hi ? len - d->hi : 0.0;
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
        double len = tt__constraint_dist_of(w, d->a, d->b);
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
        if (out && cap > 0) out[0] = tt__cgroup_particle(w, d->a);
        if (out && cap > 1) out[1] = tt__cgroup_particle(w, d->b);
    } else {
        const tt__gcon *gc = &g->gen[s->dense];
        n = gc->n;
        for (uint32_t k = 0; out && k < n && k < cap; k++) out[k] = tt__cgroup_particle(w, gc->list ? gc->list[k] : gc->p[k]);
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
        tt__distance_hot_sync(g, s->dense);
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
    if ((r = tt__constraint_check_compliance(w, alpha, fn)) != TT_OK) return r;
    tt__cslot *s = &g->slots[c.index];
    if (s->kind == TT_CONSTRAINT_BOUNDS) return tt__fail(w, TT_ESTATE, "%s: bounds are always stiff", fn);
    if (s->kind == TT_CONSTRAINT_DISTANCE) {
        tt__dist *d = &g->dist[s->dense];
        g->nxpbd += (alpha > 0) - (d->alpha > 0);
        d->alpha = alpha;
        tt__distance_hot_sync(g, s->dense);
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
    const double to[2] = {length, 0.0};
    if (!tt__target_move(g, c.index, to)) return tt__fail(w, TT_ENOMEM, "%s: out of memory", fn);
    g->dx[g->slots[c.index].dense].rest = length; /* the solver's length follows in the next step (constraint_relax.c) */
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
    const double to[2] = {anchor.x, anchor.y};
    if (!tt__target_move((tt__cgroup *)g, c.index, to)) return tt__fail(w, TT_ENOMEM, "%s: out of memory", fn);
    return TT_OK;
}

tt_result tt_pin_get_anchor(const tt_world *w, tt_constraint c, tt_vec2 *out)
{
    const char *fn = "tt_pin_get_anchor";
    const tt__cgroup *g;
    tt_result r = kind_check(w, c, TT_CONSTRAINT_PIN, fn, &g);
    if (r != TT_OK) return r;
    if (!out) return tt__fail(w, TT_EINVAL, "%s: out is NULL", fn);
    uint32_t k = g->slots[c.index].mover;
    const tt__gcon *p = &g->gen[g->slots[c.index].dense];
    /* the anchor set, not the one the solver is on its way through */
    *out = k ? (tt_vec2){g->moving[k - 1].to[0], g->moving[k - 1].to[1]} : (tt_vec2){p->v[0], p->v[1]};
    return TT_OK;
}

/* Distance constraints and pins: the field that holds the rate; NULL (and the error set) for other kinds. */
static double *rate_of(const tt_world *w, const tt__cgroup *g, tt_constraint c, const char *fn)
{
    const tt__cslot *s = &g->slots[c.index];
    if (s->kind == TT_CONSTRAINT_DISTANCE || s->kind == TT_CONSTRAINT_PIN) return &((tt__cgroup *)g)->slots[c.index].max_rate;
    tt__fail(w, TT_EINVAL, "%s: max_rate is for distance constraints and pins", fn);
    return NULL;
}

tt_result tt_constraint_set_max_rate(tt_world *w, tt_constraint c, double rate)
{
    const char *fn = "tt_constraint_set_max_rate";
    const tt__cgroup *g;
    tt_result r = con_check(w, c, fn, &g);
    if (r != TT_OK) return r;
    if ((r = tt__constraint_check_rate(w, rate, fn)) != TT_OK) return r;
    double *field = rate_of(w, g, c, fn);
    if (!field) return TT_EINVAL;
    *field = rate;
    return TT_OK;
}

tt_result tt_constraint_get_max_rate(const tt_world *w, tt_constraint c, double *out)
{
    const char *fn = "tt_constraint_get_max_rate";
    const tt__cgroup *g;
    tt_result r = con_check(w, c, fn, &g);
    if (r != TT_OK) return r;
    if (!out) return tt__fail(w, TT_EINVAL, "%s: out is NULL", fn);
    const double *field = rate_of(w, g, c, fn);
    if (!field) return TT_EINVAL;
    *out = *field;
    return TT_OK;
}

tt_result tt_bounds_set_box(tt_world *w, tt_constraint c, tt_vec2 lo, tt_vec2 hi)
{
    const char *fn = "tt_bounds_set_box";
    const tt__cgroup *g;
    tt_result r = kind_check(w, c, TT_CONSTRAINT_BOUNDS, fn, &g);
    if (r != TT_OK) return r;
    if ((r = tt__constraint_check_box(w, lo, hi, fn)) != TT_OK) return r;
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

