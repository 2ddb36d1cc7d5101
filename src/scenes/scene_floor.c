/* tether — the reference pour into a U floor, as a chain shape or as a mask
 * terrain of 0.1 m pixels (issue 19: the mask floor's cost per
 * particle-contact against the same floor as a chain). The circles are
 * ts_scene_pour's (grid, radius, friction 0.3, g = 10, dt = 1/60); the U
 * has its floor top at y = 0 and its inner walls at ±width/2, as the
 * pour's box, but no thickness: a chain's edges, or 2 m of solid pixels. */
#include "scene.h"

#include <math.h>
#include <string.h>

#define PIXEL 0.1 /* m */

static tt_result add_floor(tt_world *w, double width, double top, bool mask)
{
    const double h = width / 2;
    if (!mask) {
        const tt_vec2 pts[4] = {{-h, top}, {-h, 0}, {h, 0}, {h, top}};
        tt_shape_def sd = tt_shape_def_default();
        sd.type = TT_SHAPE_CHAIN;
        sd.points = pts;
        sd.count = 4;
        sd.friction_static = sd.friction_kinetic = 0.3;
        return tt_shape_create(w, &sd).gen ? TT_OK : TT_ENOMEM;
    }
    /* 2 m of solid pixels beyond each wall and under the floor; whole
     * pixels above the floor, so its top is at y = 0 */
    const int in = (int)lround(width / PIXEL), wall = (int)lround(2 / PIXEL), above = (int)ceil(top / PIXEL);
    const int mh = above + wall;
    tt_mask *m = tt_mask_create(in + 2 * wall, mh, false);
    if (!m) return TT_ENOMEM;
    tt_mask_fill_rect(m, 0, mh - wall, in + 2 * wall, wall, true);
    tt_mask_fill_rect(m, 0, 0, wall, mh, true);
    tt_mask_fill_rect(m, wall + in, 0, wall, mh, true);
    tt_terrain_def td = tt_terrain_def_default();
    td.solid = m;
    td.pixel = PIXEL;
    td.origin = (tt_vec2){-wall * PIXEL - h, above * PIXEL};
    td.friction_static = td.friction_kinetic = 0.3;
    const tt_terrain t = tt_terrain_create(w, &td);
    tt_mask_destroy(m);
    return t.gen ? TT_OK : TT_ENOMEM;
}

tt_result ts_floor_build(uint32_t n, double width, bool mask, ts_tether *t, const char **why)
{
    double top;
    uint32_t steps;
    tt_result r = ts_tether_pour_circles(n, width, 0, mask ? "pour on a mask floor" : "pour on a chain floor", t, &top, &steps,
                                         why);
    if (r != TT_OK) return r;
    r = add_floor(t->world, width, top, mask);
    if (r != TT_OK) {
        if (why) *why = "out of memory";
        ts_tether_free(t);
    }
    return r;
}
