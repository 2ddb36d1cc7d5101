/* Outlines as geometry: marching squares + Douglas-Peucker on known shapes,
 * and outlines made into chain shapes a particle bounces on, through the
 * pixel/world conversion (y flips). */
#include "test.h"
#include "tether.h"

#include <stdlib.h>

static double area(const tt_mask_polyline *l)
{
    double a = 0;
    for (uint32_t i = 0, j = l->count - 1; i < l->count; j = i++)
        a += l->points[j].x * l->points[i].y - l->points[i].x * l->points[j].y;
    return a / 2; /* y down: counter-clockwise on screen is negative */
}

TEST(mask_disc_outline_area_within_one_percent)
{
    for (int r = 20; r <= 80; r += 30) {
        tt_mask *m = tt_mask_create(2 * r + 10, 2 * r + 10, false);
        ENSURE_OK(tt_mask_fill_circle(m, r + 5, r + 5, r, true));
        for (int t = 0; t < 3; t++) {
            double tol = (double[]){ 0, 0.5, 1.0 }[t];
            tt_mask_polyline *l;
            uint32_t n;
            ENSURE_OK(tt_mask_polylines(m, tol, &l, &n));
            ENSURE(n == 1);
            ENSURE(area(&l[0]) < 0); /* counter-clockwise on screen */
            ENSURE_NEAR(-area(&l[0]), M_PI * r * r, 0.01 * M_PI * r * r);
            for (uint32_t i = 0; i < l[0].count; i++) { /* every point on the circle, within the tolerance + a pixel */
                double d = hypot(l[0].points[i].x - (r + 5), l[0].points[i].y - (r + 5));
                ENSURE_NEAR(d, r, 1.0 + tol);
            }
            if (t == 2) ENSURE(l[0].count < 60 + 2 * (uint32_t)r); /* simplified */
            tt_mask_polylines_free(l, n);
        }
        tt_mask_destroy(m);
    }
}

TEST(mask_polylines_of_known_shapes)
{
    tt_mask *m = tt_mask_create(30, 30, false);
    ENSURE_OK(tt_mask_fill_rect(m, 5, 5, 20, 20, true));
    ENSURE_OK(tt_mask_fill_rect(m, 10, 10, 10, 10, false)); /* a square hole */
    ENSURE_OK(tt_mask_set(m, 0, 0, true));                  /* a lone pixel */
    tt_mask_polyline *l;
    uint32_t n;
    ENSURE_OK(tt_mask_polylines(m, 0, &l, &n));
    ENSURE(n == 3);
    /* the lone pixel: a diamond through its edge midpoints */
    ENSURE(l[0].count == 4);
    ENSURE_NEAR(area(&l[0]), -0.5, 1e-12);
    /* the frame: outer square with cut corners, counter-clockwise; the hole clockwise */
    ENSURE(l[1].count == 8 && l[2].count == 8);
    ENSURE_NEAR(area(&l[1]), -(400 - 4 * 0.125), 1e-9);
    ENSURE_NEAR(area(&l[2]), 100 - 4 * 0.125, 1e-9); /* the hole's corners are cut too */
    tt_mask_polylines_free(l, n);
    ENSURE(tt_mask_polylines(m, -1, &l, &n) == TT_EINVAL);
    ENSURE(tt_mask_polylines(m, NAN, &l, &n) == TT_EINVAL);
    ENSURE(tt_mask_polylines(NULL, 0, &l, &n) == TT_EINVAL);
    tt_mask_destroy(m);
    /* two pixels touching at a corner are one loop (8-connected, as the components) */
    m = tt_mask_create(2, 2, false);
    ENSURE_OK(tt_mask_set(m, 0, 0, true));
    ENSURE_OK(tt_mask_set(m, 1, 1, true));
    ENSURE_OK(tt_mask_polylines(m, 0, &l, &n));
    ENSURE(n == 1 && tt_mask_component_count(m) == 1);
    tt_mask_polylines_free(l, n);
    tt_mask_destroy(m);
}

TEST(mask_place_flips_y)
{
    tt_mask_place p = { { 10, 5 }, 0.5 };
    tt_vec2 w = tt_mask_to_world(&p, (tt_vec2){ 4, 2 }); /* pixel (4, 2)'s top-left corner */
    ENSURE_NEAR(w.x, 12, 1e-12);
    ENSURE_NEAR(w.y, 4, 1e-12); /* two rows down in the image is lower in the world */
    tt_vec2 q = tt_mask_from_world(&p, (tt_vec2){ 12.1, 3.9 });
    ENSURE(floor(q.x) == 4 && floor(q.y) == 2);
}

TEST(mask_outline_chains_hold_a_falling_particle)
{
    /* a 40×20 pixel slab with its top at image row 10: at 0.1 m per pixel
     * with the origin at (0, 3), the slab's top is at y = 3 − 1 = 2 m */
    tt_mask *m = tt_mask_create(40, 30, false);
    ENSURE_OK(tt_mask_fill_rect(m, 0, 10, 40, 20, true));
    tt_world *w = tt_world_create(NULL);
    tt_mask_place p = { { 0, 3 }, 0.1 };
    tt_shape s[4];
    uint32_t n;
    ENSURE(tt_mask_to_chains(m, w, &p, 0.5, NULL, s, 0, &n) == TT_EINVAL); /* no room: nothing made */
    ENSURE(n == 1 && tt_world_list_shapes(w, NULL, 0) == 0);
    ENSURE_OK(tt_mask_to_chains(m, w, &p, 0.5, NULL, s, 4, &n));
    ENSURE(n == 1 && tt_world_list_shapes(w, NULL, 0) == 1);
    tt_particle_def pd = tt_particle_def_default();
    pd.position = (tt_vec2){ 2, 3 };
    pd.radius = 0.1;
    tt_particle a = tt_particle_create(w, &pd);
    for (int i = 0; i < 180; i++) ENSURE_OK(tt_world_step(w, 1.0 / 60));
    tt_vec2 x;
    ENSURE_OK(tt_particle_get_position(w, a, &x));
    ENSURE_NEAR(x.y, 2.0 + 0.1, 0.02); /* resting on the slab's top */
    p.pixel = 0;
    ENSURE(tt_mask_to_chains(m, w, &p, 0.5, NULL, s, 4, &n) == TT_EINVAL);
    p.pixel = NAN;
    ENSURE(tt_mask_to_chains(m, w, &p, 0.5, NULL, s, 4, &n) == TT_EINVAL);
    ENSURE(tt_mask_to_chains(m, NULL, &p, 0.5, NULL, s, 4, &n) == TT_EINVAL);
    ENSURE(tt_world_list_shapes(w, NULL, 0) == 1);
    tt_world_destroy(w);
    tt_mask_destroy(m);
}
