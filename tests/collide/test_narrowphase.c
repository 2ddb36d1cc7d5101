/* Narrowphase: a circle against each kind of shape gives hit, normal,
 * depth and the nearest valid position, checked against answers worked
 * out by hand; rays against primitives likewise. */
#include "test.h"
#include "collide/collide_internal.h"

#include <math.h>
#include <string.h>

static tt__collide *with_shape(tt_world *w, const tt_shape_def *d)
{
    tt_shape s = tt_shape_create(w, d);
    if (!s.gen) return NULL;
    tt__collide *c = tt__collide_peek(w);
    tt__shapes_rebuild(w, c);
    return c;
}

/* depth, normal and nearest valid position of a circle (x, y, r) vs the last shape's first primitive */
#define HIT(c, x, y, r, d, nx_, ny_)                                                   \
    do {                                                                               \
        tt__hit h_;                                                                    \
        tt__circle_vs_prim(c, &(c)->prims[(c)->nprim - 1], x, y, r, &h_);              \
        ENSURE_NEAR(h_.depth, d, 1e-12);                                               \
        ENSURE_NEAR(h_.nx, nx_, 1e-12);                                                \
        ENSURE_NEAR(h_.ny, ny_, 1e-12);                                                \
        if (h_.depth > 0) { /* the nearest valid position touches: depth 0 there */    \
            tt__hit v_;                                                                \
            tt__circle_vs_prim(c, &(c)->prims[(c)->nprim - 1], (x) + h_.nx * h_.depth, \
                               (y) + h_.ny * h_.depth, r, &v_);                        \
            ENSURE_NEAR(v_.depth, 0.0, 1e-12);                                         \
        }                                                                              \
    } while (0)

TEST(circle_against_segment_capsule_and_circle)
{
    tt_world *w = tt_world_create(NULL);
    tt_shape_def d = tt_shape_def_default();
    d.a = (tt_vec2){-1, 0};
    d.b = (tt_vec2){1, 0};
    tt__collide *c = with_shape(w, &d);
    HIT(c, 0.3, 0.4, 0.5, 0.1, 0, 1);                 /* above the middle */
    HIT(c, 0.3, -0.2, 0.5, 0.3, 0, -1);               /* below: two-sided */
    HIT(c, 1.3, 0.4, 0.6, 0.1, 0.6, 0.8);             /* past the end: round */
    HIT(c, 0, 2, 0.5, -1.5, 0, 1);                    /* a miss has negative depth */
    d.type = TT_SHAPE_CAPSULE;
    d.radius = 0.25;
    c = with_shape(w, &d);
    HIT(c, 0.3, 0.4, 0.5, 0.35, 0, 1);
    d.type = TT_SHAPE_CIRCLE;
    d.position = (tt_vec2){2, 3};
    d.radius = 1;
    c = with_shape(w, &d);
    HIT(c, 2.6, 3.8, 0.5, 0.5, 0.6, 0.8);
    HIT(c, 2, 3, 0.5, 1.5, 0, 1); /* centre on centre: pushed out upwards */
    tt_world_destroy(w);
}

TEST(circle_against_aabb_box_and_polygon)
{
    tt_world *w = tt_world_create(NULL);
    tt_shape_def d = tt_shape_def_default();
    d.type = TT_SHAPE_AABB;
    d.a = (tt_vec2){0, 0};
    d.b = (tt_vec2){4, 2};
    tt__collide *c = with_shape(w, &d);
    HIT(c, 2, 2.3, 0.5, 0.2, 0, 1);      /* on the top face */
    HIT(c, 3.9, 1, 0.5, 0.6, 1, 0);      /* centre inside, nearest face is the right one */
    HIT(c, 4.3, 2.4, 1, 0.5, 0.6, 0.8);  /* near the corner: round */
    HIT(c, -2, 1, 0.5, -1.5, -1, 0);
    d.type = TT_SHAPE_BOX;
    d.half_extents = (tt_vec2){1, 0.5};
    d.position = (tt_vec2){10, 0};
    d.angle = M_PI / 2; /* now 1 wide (x) and 2 tall (y) */
    c = with_shape(w, &d);
    HIT(c, 10, 1.2, 0.5, 0.3, 0, 1);
    HIT(c, 10.7, 0, 0.5, 0.3, 1, 0);
    tt_vec2 tri[3] = {{0, 0}, {0, 3}, {3, 0}}; /* clockwise on purpose */
    d.type = TT_SHAPE_POLYGON;
    d.angle = 0;
    d.position = (tt_vec2){0, 0};
    d.points = tri;
    d.count = 3;
    c = with_shape(w, &d);
    double s = sqrt(0.5);
    HIT(c, 2, 2, 1, 1 - 1 * s, s, s);      /* outside the slanted face, distance 1/√2 */
    HIT(c, 1, -0.25, 0.5, 0.25, 0, -1);
    HIT(c, 0.5, 1, 0.1, 0.6, -1, 0);       /* inside: out through the nearest face */
    tt_world_destroy(w);
}

TEST(chain_is_a_series_of_segments_and_bad_shapes_are_refused)
{
    tt_world *w = tt_world_create(NULL);
    tt_vec2 pts[4] = {{0, 0}, {1, 1}, {2, 0}, {3, 1}};
    tt_shape_def d = tt_shape_def_default();
    d.type = TT_SHAPE_CHAIN;
    d.points = pts;
    d.count = 4;
    tt__collide *c = with_shape(w, &d);
    ENSURE(c->nprim == 3);
    d.loop = true;
    c = with_shape(w, &d);
    ENSURE(c->nprim == 3 + 4);
    tt_vec2 concave[4] = {{0, 0}, {2, 0}, {1, 0.5}, {1, 2}};
    d.type = TT_SHAPE_POLYGON;
    d.points = concave;
    ENSURE(tt_shape_create(w, &d).gen == 0);
    ENSURE(strstr(tt_last_error(w), "convex") != NULL);
    d = tt_shape_def_default();
    d.a.x = NAN;
    ENSURE(tt_shape_create(w, &d).gen == 0);
    d = tt_shape_def_default();
    d.type = TT_SHAPE_AABB;
    d.a = (tt_vec2){1, 1};
    d.b = (tt_vec2){0, 0};
    ENSURE(tt_shape_create(w, &d).gen == 0);
    d = tt_shape_def_default();
    d.restitution = 1.5;
    ENSURE(tt_shape_create(w, &d).gen == 0);
    ENSURE(strstr(tt_last_error(w), "restitution") != NULL);
    tt_world_destroy(w);
}

TEST(rays_against_primitives)
{
    tt_world *w = tt_world_create(NULL);
    tt_shape_def d = tt_shape_def_default();
    d.type = TT_SHAPE_AABB;
    d.a = (tt_vec2){1, -1};
    d.b = (tt_vec2){2, 1};
    tt__collide *c = with_shape(w, &d);
    double t, nx, ny;
    const tt__prim *p = &c->prims[c->nprim - 1];
    ENSURE(tt__ray_vs_prim(c, p, 0, 0, 4, 0, 0.0, 1.0, &t, &nx, &ny));
    ENSURE_NEAR(t, 0.25, 1e-15);
    ENSURE(nx == -1 && ny == 0);
    ENSURE(tt__ray_vs_prim(c, p, 0, 0, 4, 0, 0.5, 1.0, &t, &nx, &ny)); /* swept circle of radius 0.5 */
    ENSURE_NEAR(t, 0.125, 1e-15);
    ENSURE(!tt__ray_vs_prim(c, p, 0, 2, 4, 0, 0.5, 1.0, &t, &nx, &ny));
    ENSURE(tt__ray_vs_prim(c, p, 0, 1.3, 4, 0, 0.5, 1.0, &t, &nx, &ny)); /* grazes the rounded corner */
    ENSURE_NEAR(t, (1 - 0.4) / 4, 1e-12);
    ENSURE_NEAR(nx, -0.8, 1e-12);
    ENSURE_NEAR(ny, 0.6, 1e-12);
    ENSURE(tt__ray_vs_circle(0, 0, 10, 0, 5, 0, 1, 1.0, &t, &nx, &ny));
    ENSURE_NEAR(t, 0.4, 1e-15);
    tt_world_destroy(w);
}

/* Shapes whose edges are too short to measure: a box of half extents
 * 1e-300 (its edges' squares underflow to 0), the same box 1e6 m out (its
 * corners round to one point), a zero-size aabb. Their edge normals were
 * 0/0 and x/0: a circle touching one was pushed to NaN and infinity, and
 * the step reported an infinite error (the C API fuzzer, seed 1796410988).
 * Each is the point (or segment) it is: the circle is pushed out to its
 * radius, every figure finite. */
TEST(shapes_with_edges_too_short_to_measure_push_out_as_points)
{
    const double at[] = {0.0, 1e6, 0.0};
    for (int k = 0; k < 3; k++) {
        tt_world_def wd = tt_world_def_default();
        wd.gravity = (tt_vec2){0, 0};
        tt_world *w = tt_world_create(&wd);
        ENSURE(w != NULL);
        tt_collision_settings cs = tt_collision_settings_default();
        ENSURE_OK(tt_world_set_collision(w, &cs));
        tt_shape_def sd = tt_shape_def_default();
        if (k < 2) {
            sd.type = TT_SHAPE_BOX;
            sd.position = (tt_vec2){at[k], 0};
            sd.half_extents = (tt_vec2){1e-300, 1e-300};
        } else {
            sd.type = TT_SHAPE_AABB;
            sd.a = sd.b = (tt_vec2){0, 0};
        }
        ENSURE(tt_shape_create(w, &sd).gen != 0);
        tt_particle_def pd = tt_particle_def_default();
        pd.radius = 0.5;
        pd.position = (tt_vec2){at[k] + 0.1, 0.3};
        tt_particle p = tt_particle_create(w, &pd);
        for (int s = 0; s < 10; s++) ENSURE_OK(tt_world_step(w, 1.0 / 60));
        tt_vec2 x, v;
        tt_particle_get_position(w, p, &x);
        tt_particle_get_velocity(w, p, &v);
        tt_stats st;
        ENSURE_OK(tt_world_get_stats(w, &st));
        ENSURE(isfinite(x.x) && isfinite(x.y) && isfinite(v.x) && isfinite(v.y) && isfinite(st.max_error));
        ENSURE(hypot(x.x - at[k], x.y) >= 0.5 - 1e-9);
        ENSURE(st.diverged == 0);
        tt_world_destroy(w);
    }
}
