/* tether — shapes: storage behind generational handles, their definitions
 * checked, and the calls that read and change them. Their primitives in
 * world coordinates and the static index over them are in static_index.c,
 * their outlines in shape_outline.c. */
#include "collide_internal.h"

#include <stdlib.h>
#include <string.h>

static const char *const type_names[TT_SHAPE_TYPE_COUNT] = {"segment", "chain", "aabb", "box", "circle", "capsule", "polygon"};

const char *tt_shape_type_name(tt_shape_type t)
{
    return (unsigned)t < TT_SHAPE_TYPE_COUNT ? type_names[t] : "unknown";
}

tt_shape_def tt_shape_def_default(void)
{
    tt_shape_def d;
    memset(&d, 0, sizeof d);
    d.type = TT_SHAPE_SEGMENT;
    d.b = (tt_vec2){1.0, 0.0};
    d.half_extents = (tt_vec2){0.5, 0.5};
    d.radius = 0.5;
    d.friction_static = 0.6;
    d.friction_kinetic = 0.5;
    d.category = 0x0001;
    d.mask = 0xFFFF;
    return d;
}

bool tt__shape_ok(const tt__collide *c, tt_shape s)
{
    return c && s.index < c->spool.count && s.gen != 0 && c->spool.gen[s.index] == s.gen && c->shapes[s.index].alive;
}

static tt_result material_check(const tt_world *w, double e, double fs, double fk, const char *fn)
{
    if (!tt__in_range(e, 0.0, 1.0)) return tt__fail(w, TT_EINVAL, "%s: restitution must be in [0, 1], got %g", fn, e);
    if (!tt__in_range(fs, 0.0, TT_MAX_VALUE)) return tt__fail(w, TT_EINVAL, "%s: static friction must be in [0, %g], got %g", fn, TT_MAX_VALUE, fs);
    if (!tt__in_range(fk, 0.0, TT_MAX_VALUE)) return tt__fail(w, TT_EINVAL, "%s: kinetic friction must be in [0, %g], got %g", fn, TT_MAX_VALUE, fk);
    return TT_OK;
}

static double cross3(tt_vec2 o, tt_vec2 a, tt_vec2 b) { return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x); }

uint32_t tt__polygon_fault(const tt_vec2 *pts, uint32_t n, bool convex)
{
    double sign = 0.0;
    for (uint32_t k = 0; k < n; k++) {
        double cr = cross3(pts[k], pts[(k + 1) % n], pts[(k + 2) % n]);
        if (cr == 0.0 || (convex && sign != 0.0 && (cr > 0.0) != (sign > 0.0))) return (k + 1) % n;
        sign = cr;
    }
    /* a convex outline cannot come back to a point; any other can, beyond its neighbours */
    for (uint32_t j = 0; !convex && j < n; j++)
        for (uint32_t i = 0; i < j; i++)
            if (pts[i].x == pts[j].x && pts[i].y == pts[j].y) return j;
    return n;
}

tt_result tt__shape_check_def(const tt_world *w, const tt_shape_def *d, const char *fn)
{
    if (!d) return tt__fail(w, TT_EINVAL, "%s: def is NULL", fn);
    if ((unsigned)d->type >= TT_SHAPE_TYPE_COUNT) return tt__fail(w, TT_EINVAL, "%s: unknown shape type %d", fn, (int)d->type);
    if (!tt__vec_ok(d->position)) return tt__fail(w, TT_EINVAL, "%s: position must be finite, |x| <= %g", fn, TT_MAX_VALUE);
    if (!tt__in_range(d->angle, -TT_MAX_VALUE, TT_MAX_VALUE)) return tt__fail(w, TT_EINVAL, "%s: angle must be finite", fn);
    if (!tt__vec_ok(d->a) || !tt__vec_ok(d->b)) return tt__fail(w, TT_EINVAL, "%s: a and b must be finite, |x| <= %g", fn, TT_MAX_VALUE);
    /* even where the type does not use them: they are kept, saved and loaded (the loader takes |x| <= 1e300) */
    if (!(fabs(d->radius) <= 1e300 && fabs(d->half_extents.x) <= 1e300 && fabs(d->half_extents.y) <= 1e300))
        return tt__fail(w, TT_EINVAL, "%s: radius and half_extents must be finite, even where the type does not use them", fn);
    tt_result r = material_check(w, d->restitution, d->friction_static, d->friction_kinetic, fn);
    if (r != TT_OK) return r;
    switch (d->type) {
    case TT_SHAPE_AABB:
        if (!(d->a.x <= d->b.x && d->a.y <= d->b.y)) return tt__fail(w, TT_EINVAL, "%s: aabb needs a <= b (min and max corners)", fn);
        if (d->angle != 0.0) return tt__fail(w, TT_EINVAL, "%s: an aabb cannot be turned (angle must be 0); use a box", fn);
        break;
    case TT_SHAPE_BOX:
        if (!(d->half_extents.x > 0.0 && d->half_extents.y > 0.0 && tt__vec_ok(d->half_extents)))
            return tt__fail(w, TT_EINVAL, "%s: box half_extents must be in (0, %g]", fn, TT_MAX_VALUE);
        break;
    case TT_SHAPE_CIRCLE:
        if (!(d->radius > 0.0 && d->radius <= TT_MAX_VALUE)) return tt__fail(w, TT_EINVAL, "%s: circle radius must be in (0, %g], got %g", fn, TT_MAX_VALUE, d->radius);
        break;
    case TT_SHAPE_CAPSULE:
        if (!tt__in_range(d->radius, 0.0, TT_MAX_VALUE)) return tt__fail(w, TT_EINVAL, "%s: capsule radius must be in [0, %g], got %g", fn, TT_MAX_VALUE, d->radius);
        break;
    case TT_SHAPE_CHAIN:
    case TT_SHAPE_POLYGON: {
        bool poly = d->type == TT_SHAPE_POLYGON;
        uint32_t lo = poly ? 3 : 2, hi = poly ? TT_MAX_POLYGON_POINTS : TT_MAX_CHAIN_POINTS;
        if (!d->points || d->count < lo || d->count > hi)
            return tt__fail(w, TT_EINVAL, "%s: %s needs points and count in [%u, %u], got %u", fn, type_names[d->type], lo, hi, d->count);
        for (uint32_t k = 0; k < d->count; k++)
            if (!tt__vec_ok(d->points[k])) return tt__fail(w, TT_EINVAL, "%s: point %u must be finite, |x| <= %g", fn, k, TT_MAX_VALUE);
        uint32_t bad = poly ? tt__polygon_fault(d->points, d->count, true) : d->count;
        if (bad < d->count)
            return tt__fail(w, TT_EINVAL, "%s: polygon must be convex with no repeated or collinear points (at point %u)", fn, bad);
        break;
    }
    default: break;
    }
    return TT_OK;
}

tt_shape tt_shape_create(tt_world *w, const tt_shape_def *def)
{
    tt_shape none = {0, 0};
    if (!w) { tt__fail(NULL, TT_EINVAL, "tt_shape_create: world is NULL"); return none; }
    if (tt__shape_check_def(w, def, "tt_shape_create") != TT_OK) return none;
    tt_vec2 *pts = NULL;
    uint32_t npts = (def->type == TT_SHAPE_CHAIN || def->type == TT_SHAPE_POLYGON) ? def->count : 0;
    if (npts) {
        pts = malloc((size_t)npts * sizeof *pts);
        if (!pts) { tt__fail(w, TT_ENOMEM, "tt_shape_create: out of memory"); return none; }
        memcpy(pts, def->points, (size_t)npts * sizeof *pts);
    }
    /* a collision group registered here goes again if the shape cannot be
     * made: a failed call leaves the world as it was */
    const bool had = tt__collide_peek(w) != NULL;
    tt__collide *c = tt__collide_get(w, true, "tt_shape_create");
    if (!c) { free(pts); return none; }
    if (c->shapes_alive >= TT_MAX_SHAPES) {
        free(pts);
        tt__fail(w, TT_ENOMEM, "tt_shape_create: the world has %u shapes, the most allowed", TT_MAX_SHAPES);
        return none;
    }
    bool grew;
    uint32_t need = c->spool.free_count ? c->spool.count : c->spool.count + 1;
    uint32_t i = tt__grow((void **)&c->shapes, &c->shcap, need, sizeof *c->shapes)
                     ? tt__pool_alloc(&c->spool, TT_MAX_SHAPES, &grew) : UINT32_MAX;
    if (i == UINT32_MAX) {
        free(pts);
        if (!had) tt__group_remove(w, &tt__contacts_ops);
        tt__fail(w, TT_ENOMEM, "tt_shape_create: out of memory");
        return none;
    }
    tt__shape *s = &c->shapes[i];
    s->def = *def;
    s->def.points = NULL;
    s->def.count = npts;
    s->pts = pts;
    s->alive = true;
    s->moved = false;
    s->from = def->position;
    s->from_angle = def->angle;
    c->shapes_alive++;
    c->dirty = true;
    return (tt_shape){i, c->spool.gen[i]};
}

static void drop_records(tt__collide *c, uint64_t lo_mask, uint64_t match)
{
    uint32_t k = 0;
    for (uint32_t j = 0; j < c->nprev; j++)
        if ((c->prev[j].key & lo_mask) != match) c->prev[k++] = c->prev[j];
    c->nprev = k;
}

tt_result tt_shape_destroy(tt_world *w, tt_shape s)
{
    TT__SHAPE_CHECK("tt_shape_destroy");
    free(sh->pts);
    sh->pts = NULL;
    sh->alive = false;
    tt__pool_free(&c->spool, s.index);
    c->shapes_alive--;
    c->dirty = true;
    /* its contacts of the last step will never END: drop them (key: bit 63 shape, bits 32..62 shape slot) */
    drop_records(c, 0xFFFFFFFF00000000ull, (1ull << 63) | ((uint64_t)s.index << 32));
    return TT_OK;
}

bool tt_shape_is_valid(const tt_world *w, tt_shape s) { return w && tt__shape_ok(tt__collide_peek(w), s); }

tt_result tt_shape_set_transform(tt_world *w, tt_shape s, tt_vec2 position, double angle)
{
    TT__SHAPE_CHECK("tt_shape_set_transform");
    if (!tt__vec_ok(position)) return tt__fail(w, TT_EINVAL, "tt_shape_set_transform: position must be finite, |x| <= %g", TT_MAX_VALUE);
    if (!tt__in_range(angle, -TT_MAX_VALUE, TT_MAX_VALUE)) return tt__fail(w, TT_EINVAL, "tt_shape_set_transform: angle must be finite");
    if (sh->def.type == TT_SHAPE_AABB && angle != 0.0) return tt__fail(w, TT_EINVAL, "tt_shape_set_transform: an aabb cannot be turned (angle must be 0)");
    if (!sh->moved) { /* the first move since the last step: the path starts where that step left it */
        sh->from = sh->def.position;
        sh->from_angle = sh->def.angle;
    }
    sh->def.position = position;
    sh->def.angle = angle;
    sh->moved = true;
    c->any_moved = true;
    c->dirty = true;
    return TT_OK;
}

tt_result tt_shape_get_transform(const tt_world *w, tt_shape s, tt_vec2 *position, double *angle)
{
    TT__SHAPE_CHECK("tt_shape_get_transform");
    if (!position || !angle) return tt__fail(w, TT_EINVAL, "tt_shape_get_transform: out is NULL");
    *position = sh->def.position;
    *angle = sh->def.angle;
    return TT_OK;
}

tt_result tt_shape_set_material(tt_world *w, tt_shape s, double e, double fs, double fk)
{
    TT__SHAPE_CHECK("tt_shape_set_material");
    tt_result r = material_check(w, e, fs, fk, "tt_shape_set_material");
    if (r != TT_OK) return r;
    sh->def.restitution = e;
    sh->def.friction_static = fs;
    sh->def.friction_kinetic = fk;
    return TT_OK;
}

tt_result tt_shape_set_filter(tt_world *w, tt_shape s, uint16_t category, uint16_t mask)
{
    TT__SHAPE_CHECK("tt_shape_set_filter");
    sh->def.category = category;
    sh->def.mask = mask;
    return TT_OK;
}

tt_result tt_shape_set_sensor(tt_world *w, tt_shape s, bool sensor)
{
    TT__SHAPE_CHECK("tt_shape_set_sensor");
    sh->def.sensor = sensor;
    return TT_OK;
}

tt_result tt_shape_get_type(const tt_world *w, tt_shape s, tt_shape_type *out)
{
    TT__SHAPE_CHECK("tt_shape_get_type");
    if (!out) return tt__fail(w, TT_EINVAL, "tt_shape_get_type: out is NULL");
    *out = sh->def.type;
    return TT_OK;
}

tt_result tt_shape_get_user(const tt_world *w, tt_shape s, uint64_t *out)
{
    TT__SHAPE_CHECK("tt_shape_get_user");
    if (!out) return tt__fail(w, TT_EINVAL, "tt_shape_get_user: out is NULL");
    *out = sh->def.user;
    return TT_OK;
}

uint32_t tt_world_shape_count(const tt_world *w)
{
    const tt__collide *c = w ? tt__collide_peek(w) : NULL;
    return c ? c->shapes_alive : 0;
}

tt_result tt_shape_get_aabb(const tt_world *w, tt_shape s, tt_vec2 *lo, tt_vec2 *hi)
{
    TT__SHAPE_CHECK("tt_shape_get_aabb");
    (void)sh;
    if (!lo || !hi) return tt__fail(w, TT_EINVAL, "tt_shape_get_aabb: out is NULL");
    if (c->dirty && tt__shapes_rebuild((tt_world *)w, c) != TT_OK) return TT_ENOMEM;
    *lo = (tt_vec2){INFINITY, INFINITY};
    *hi = (tt_vec2){-INFINITY, -INFINITY};
    for (uint32_t k = 0; k < c->nprim; k++) {
        const tt__prim *p = &c->prims[k];
        if (p->shape != s.index) continue;
        lo->x = fmin(lo->x, p->lox); lo->y = fmin(lo->y, p->loy);
        hi->x = fmax(hi->x, p->hix); hi->y = fmax(hi->y, p->hiy);
    }
    return TT_OK;
}

void tt__shapes_free(tt__collide *c)
{
    /* a load that ran out of memory may leave the pool read and the array not made */
    for (uint32_t i = 0; c->shapes && i < c->spool.count; i++) free(c->shapes[i].pts);
    free(c->shapes);
    tt__pool_destroy(&c->spool);
    free(c->prims); free(c->verts); free(c->norms);
    free(c->sgrid.start); free(c->sgrid.items); free(c->sgrid.big);
    free(c->pstamp); free(c->sstamp);
}

size_t tt__shapes_bytes(const tt__collide *c)
{
    size_t b = (size_t)c->shcap * sizeof(tt__shape) + tt__pool_bytes(&c->spool);
    for (uint32_t i = 0; i < c->spool.count; i++)
        if (c->shapes[i].alive) b += (size_t)c->shapes[i].def.count * sizeof(tt_vec2);
    b += (size_t)c->primcap * sizeof(tt__prim) + ((size_t)c->vertcap + c->normcap) * sizeof(tt_vec2);
    b += ((size_t)c->sgrid.cap_cells + c->sgrid.cap_items + c->sgrid.cap_big) * sizeof(uint32_t);
    b += ((size_t)c->pstamp_cap + c->sstamp_cap) * sizeof(uint32_t);
    return b;
}

uint32_t tt_world_list_shapes(const tt_world *w, tt_shape *out, uint32_t cap)
{
    const tt__collide *c = w ? tt__collide_peek(w) : NULL;
    if (!c) return 0;
    uint32_t n = 0;
    for (uint32_t i = 0; i < c->spool.count; i++) {
        if (!c->shapes[i].alive) continue;
        if (out && n < cap) out[n] = (tt_shape){i, c->spool.gen[i]};
        n++;
    }
    return n;
}

tt_result tt_shape_get_sensor(const tt_world *w, tt_shape s, bool *out)
{
    TT__SHAPE_CHECK("tt_shape_get_sensor");
    if (!out) return tt__fail(w, TT_EINVAL, "tt_shape_get_sensor: out is NULL");
    *out = sh->def.sensor;
    return TT_OK;
}
