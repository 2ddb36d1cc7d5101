/* tether — masks in the world: the conversion between mask pixels (y down)
 * and world coordinates (y up), and outlines made into chain shapes. The
 * only file of the mask library that touches a world, and only through the
 * collision module's public shape calls. */
#include "mask_internal.h"

#include <math.h>
#include <stdlib.h>

tt_mask_place tt_mask_place_default(void)
{
    return (tt_mask_place){ { 0, 0 }, 1.0 };
}

tt_vec2 tt_mask_to_world(const tt_mask_place *place, tt_vec2 p)
{
    tt_mask_place d = tt_mask_place_default();
    if (!place) place = &d;
    return (tt_vec2){ place->origin.x + p.x * place->pixel, place->origin.y - p.y * place->pixel };
}

tt_vec2 tt_mask_from_world(const tt_mask_place *place, tt_vec2 q)
{
    tt_mask_place d = tt_mask_place_default();
    if (!place || !(place->pixel > 0)) place = &d;
    return (tt_vec2){ (q.x - place->origin.x) / place->pixel, (place->origin.y - q.y) / place->pixel };
}

static tt_result check_place(const char *fn, const tt_mask_place *p)
{
    if (!p) return tt__mask_fail(TT_EINVAL, "%s: place is NULL", fn);
    if (!(fabs(p->origin.x) <= TT_MAX_VALUE && fabs(p->origin.y) <= TT_MAX_VALUE))
        return tt__mask_fail(TT_EINVAL, "%s: origin (%g, %g) not finite within %g", fn, p->origin.x, p->origin.y, TT_MAX_VALUE);
    if (!(p->pixel > 0 && p->pixel * TT_MASK_MAX_SIDE <= TT_MAX_VALUE))
        return tt__mask_fail(TT_EINVAL, "%s: pixel size %g not in (0, %g]", fn, p->pixel, TT_MAX_VALUE / TT_MASK_MAX_SIDE);
    return TT_OK;
}

/* Creates one looped chain per polyline; on a failure destroys those made. */
static tt_result make_chains(const char *fn, tt_world *w, const tt_mask_place *place, const tt_shape_def *tmpl,
                             const tt_mask_polyline *lines, uint32_t n, tt_shape *out)
{
    for (uint32_t i = 0; i < n; i++) {
        tt_vec2 *p = malloc(lines[i].count * sizeof *p);
        tt_shape s = { 0, 0 };
        if (p) {
            for (uint32_t k = 0; k < lines[i].count; k++) p[k] = tt_mask_to_world(place, lines[i].points[k]);
            tt_shape_def d = *tmpl;
            d.type = TT_SHAPE_CHAIN;
            d.position = (tt_vec2){ 0, 0 };
            d.angle = 0;
            d.points = p;
            d.count = lines[i].count;
            d.loop = true;
            s = tt_shape_create(w, &d);
            free(p);
        }
        if (s.gen == 0) {
            while (i-- > 0) tt_shape_destroy(w, out[i]);
            return tt__mask_fail(p ? TT_EINVAL : TT_ENOMEM, "%s: chain %u: %s", fn, i, p ? tt_last_error(w) : "out of memory");
        }
        out[i] = s;
    }
    return TT_OK;
}

tt_result tt_mask_to_chains(const tt_mask *m, tt_world *w, const tt_mask_place *place, double tolerance,
                            const tt_shape_def *def, tt_shape *out, uint32_t cap, uint32_t *count)
{
    const char *fn = "tt_mask_to_chains";
    if (!m || !w || !count || (!out && cap))
        return tt__mask_fail(TT_EINVAL, "%s: %s is NULL", fn, !m ? "mask" : !w ? "world" : !count ? "count" : "out");
    tt_result r = check_place(fn, place);
    if (r != TT_OK) return r;
    tt_shape_def d = def ? *def : tt_shape_def_default();
    tt_mask_polyline *lines;
    uint32_t n;
    if ((r = tt_mask_polylines(m, tolerance, &lines, &n)) != TT_OK) return r;
    *count = n;
    if (n > cap) r = tt__mask_fail(TT_EINVAL, "%s: the outline has %u loops, more than cap %u", fn, n, cap);
    else r = make_chains(fn, w, place, &d, lines, n, out);
    tt_mask_polylines_free(lines, n);
    return r;
}
