/* tether — shape outlines: each shape's points in world coordinates, as
 * the debug draw shows them (circles and capsule ends as polylines). */
#include "collide_internal.h"

/* Appends the world position of local point p (shape placed by pos + R(angle)). */
static void put(tt_vec2 *out, uint32_t cap, uint32_t *n, const tt_shape_def *d, double x, double y)
{
    if (out && *n < cap) {
        double cs = cos(d->angle), sn = sin(d->angle);
        out[*n] = (tt_vec2){d->position.x + cs * x - sn * y, d->position.y + sn * x + cs * y};
    }
    (*n)++;
}

/* A half circle of `segs` steps around centre (cx, cy) from angle a0. */
static void arc(tt_vec2 *out, uint32_t cap, uint32_t *n, const tt_shape_def *d, double cx, double cy, double r,
                double a0, double sweep, int segs)
{
    for (int k = 0; k <= segs; k++) {
        double a = a0 + sweep * k / segs;
        put(out, cap, n, d, cx + r * cos(a), cy + r * sin(a));
    }
}

tt_result tt_shape_get_outline(const tt_world *w, tt_shape s, tt_vec2 *out, uint32_t cap, uint32_t *count, bool *closed)
{
    TT__SHAPE_CHECK("tt_shape_get_outline");
    if (!count || !closed) return tt__fail(w, TT_EINVAL, "tt_shape_get_outline: out is NULL");
    const tt_shape_def *d = &sh->def;
    uint32_t n = 0;
    *closed = true;
    switch (d->type) {
    case TT_SHAPE_SEGMENT:
        put(out, cap, &n, d, d->a.x, d->a.y);
        put(out, cap, &n, d, d->b.x, d->b.y);
        *closed = false;
        break;
    case TT_SHAPE_CHAIN:
        for (uint32_t k = 0; k < d->count; k++) put(out, cap, &n, d, sh->pts[k].x, sh->pts[k].y);
        *closed = d->loop;
        break;
    case TT_SHAPE_AABB:
        put(out, cap, &n, d, d->a.x, d->a.y);
        put(out, cap, &n, d, d->b.x, d->a.y);
        put(out, cap, &n, d, d->b.x, d->b.y);
        put(out, cap, &n, d, d->a.x, d->b.y);
        break;
    case TT_SHAPE_BOX: {
        double hx = d->half_extents.x, hy = d->half_extents.y;
        put(out, cap, &n, d, -hx, -hy);
        put(out, cap, &n, d, hx, -hy);
        put(out, cap, &n, d, hx, hy);
        put(out, cap, &n, d, -hx, hy);
        break;
    }
    case TT_SHAPE_CIRCLE:
        arc(out, cap, &n, d, 0, 0, d->radius, 0, 2 * M_PI * 31 / 32, 31);
        break;
    case TT_SHAPE_CAPSULE: {
        double ang = atan2(d->b.y - d->a.y, d->b.x - d->a.x);
        arc(out, cap, &n, d, d->b.x, d->b.y, d->radius, ang - M_PI / 2, M_PI, 12);
        arc(out, cap, &n, d, d->a.x, d->a.y, d->radius, ang + M_PI / 2, M_PI, 12);
        break;
    }
    case TT_SHAPE_POLYGON:
        for (uint32_t k = 0; k < d->count; k++) put(out, cap, &n, d, sh->pts[k].x, sh->pts[k].y);
        break;
    default:
        break;
    }
    *count = n;
    return TT_OK;
}
