/* tether — the collision definitions: the defaults of the world's
 * collision settings and of a shape (tether/collide.h), the shape types'
 * names, and the check every shape definition passes (tt_shape_create and
 * the snapshot loader). Pure functions that every file of the feature,
 * and the group that owns its state (contacts.c), may use. */
#include "collide_internal.h"

#include <string.h>

tt_collision_settings tt_collision_settings_default(void)
{
    tt_collision_settings s;
    memset(&s, 0, sizeof s);
    s.particles = true;
    s.broadphase = TT_BROADPHASE_GRID;
    s.cell_size = 0.0;
    s.restitution = 0.0;
    s.friction_static = 0.6;
    s.friction_kinetic = 0.5;
    s.restitution_threshold = -1.0;
    s.events = 0;
    return s;
}

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

tt_result tt__material_check(const tt_world *w, double e, double fs, double fk, double max_friction, const char *fn)
{
    if (!tt__in_range(e, 0.0, 1.0)) return tt__fail(w, TT_EINVAL, "%s: restitution must be in [0, 1], got %g", fn, e);
    if (!tt__in_range(fs, 0.0, max_friction)) return tt__fail(w, TT_EINVAL, "%s: static friction must be in [0, %g], got %g", fn, max_friction, fs);
    if (!tt__in_range(fk, 0.0, max_friction)) return tt__fail(w, TT_EINVAL, "%s: kinetic friction must be in [0, %g], got %g", fn, max_friction, fk);
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
    tt_result r = tt__material_check(w, d->restitution, d->friction_static, d->friction_kinetic, TT_MAX_VALUE, fn);
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
