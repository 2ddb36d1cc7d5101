/* tether — the shared scene descriptions: the reference pours are the
 * scene issue 12 defines, bad bodies are refused, the pile measures and the
 * tether builder give what a rigid body would. */
#include "test.h"

#include "scenes/scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static bool is_circle(const ts_body *b) { return b->dynamic && b->shape == TS_CIRCLE; }

TEST(scenes_reference_pour_is_the_defined_scene)
{
    ts_scene s;
    ts_scene_pour(&s, 10000, 100);
    ENSURE(s.body_count == 3 + 10000);
    ENSURE(s.gravity.x == 0 && s.gravity.y == -10);
    ENSURE_NEAR(s.dt, 1.0 / 60, 1e-15);
    ENSURE(s.steps == 1200); /* 20 s */
    /* floor top at y = 0, inner wall faces at ±50 up to y = 400, friction 0.3, no bounce */
    for (int i = 0; i < 3; i++) {
        const ts_body *b = &s.bodies[i];
        ENSURE(!b->dynamic && b->friction == 0.3 && b->restitution == 0);
        if (i == 0) ENSURE_NEAR(b->position.y + b->half.y, 0, 1e-12);
        else {
            ENSURE_NEAR(fabs(b->position.x) - b->half.x, 50, 1e-12);
            ENSURE_NEAR(b->position.y + b->half.y, 400, 1e-12);
        }
    }
    const ts_body *c = &s.bodies[3];
    ENSURE(is_circle(c) && c->radius == 0.5 && c->friction == 0.3 && c->restitution == 0);
    /* 89 per row, 1.1 apart, odd rows 0.05 to the right, lowest row at 0.55 */
    ENSURE_NEAR(s.bodies[3 + 1].position.x - c->position.x, 1.1, 1e-12);
    ENSURE_NEAR(s.bodies[3 + 89].position.x - c->position.x, 0.05, 1e-12);
    ENSURE_NEAR(s.bodies[3 + 89].position.y - c->position.y, 1.1, 1e-12);
    ENSURE_NEAR(c->position.y, 0.55, 1e-12);
    ENSURE_NEAR(s.bodies[3 + 88].position.y, 0.55, 1e-12);
    double lo = 1e9, hi = -1e9, top = 0;
    for (uint32_t i = 3; i < s.body_count; i++) {
        ENSURE(is_circle(&s.bodies[i]));
        lo = fmin(lo, s.bodies[i].position.x);
        hi = fmax(hi, s.bodies[i].position.x);
        top = fmax(top, s.bodies[i].position.y);
    }
    ENSURE(lo - 0.5 > -50 && hi + 0.5 < 50);
    ENSURE_NEAR(top, 0.55 + 112 * 1.1, 1e-9); /* 113 rows: free fall from there ends at 49.7 m/s */
    ts_scene_free(&s);
}

TEST(scenes_100k_pour_fits_its_box)
{
    ts_scene s;
    ENSURE(ts_scene_named(&s, "pour100k", false));
    ENSURE(s.body_count == 3 + 100000);
    ENSURE_NEAR(s.bodies[1].position.x + s.bodies[1].half.x, -158, 1e-12);
    ENSURE_NEAR(s.bodies[3 + 286].position.y, 0.55 + 1.1, 1e-12); /* 286 per row */
    ENSURE(s.bodies[s.body_count - 1].position.y + 0.5 < 400);
    ts_scene_free(&s);
}

TEST(scenes_every_named_scene_builds_in_tether)
{
    for (int i = 0; ts_scene_names[i]; i++) {
        if (!strcmp(ts_scene_names[i], "pour100k")) continue; /* 100 000 particles: the bench's, not a test's */
        ts_scene s;
        ENSURE(ts_scene_named(&s, ts_scene_names[i], true));
        ts_tether t;
        const char *why = NULL;
        const ts_tether_settings set = ts_tether_settings_default();
        ENSURE(ts_tether_build(&s, &set, &t, &why) == TT_OK);
        ENSURE(t.count == s.body_count);
        ENSURE_OK(tt_world_step(t.world, s.dt));
        ts_tether_free(&t);
        ts_scene_free(&s);
    }
    ts_scene s;
    ENSURE(!ts_scene_named(&s, "no such scene", false));
}

TEST(scenes_refuse_bad_bodies_and_joints)
{
    ts_scene s;
    ts_scene_init(&s, "bad");
    const char *why = NULL;
    ts_body b = ts_circle(true, (tt_vec2){NAN, 0}, 0.5);
    ENSURE(ts_scene_add_body(&s, &b, &why) == -1 && why != NULL);
    b = ts_circle(true, (tt_vec2){0, 0}, 0);
    ENSURE(ts_scene_add_body(&s, &b, &why) == -1);
    b = ts_box(true, (tt_vec2){0, 0}, 0.5, 0.5, 0);
    b.restitution = 2;
    ENSURE(ts_scene_add_body(&s, &b, &why) == -1);
    b = ts_body_default();
    b.shape = TS_POLYGON; /* clockwise: refused (Box2D needs counter-clockwise) */
    b.count = 3;
    b.points[0] = (tt_vec2){0, 0}, b.points[1] = (tt_vec2){0, 1}, b.points[2] = (tt_vec2){1, 0};
    ENSURE(ts_scene_add_body(&s, &b, &why) == -1);
    b.points[1] = (tt_vec2){1, 0}, b.points[2] = (tt_vec2){0, 1};
    b.dynamic = true;
    ENSURE(ts_scene_add_body(&s, &b, &why) == 0);
    b = ts_body_default();
    b.shape = TS_EDGE, b.dynamic = true, b.b = (tt_vec2){1, 0};
    ENSURE(ts_scene_add_body(&s, &b, &why) == -1); /* edges are static only */
    ts_joint j = {TS_REVOLUTE, TS_GROUND, 5, {0, 0}, {0, 0}};
    ENSURE(ts_scene_add_joint(&s, &j, &why) == -1);
    j.b = 0;
    ENSURE(ts_scene_add_joint(&s, &j, &why) == 0);
    ENSURE(s.body_count == 1 && s.joint_count == 1);
    ts_scene_free(&s);
}

TEST(scenes_pile_measures)
{
    /* three circles of radius 0.5 on a row: two overlap by 0.1, one touches nothing */
    double xy[] = {5, 0.5, 0, 0.5, 0.9, 0.5};
    ts_pile p;
    ts_pile_measure(xy, 3, 0.5, &p);
    ENSURE(p.overlapping == 1);
    ENSURE_NEAR(p.max_overlap, 0.2, 1e-12);
    ENSURE_NEAR(p.mean_overlap, 0.2, 1e-12);
    ENSURE_NEAR(p.height, 1, 1e-12);
    ENSURE_NEAR(p.contacts, 2.0 / 3, 1e-12); /* one contact between three circles */
    /* a contact is a pair within 1 % of a radius of touching: 0.004 apart counts, 0.006 does not */
    double near[] = {0, 0.5, 1.004, 0.5, 2.01, 0.5};
    ts_pile_measure(near, 3, 0.5, &p);
    ENSURE(p.overlapping == 0);
    ENSURE_NEAR(p.contacts, 2.0 / 3, 1e-12);
    ts_pile_measure(NULL, 3, 0.5, &p);
    ENSURE(isnan(p.height) && isnan(p.contacts) && p.overlapping == 0);
    ts_pile_measure(xy, 3, 0, &p);
    ENSURE(isnan(p.max_overlap));
}

/* A box as a lattice keeps the rigid body's mass, centre and motion. */
TEST(scenes_tether_lattice_box_is_the_body)
{
    ts_scene s;
    ts_scene_init(&s, "one box");
    s.gravity = (tt_vec2){0, 0};
    ts_body b = ts_box(true, (tt_vec2){1, 2}, 1, 0.5, 0.3);
    b.density = 2;
    b.velocity = (tt_vec2){3, -1};
    b.spin = 2;
    ENSURE(ts_scene_add_body(&s, &b, NULL) == 0);
    ts_tether t;
    const ts_tether_settings set = ts_tether_settings_default();
    ENSURE(ts_tether_build(&s, &set, &t, NULL) == TT_OK);
    ENSURE_NEAR(t.mass, 4, 1e-12);
    ts_state st;
    ENSURE_OK(ts_tether_state(&t, 0, &st));
    ENSURE_NEAR(st.position.x, 1, 1e-12);
    ENSURE_NEAR(st.position.y, 2, 1e-12);
    ENSURE_NEAR(st.angle, 0.3, 1e-12);
    ENSURE_NEAR(st.velocity.x, 3, 1e-9);
    ENSURE_NEAR(st.velocity.y, -1, 1e-9);
    ENSURE_NEAR(st.spin, 2, 1e-9);
    ENSURE(ts_tether_state(&t, 1, &st) == TT_EINVAL);
    ts_tether_free(&t);
    ts_scene_free(&s);
}

/* The three joints, as tether builds them: a box on a ground pivot swings at
 * a fixed distance, a box welded to the ground stays, two circles on a
 * distance joint keep it, two boxes on a pivot between them stay joined. */
TEST(scenes_tether_joints_hold)
{
    ts_scene s;
    ts_scene_init(&s, "joints");
    ts_body box = ts_box(true, (tt_vec2){2, 0}, 0.25, 0.25, 0);
    ENSURE(ts_scene_add_body(&s, &box, NULL) == 0);
    ts_joint j = {TS_REVOLUTE, TS_GROUND, 0, {0, 0}, {0, 0}};
    ENSURE(ts_scene_add_joint(&s, &j, NULL) == 0);
    box.position = (tt_vec2){10, 0};
    ENSURE(ts_scene_add_body(&s, &box, NULL) == 1);
    j = (ts_joint){TS_WELD, TS_GROUND, 1, {10, 0}, {0, 0}};
    ENSURE(ts_scene_add_joint(&s, &j, NULL) == 0 + 1);
    ts_body c = ts_circle(true, (tt_vec2){20, 0}, 0.5);
    ENSURE(ts_scene_add_body(&s, &c, NULL) == 2);
    c.position = (tt_vec2){22, 0};
    ENSURE(ts_scene_add_body(&s, &c, NULL) == 3);
    j = (ts_joint){TS_DISTANCE, 2, 3, {20, 0}, {22, 0}};
    ENSURE(ts_scene_add_joint(&s, &j, NULL) == 2);
    box.position = (tt_vec2){30, 0};
    ENSURE(ts_scene_add_body(&s, &box, NULL) == 4);
    box.position = (tt_vec2){30.5, 0};
    ENSURE(ts_scene_add_body(&s, &box, NULL) == 5);
    j = (ts_joint){TS_REVOLUTE, 4, 5, {30.25, 0}, {0, 0}};
    ENSURE(ts_scene_add_joint(&s, &j, NULL) == 3);
    ts_tether t;
    const ts_tether_settings set = ts_tether_settings_default();
    ENSURE(ts_tether_build(&s, &set, &t, NULL) == TT_OK);
    for (int i = 0; i < 60; i++) ENSURE_OK(tt_world_step(t.world, s.dt));
    ts_state st[6];
    for (uint32_t i = 0; i < 6; i++) ENSURE_OK(ts_tether_state(&t, i, &st[i]));
    ENSURE(st[0].position.y < -0.5);                             /* it swung down */
    ENSURE_NEAR(hypot(st[0].position.x, st[0].position.y), 2, 0.02); /* on its arm */
    ENSURE_NEAR(st[1].position.y, 0, 0.05);                      /* the welded box hangs on */
    ENSURE_NEAR(hypot(st[3].position.x - st[2].position.x, st[3].position.y - st[2].position.y), 2, 1e-3);
    ENSURE(st[4].position.y < -4);                               /* the pair falls together */
    ENSURE_NEAR(hypot(st[5].position.x - st[4].position.x, st[5].position.y - st[4].position.y), 0.5, 0.02);
    ts_tether_free(&t);
    ts_scene_free(&s);
}

/* The lattice the benchmarks place: centres in the middle of their cells,
 * row by row, every big_every-th big. */
TEST(scenes_grid_places_particles_in_the_middle_of_their_cells)
{
    tt_world *w = tt_world_create(NULL);
    ts_grid g = ts_grid_default();
    g.count = 7;
    g.columns = 3;
    g.corner = (tt_vec2){-1, 2};
    g.spacing = 0.5;
    g.radius = 0.1;
    g.big_radius = 0.2;
    g.big_every = 4;
    ENSURE(ts_grid_add(w, &g) == 7);
    tt_particle ps[7];
    ENSURE(tt_world_list_particles(w, ps, 7) == 7);
    for (uint32_t i = 0; i < 7; i++) {
        tt_vec2 x;
        double r;
        ENSURE_OK(tt_particle_get_position(w, ps[i], &x));
        ENSURE_OK(tt_particle_get_radius(w, ps[i], &r));
        ENSURE_NEAR(x.x, -1 + 0.25 + 0.5 * (i % 3), 1e-15);
        ENSURE_NEAR(x.y, 2 + 0.25 + 0.5 * (i / 3), 1e-15);
        ENSURE_NEAR(r, i % 4 == 0 ? 0.2 : 0.1, 1e-7); /* radii are stored as floats */
    }
    g.columns = 0;
    ENSURE(ts_grid_add(w, &g) == 0);
    tt_world_destroy(w);
}

/* The U of the terrain bench, as a chain and as a mask: the same walls
 * and floor, and a small pour comes to rest on the floor in both. */
TEST(scenes_floor_as_chain_and_as_mask_holds_the_pour_alike)
{
    for (int mask = 0; mask < 2; mask++) {
        ts_tether t;
        const char *why = NULL;
        ENSURE_OK(ts_floor_build(300, 10, mask, &t, &why));
        ENSURE(t.circle_count == 300);
        for (int s = 0; s < 240; s++) ENSURE_OK(tt_world_step(t.world, 1.0 / 60));
        double lo = INFINITY, left = INFINITY, right = -INFINITY;
        for (uint32_t i = 0; i < t.circle_count; i++) {
            tt_vec2 x;
            ENSURE_OK(tt_particle_get_position(t.world, t.circles[i], &x));
            lo = fmin(lo, x.y);
            left = fmin(left, x.x);
            right = fmax(right, x.x);
        }
        ENSURE(lo > 0.5 - 0.05 && lo < 0.5 + 0.02); /* on the floor's top, y = 0 */
        ENSURE(left > -5 + 0.5 - 0.05 && right < 5 - 0.5 + 0.05);
        ENSURE(ts_tether_kinetic_per_kg(&t) < 0.05);
        ts_tether_free(&t);
    }
}

/* The bowl as a scene for Box2D is the tether bowl: the same circles bit for
 * bit, and edges that lie on the mask's surface (within a pixel, 0.1 m). */
TEST(scenes_bowl_as_edges_is_the_mask_bowl)
{
    ts_bowl b;
    ts_scene s;
    const char *why = NULL;
    ENSURE_OK(ts_bowl_build(200, 20, &b, &why));
    ENSURE(ts_scene_bowl(&s, 200, 20, 64, true, &why));
    uint32_t circles = 0, edges = 0;
    for (uint32_t i = 0; i < s.body_count; i++) {
        const ts_body *c = &s.bodies[i];
        if (c->shape == TS_CIRCLE) {
            tt_vec2 x;
            ENSURE(i == circles && c->dynamic && c->fixed_rotation && c->radius == 0.5);
            ENSURE_OK(tt_particle_get_position(b.t.world, b.t.circles[circles++], &x));
            ENSURE(x.x == c->position.x && x.y == c->position.y);
            continue;
        }
        ENSURE(c->shape == TS_EDGE && !c->dynamic);
        edges++;
        /* near both ends and halfway (a wall's top end is the mask's top row, where the terrain ends) */
        for (int k = 0; k < 3; k++) {
            const double f = k == 0 ? 0.02 : k == 1 ? 0.5 : 0.98;
            const tt_vec2 at = {c->a.x + f * (c->b.x - c->a.x), c->a.y + f * (c->b.y - c->a.y)};
            double d = 1;
            ENSURE_OK(tt_terrain_distance(b.t.world, b.terrain, at, &d, NULL));
            ENSURE(fabs(d) <= 0.1);
        }
    }
    ENSURE(circles == 200 && edges == 64 + 2);
    ts_scene_free(&s);
    ts_bowl_free(&b);
    ENSURE(!ts_scene_bowl(&s, 10, 20, 0, false, &why) && strstr(why, "edges") && s.body_count == 0);
}
