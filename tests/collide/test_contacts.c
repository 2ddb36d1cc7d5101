/* Contact response: bounce (e² rule), rest, friction on a slope (tan θ vs
 * μs), a 2000-particle pour that settles, coincident particles, filtering,
 * sensors, events and changing the world while reading them. */
#include "test.h"
#include "collide/collide_internal.h"

#include <fenv.h>
#include <stdlib.h>
#include <string.h>

static tt_shape ground(tt_world *w, double e)
{
    tt_shape_def sd = tt_shape_def_default();
    sd.type = TT_SHAPE_AABB;
    sd.a = (tt_vec2){-50, -1};
    sd.b = (tt_vec2){50, 0};
    sd.restitution = e;
    return tt_shape_create(w, &sd);
}

/* Drops a ball (bottom 1 m above the ground) and returns the top of its first rebound. */
static double rebound(tt_integrator integ, double e, uint32_t substeps)
{
    tt_world_def wd = tt_world_def_default();
    wd.integrator = integ;
    wd.substeps = substeps;
    tt_world *w = tt_world_create(&wd);
    ground(w, e);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.1;
    pd.position = (tt_vec2){0, 1.1};
    tt_particle p = tt_particle_create(w, &pd);
    tt_particle_set_material(w, p, e, 0.6, 0.5);
    double top = 0;
    bool bounced = false;
    for (int s = 0; s < 240; s++) {
        tt_world_step(w, 1.0 / 60);
        tt_vec2 x, v;
        tt_particle_get_position(w, p, &x);
        tt_particle_get_velocity(w, p, &v);
        if (v.y > 0) bounced = true;
        if (bounced && v.y < 0 && x.y - 0.1 < 0.02) break; /* second landing */
        if (bounced) top = fmax(top, x.y - 0.1);
    }
    tt_world_destroy(w);
    return top;
}

TEST(ball_rebounds_to_e_squared_of_its_height)
{
    const tt_integrator ints[] = {TT_VERLET, TT_SYMPLECTIC_EULER};
    const double es[] = {0.5, 0.8, 0.95};
    for (int k = 0; k < 2; k++)
        for (int j = 0; j < 3; j++) {
            double top = rebound(ints[k], es[j], 8);
            ENSURE_NEAR(top / (es[j] * es[j]), 1.0, 0.02);
        }
}

/* The top of the first rebound of a ball dropped from h (its bottom) at
 * the world's defaults (one substep of 1/60 s) but for the integrator and
 * substeps by speed (max_travel; 0: off):
 * the vertex of the parabola through the three samples around the
 * highest, exact for Verlet and symplectic Euler, whose samples lie on
 * the flight's parabola. */
static double rebound_at_defaults(tt_integrator integ, double e, double h, double travel)
{
    tt_world_def wd = tt_world_def_default();
    wd.integrator = integ;
    wd.max_travel = travel;
    tt_world *w = tt_world_create(&wd);
    ground(w, e);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.1;
    pd.position = (tt_vec2){0, h + 0.1};
    tt_particle p = tt_particle_create(w, &pd);
    tt_particle_set_material(w, p, e, 0.6, 0.5);
    double y[3] = {0, 0, 0}, top = -1.0;
    bool up = false;
    for (int s = 0; s < 20000 && top < 0.0; s++) {
        tt_world_step(w, 1.0 / 60);
        tt_vec2 x, v;
        tt_particle_get_position(w, p, &x);
        tt_particle_get_velocity(w, p, &v);
        y[0] = y[1];
        y[1] = y[2];
        y[2] = x.y - 0.1;
        if (v.y > 0) up = true;
        if (up && s > 2 && y[2] < y[1] && y[1] >= y[0]) {
            const double den = 2 * y[1] - y[0] - y[2];
            top = den > 0 ? y[1] + (y[2] - y[0]) * (y[2] - y[0]) / (8 * den) : y[1];
        }
    }
    tt_world_destroy(w);
    return top;
}

/* Issue 21: e² of the height within 2 % at the defaults, from 0.1 to 10 m
 * (before the bounce was placed in time, Verlet: −51 % from 0.1 m at
 * e = 0.2, the time between impact and the substep's end lost; symplectic
 * Euler −42 %), with substeps by speed on and off (symplectic Euler's
 * plain kick lost 9.6 % from 1 m at e = 0.2, its velocity jumping where
 * the substeps changed between the fall and the climb). */
TEST(ball_rebounds_to_e_squared_at_the_defaults_from_any_height)
{
    const tt_integrator ints[] = {TT_VERLET, TT_SYMPLECTIC_EULER};
    const double es[] = {0.2, 0.5, 0.8, 1.0}, hs[] = {0.1, 0.3, 1.0, 3.0, 10.0}, travel[] = {0.0, 0.5};
    for (int i = 0; i < 2; i++)
        for (int j = 0; j < 4; j++)
            for (int k = 0; k < 5; k++)
                for (int m = 0; m < 2; m++)
                    ENSURE_NEAR(rebound_at_defaults(ints[i], es[j], hs[k], travel[m]) / (es[j] * es[j] * hs[k]), 1.0, 0.02);
}

TEST(ball_with_no_restitution_comes_to_rest_on_the_ground)
{
    for (int k = 0; k < TT_INTEGRATOR_COUNT; k++) {
        tt_world_def wd = tt_world_def_default();
        wd.integrator = (tt_integrator)k;
        tt_world *w = tt_world_create(&wd);
        ground(w, 0);
        tt_particle_def pd = tt_particle_def_default();
        pd.radius = 0.25;
        pd.position = (tt_vec2){0, 2};
        tt_particle p = tt_particle_create(w, &pd);
        for (int s = 0; s < 120; s++) tt_world_step(w, 1.0 / 60);
        tt_vec2 x, v;
        tt_particle_get_position(w, p, &x);
        tt_particle_get_velocity(w, p, &v);
        ENSURE_NEAR(x.y, 0.25, 1e-9);
        ENSURE(fabs(v.x) < 1e-9 && fabs(v.y) <= 9.81 / 60 + 1e-9);
        tt_world_destroy(w);
    }
}

/* A particle on a slope of angle θ with μs = μ (shape and particle alike), from rest for 2 s. */
static double slide(tt_integrator integ, double theta, double mus, double muk, double *accel)
{
    tt_world_def wd = tt_world_def_default();
    wd.integrator = integ;
    tt_world *w = tt_world_create(&wd);
    tt_shape_def sd = tt_shape_def_default();
    sd.a = (tt_vec2){-100 * cos(theta), -100 * sin(theta)};
    sd.b = (tt_vec2){100 * cos(theta), 100 * sin(theta)};
    sd.friction_static = mus;
    sd.friction_kinetic = muk;
    tt_shape_create(w, &sd);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.5;
    pd.position = (tt_vec2){-0.5 * sin(theta), 0.5 * cos(theta)}; /* touching */
    tt_particle p = tt_particle_create(w, &pd);
    tt_particle_set_material(w, p, 0, mus, muk);
    const double T = 2.0;
    for (int s = 0; s < 120; s++) tt_world_step(w, 1.0 / 60);
    tt_vec2 x, v;
    tt_particle_get_position(w, p, &x);
    tt_particle_get_velocity(w, p, &v);
    double along = (x.x - pd.position.x) * cos(theta) + (x.y - pd.position.y) * sin(theta);
    *accel = -(v.x * cos(theta) + v.y * sin(theta)) / T; /* from the velocity: the position lags by O(h) */
    tt_world_destroy(w);
    return fabs(along);
}

TEST(particle_on_a_slope_sticks_below_the_friction_angle_and_slides_above)
{
    for (int k = 0; k < TT_INTEGRATOR_COUNT; k++) {
        tt_integrator in = (tt_integrator)k;
        double a;
        double theta = atan(0.45); /* tan θ = 0.45 < μs = 0.5 */
        double d0 = slide(in, theta, 0.5, 0.4, &a);
        ENSURE(d0 < 1e-9);
        theta = atan(0.55);        /* tan θ = 0.55 > μs = 0.5: slides at g(sin θ − μk cos θ) */
        ENSURE(slide(in, theta, 0.5, 0.4, &a) > 0.1);
        ENSURE_NEAR(a / (9.81 * (sin(theta) - 0.4 * cos(theta))), 1.0, 0.03);
        theta = atan(0.3);         /* frictionless: g sin θ */
        slide(in, theta, 0, 0, &a);
        ENSURE_NEAR(a / (9.81 * sin(theta)), 1.0, 0.03);
    }
}

/* 2000 particles (r = 0.5) poured into a 40-wide box: 8 substeps, 8
 * iterations, as docs/collisions.md recommends for deep piles (the deepest
 * overlap measured is 0.0035, two thirds of the 1 % limit; at 8 × 6 it is
 * 0.0046, and has reached 0.0052 as the solve order changed). 10 s simulated at 60 Hz (600 steps): about 2.5 s here. */
TEST(two_thousand_particles_poured_into_a_box_settle)
{
    if (getenv("TT_MEMCHECK")) return; /* 8 × 8 on 2 000: the longest C test, minutes under valgrind; smaller pours cover its code */
    tt_world_def wd = tt_world_def_default();
    wd.substeps = 8;
    wd.iterations = 8;
    tt_world *w = tt_world_create(&wd);
    tt_collision_settings cs = tt_collision_settings_default();
    tt_world_set_collision(w, &cs);
    const double W = 20, r = 0.5;
    tt_shape_def sd = tt_shape_def_default();
    sd.type = TT_SHAPE_AABB;
    sd.a = (tt_vec2){-W - 1, -1}; sd.b = (tt_vec2){W + 1, 0};   tt_shape_create(w, &sd); /* floor */
    sd.a = (tt_vec2){-W - 1, 0}; sd.b = (tt_vec2){-W, 200};    tt_shape_create(w, &sd); /* walls */
    sd.a = (tt_vec2){W, 0}; sd.b = (tt_vec2){W + 1, 200};      tt_shape_create(w, &sd);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = r;
    uint64_t s = 12345;
    for (int i = 0; i < 2000; i++) { /* a loose column, jittered */
        s = s * 6364136223846793005ull + 1442695040888963407ull;
        double j = (double)(s >> 11) / 9007199254740992.0 - 0.5;
        pd.position = (tt_vec2){-15 + (i % 25) * 1.25 + 0.1 * j, 2 + (i / 25) * 1.25};
        tt_particle_create(w, &pd);
    }
    for (int k = 0; k < 600; k++) tt_world_step(w, 1.0 / 60);
    uint32_t n = tt_world_particle_count(w);
    double *xy = malloc(2 * n * sizeof *xy);
    tt_world_read_positions(w, xy, n);
    double deepest = 0, top = 0;
    for (uint32_t i = 0; i < n; i++) {
        ENSURE(xy[2 * i] >= -W + r - 1e-3 && xy[2 * i] <= W - r + 1e-3 && xy[2 * i + 1] >= r - 1e-3);
        top = fmax(top, xy[2 * i + 1]);
        for (uint32_t j = i + 1; j < n; j++) {
            double dx = xy[2 * i] - xy[2 * j], dy = xy[2 * i + 1] - xy[2 * j + 1];
            if (dx * dx + dy * dy < 4 * r * r) deepest = fmax(deepest, 2 * r - sqrt(dx * dx + dy * dy));
        }
    }
    ENSURE(deepest <= 0.01 * r);
    ENSURE(top < 2000.0 / 40 * 1.0 + 5); /* it is a pile, not a cloud */
    tt_energy e;
    tt_world_get_energy(w, &e);
    ENSURE(e.kinetic / n < 0.01); /* settled: under 1 cJ per particle */
    free(xy);
    tt_world_destroy(w);
}

/* Overlaps are removed by moving positions, not by throwing: a particle
 * 0.15 m into the floor, or into another particle, leaves the step out of
 * the overlap and without the speed of the push (0.15 m in 1/60 s would be
 * 9 m/s). Deep piles at one substep boiled from exactly this: each layer
 * thrown up by the overlap it was pushed out of. A shape moved by the
 * script into a particle does throw it (a paddle hits a ball). */
static tt_world *overlap_world(tt_integrator in, tt_vec2 g)
{
    tt_world_def wd = tt_world_def_default();
    wd.integrator = in;
    wd.gravity = g;
    tt_world *w = tt_world_create(&wd);
    tt_collision_settings cs = tt_collision_settings_default();
    tt_world_set_collision(w, &cs);
    return w;
}

TEST(a_push_out_of_an_overlap_gives_no_speed_but_a_moving_shape_throws)
{
    for (int k = 0; k < TT_INTEGRATOR_COUNT; k++) {
        tt_integrator in = (tt_integrator)k;
        /* into the floor, at rest */
        tt_world *w = overlap_world(in, (tt_vec2){0, -9.81});
        tt_shape_def sd = tt_shape_def_default();
        sd.type = TT_SHAPE_AABB;
        sd.a = (tt_vec2){-10, -1};
        sd.b = (tt_vec2){10, 0};
        tt_shape floor = tt_shape_create(w, &sd);
        tt_particle_def pd = tt_particle_def_default();
        pd.radius = 0.5;
        pd.position = (tt_vec2){0, 0.35};
        tt_particle p = tt_particle_create(w, &pd);
        tt_world_step(w, 1.0 / 60);
        tt_vec2 x, v;
        tt_particle_get_position(w, p, &x);
        tt_particle_get_velocity(w, p, &v);
        ENSURE(x.y >= 0.5 - 1e-9);
        ENSURE(fabs(v.y) < 0.5);
        /* the floor moved up into it by 0.15 m: thrown at about 0.15·60 = 9 m/s */
        for (int s = 0; s < 30; s++) tt_world_step(w, 1.0 / 60);
        tt_shape_set_transform(w, floor, (tt_vec2){0, 0.15}, 0);
        tt_world_step(w, 1.0 / 60);
        tt_particle_get_velocity(w, p, &v);
        ENSURE(v.y > 4.0);
        tt_world_destroy(w);
        /* two particles 0.3 m into each other, no gravity */
        w = overlap_world(in, (tt_vec2){0, 0});
        pd.position = (tt_vec2){0, 0};
        tt_particle a = tt_particle_create(w, &pd);
        pd.position = (tt_vec2){0.7, 0};
        tt_particle b = tt_particle_create(w, &pd);
        tt_world_step(w, 1.0 / 60);
        tt_vec2 xa, xb, va, vb;
        tt_particle_get_position(w, a, &xa);
        tt_particle_get_position(w, b, &xb);
        tt_particle_get_velocity(w, a, &va);
        tt_particle_get_velocity(w, b, &vb);
        ENSURE(xb.x - xa.x >= 1.0 - 1e-9);
        ENSURE(fabs(vb.x - va.x) < 0.5);
        tt_world_destroy(w);
    }
}

TEST(coincident_particles_separate_without_nan)
{
    for (int order = 0; order < 2; order++) {
        tt_world_def wd = tt_world_def_default();
        wd.gravity = (tt_vec2){0, 0};
        wd.order = (tt_solver_order)order;
        tt_world *w = tt_world_create(&wd);
        tt_collision_settings cs = tt_collision_settings_default();
        tt_world_set_collision(w, &cs);
        tt_particle_def pd = tt_particle_def_default();
        pd.radius = 0.5;
        pd.position = (tt_vec2){3, 4};
        tt_particle p[5];
        for (int i = 0; i < 5; i++) p[i] = tt_particle_create(w, &pd);
        for (int s = 0; s < 60; s++) tt_world_step(w, 1.0 / 60);
        for (int i = 0; i < 5; i++) {
            tt_vec2 a, v;
            tt_particle_get_position(w, p[i], &a);
            tt_particle_get_velocity(w, p[i], &v);
            ENSURE(isfinite(a.x) && isfinite(a.y) && isfinite(v.x) && isfinite(v.y));
            for (int j = i + 1; j < 5; j++) {
                tt_vec2 b;
                tt_particle_get_position(w, p[j], &b);
                ENSURE(hypot(a.x - b.x, a.y - b.y) >= 1.0 - 0.01);
            }
        }
        tt_world_destroy(w);
    }
}

/* Two overlapping particles, no gravity: the distance after one step. */
static double apart(bool exclude, uint16_t mask_b)
{
    tt_world_def wd = tt_world_def_default();
    wd.gravity = (tt_vec2){0, 0};
    tt_world *w = tt_world_create(&wd);
    tt_collision_settings cs = tt_collision_settings_default();
    tt_world_set_collision(w, &cs);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.5;
    tt_particle a = tt_particle_create(w, &pd);
    pd.position.x = 0.5;
    pd.mask = mask_b;
    tt_particle b = tt_particle_create(w, &pd);
    if (exclude) tt_world_set_pair_collision(w, a, b, false);
    tt_world_step(w, 1.0 / 60);
    tt_vec2 xa, xb;
    tt_particle_get_position(w, a, &xa);
    tt_particle_get_position(w, b, &xb);
    tt_world_destroy(w);
    return xb.x - xa.x;
}

TEST(layers_masks_and_pair_exclusion_filter_contacts)
{
    ENSURE_NEAR(apart(false, 0xFFFF), 1.0, 1e-12);
    ENSURE_NEAR(apart(true, 0xFFFF), 0.5, 1e-12);
    ENSURE_NEAR(apart(false, 0x0002), 0.5, 1e-12);
}

TEST(sensors_report_overlaps_and_do_not_push)
{
    tt_world *w = tt_world_create(NULL);
    tt_collision_settings cs = tt_collision_settings_default();
    cs.events = TT_EVENT_BEGIN | TT_EVENT_END | TT_EVENT_PERSIST;
    tt_world_set_collision(w, &cs);
    tt_shape_def sd = tt_shape_def_default();
    sd.type = TT_SHAPE_AABB;
    sd.a = (tt_vec2){-1, -1};
    sd.b = (tt_vec2){1, 1};
    sd.sensor = true;
    tt_shape sensor = tt_shape_create(w, &sd);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.1;
    pd.position = (tt_vec2){0, 1.5};
    tt_particle p = tt_particle_create(w, &pd);
    int begins = 0, ends = 0, persists = 0;
    for (int s = 0; s < 60; s++) {
        tt_world_step(w, 1.0 / 60);
        uint32_t n;
        const tt_contact_event *ev = tt_world_get_contact_events(w, &n);
        for (uint32_t k = 0; k < n; k++) {
            ENSURE(ev[k].sensor && ev[k].shape.index == sensor.index && ev[k].a.index == p.index);
            begins += ev[k].kind == TT_EVENT_BEGIN;
            ends += ev[k].kind == TT_EVENT_END;
            persists += ev[k].kind == TT_EVENT_PERSIST;
        }
    }
    tt_vec2 x;
    tt_particle_get_position(w, p, &x);
    ENSURE(x.y < -3.0); /* fell through it: 1 s of free fall from 1.5 m */
    ENSURE(begins == 1 && ends == 1 && persists > 5);
    tt_world_destroy(w);
}

TEST(contact_events_begin_persist_end_with_impulse)
{
    tt_world *w = tt_world_create(NULL);
    tt_collision_settings cs = tt_collision_settings_default();
    cs.events = TT_EVENT_BEGIN | TT_EVENT_PERSIST | TT_EVENT_END;
    tt_world_set_collision(w, &cs);
    tt_shape g = ground(w, 0);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.5;
    pd.mass = 2;
    pd.position = (tt_vec2){0, 0.5 + 0.5 * 9.81 * 0.25}; /* lands after about 0.5 s at 4.9 m/s */
    tt_particle p = tt_particle_create(w, &pd);
    int begin_step = -1, end_step = -1;
    double impulse = 0;
    for (int s = 0; s < 90; s++) {
        if (s == 60) tt_particle_set_position(w, p, (tt_vec2){0, 5}, TT_MOVE_RESET_VELOCITY); /* lifted away */
        tt_world_step(w, 1.0 / 60);
        uint32_t n;
        const tt_contact_event *ev = tt_world_get_contact_events(w, &n);
        for (uint32_t k = 0; k < n; k++) {
            ENSURE(ev[k].shape.index == g.index && ev[k].b.gen == 0 && !ev[k].sensor);
            if (ev[k].kind == TT_EVENT_BEGIN) {
                ENSURE(begin_step < 0);
                begin_step = s;
                impulse = ev[k].impulse;
                ENSURE_NEAR(ev[k].normal.y, 1, 1e-9);
                ENSURE_NEAR(ev[k].point.y, 0, 0.1);
            }
            if (ev[k].kind == TT_EVENT_END) end_step = s;
        }
    }
    ENSURE(begin_step >= 28 && begin_step <= 32);
    ENSURE_NEAR(impulse, 2 * 9.81 * 0.5, 0.1 * 2 * 9.81 * 0.5); /* m·v at impact, e = 0 */
    ENSURE(end_step == 60);
    tt_world_destroy(w);
}

/* The test other engines fail: remove and move bodies (and shapes) while handling events. */
TEST(removing_and_moving_things_while_reading_events_is_safe)
{
    tt_world *w = tt_world_create(NULL);
    tt_collision_settings cs = tt_collision_settings_default();
    cs.events = TT_EVENT_BEGIN | TT_EVENT_PERSIST | TT_EVENT_END;
    tt_world_set_collision(w, &cs);
    ground(w, 0.3);
    tt_shape pegs[20];
    tt_shape_def sd = tt_shape_def_default();
    sd.type = TT_SHAPE_CIRCLE;
    sd.radius = 0.3;
    for (int k = 0; k < 20; k++) {
        sd.position = (tt_vec2){-10 + k, 3 + (k % 3)};
        pegs[k] = tt_shape_create(w, &sd);
    }
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.4;
    for (int i = 0; i < 300; i++) {
        pd.position = (tt_vec2){-10 + (i % 20) * 1.0 + 0.3, 6 + (i / 20) * 1.0};
        tt_particle_create(w, &pd);
    }
    int removed = 0, moved = 0, shapes_removed = 0, stale_seen = 0, events = 0;
    for (int s = 0; s < 240; s++) {
        tt_world_step(w, 1.0 / 60);
        uint32_t n;
        const tt_contact_event *ev = tt_world_get_contact_events(w, &n);
        for (uint32_t k = 0; k < n; k++) {
            events++;
            if (!tt_particle_is_valid(w, ev[k].a)) { stale_seen++; continue; }
            if (ev[k].kind == TT_EVENT_BEGIN && (k % 3) == 0) {
                ENSURE_OK(tt_particle_destroy(w, ev[k].a)); /* destroyed inside "the callback" */
                removed++;
                if (ev[k].b.gen && tt_particle_is_valid(w, ev[k].b)) {
                    ENSURE_OK(tt_particle_set_position(w, ev[k].b, (tt_vec2){0, 20}, TT_MOVE_RESET_VELOCITY));
                    moved++;
                }
                pd.position = (tt_vec2){(k % 7) - 3.0, 15};
                tt_particle_create(w, &pd); /* and a new one made */
            } else if (ev[k].kind == TT_EVENT_PERSIST && ev[k].shape.gen && tt_shape_is_valid(w, ev[k].shape) &&
                       ev[k].shape.index != 0 && shapes_removed < 10) {
                ENSURE_OK(tt_shape_destroy(w, ev[k].shape));
                shapes_removed++;
            }
        }
    }
    ENSURE(removed > 50 && moved > 5 && shapes_removed == 10 && events > 500);
    ENSURE(stale_seen > 0); /* handles in the array went stale, and said so */
    tt_stats st;
    tt_world_get_stats(w, &st);
    ENSURE(st.diverged == 0);
    (void)pegs;
    tt_world_destroy(w);
}

TEST(collision_runs_are_deterministic)
{
    uint64_t h[2];
    for (int run = 0; run < 2; run++) {
        tt_world *w = tt_world_create(NULL);
        tt_collision_settings cs = tt_collision_settings_default();
        cs.restitution = 0.3;
        tt_world_set_collision(w, &cs);
        ground(w, 0.2);
        tt_particle_def pd = tt_particle_def_default();
        for (int i = 0; i < 200; i++) {
            pd.radius = 0.2 + 0.1 * (i % 4);
            pd.position = (tt_vec2){(i % 17) * 0.9 - 8, 1 + (i / 17) * 0.9};
            tt_particle_create(w, &pd);
        }
        for (int s = 0; s < 120; s++) tt_world_step(w, 1.0 / 60);
        h[run] = tt_world_hash(w);
        tt_world_destroy(w);
    }
    ENSURE(h[0] == h[1]);
}

TEST(collision_api_refuses_bad_input)
{
    tt_world *w = tt_world_create(NULL);
    tt_collision_settings cs = tt_collision_settings_default();
    cs.cell_size = -1;
    ENSURE(tt_world_set_collision(w, &cs) == TT_EINVAL);
    ENSURE(strstr(tt_last_error(w), "cell_size") != NULL);
    cs = tt_collision_settings_default();
    cs.friction_static = NAN;
    ENSURE(tt_world_set_collision(w, &cs) == TT_EINVAL);
    cs = tt_collision_settings_default();
    cs.events = 64;
    ENSURE(tt_world_set_collision(w, &cs) == TT_EINVAL);
    tt_particle_def pd = tt_particle_def_default();
    tt_particle p = tt_particle_create(w, &pd);
    ENSURE(tt_particle_set_material(w, p, 2, 0, 0) == TT_EINVAL);
    ENSURE(tt_world_set_pair_collision(w, p, p, false) == TT_EINVAL);
    tt_particle_destroy(w, p);
    ENSURE(tt_particle_set_bullet(w, p, true) == TT_ESTALE);
    tt_shape none = {5, 1};
    ENSURE(tt_shape_destroy(w, none) == TT_ESTALE);
    ENSURE(tt_world_raycast(w, (tt_vec2){0, 0}, (tt_vec2){INFINITY, 0}, 0xFFFF, &(tt_ray_hit){0}) == TT_EINVAL);
    tt_world_destroy(w);
}

/* ---- pair contacts in vector lanes against the scalar loop --------------- */

/* A pile that reaches every branch of the batched pair sweep and velocity
 * pass (bounce, no approach, stick, slide): radii 0.2 to
 * 0.6, a pinned row (pairs of two pinned particles are left out, a pinned
 * and a free one are solved), a pinned particle at x = −0, pairs on one
 * centre (the batch goes to the scalar code), particles removed and added
 * while it settles; with materials, most particles have their own (some
 * frictionless: lanes that skip friction beside lanes that do). Returns the
 * world hash folded with every step's largest error; *pairs: pair contacts
 * in the last substep. */
static uint64_t batch_scene(tt__simd_mode mode, bool materials, uint32_t *pairs)
{
    tt_world_def wd = tt_world_def_default();
    wd.iterations = 6;
    wd.substeps = 2;
    wd.tolerance = 0;
    tt_world *w = tt_world_create(&wd);
    if (!tt__contacts_set_simd(w, mode)) {
        tt_world_destroy(w);
        return 0;
    }
    tt_collision_settings cs = tt_collision_settings_default();
    cs.restitution = 0.3; /* impacts bounce, contacts stick and slide */
    tt_world_set_collision(w, &cs);
    tt_shape_def sd = tt_shape_def_default();
    sd.type = TT_SHAPE_AABB;
    sd.a = (tt_vec2){-11, -1}; sd.b = (tt_vec2){11, 0};   tt_shape_create(w, &sd);
    sd.a = (tt_vec2){-11, 0}; sd.b = (tt_vec2){-10, 60};  tt_shape_create(w, &sd);
    sd.a = (tt_vec2){10, 0}; sd.b = (tt_vec2){11, 60};    tt_shape_create(w, &sd);
    tt_particle_def pd = tt_particle_def_default();
    /* first, pinned at x = −0, with free ones east and north of it just out of touch (pairs
     * in which it comes first, no overlap): a lane that leaves a particle where it was must
     * leave the sign of its zero */
    pd.radius = 0.3;
    pd.pinned = true;
    pd.position = (tt_vec2){-0.0, 100.0};
    tt_particle_create(w, &pd);
    pd.pinned = false;
    pd.position = (tt_vec2){0.63, 100.0};
    tt_particle_create(w, &pd);
    pd.position = (tt_vec2){0.0, 100.63};
    tt_particle_create(w, &pd);
    tt_particle ps[900];
    uint64_t r = 99;
    for (int i = 0; i < 900; i++) {
        r = r * 6364136223846793005ull + 1442695040888963407ull;
        pd.radius = 0.2 + 0.4 * (double)(r >> 11) / 9007199254740992.0;
        pd.position = (tt_vec2){-9.5 + (i % 30) * 0.65, 0.6 + (i / 30) * 0.9};
        pd.pinned = i < 30; /* the bottom row */
        pd.mass = 1.0 + (i % 3);
        ps[i] = tt_particle_create(w, &pd);
        /* materials: each its own, some frictionless, some left at the world's */
        if (materials && i % 5 != 4)
            tt_particle_set_material(w, ps[i], (i % 7) * 0.15, i % 5 == 0 ? 0.0 : 0.1 * (i % 9), i % 5 == 0 ? 0.0 : 0.05 * (i % 9));
    }
    pd.pinned = false;
    pd.mass = 1.0;
    pd.radius = 0.4;
    for (int j = 0; j < 6; j++) { /* three pairs on one centre */
        pd.position = (tt_vec2){-6.0 + 4.0 * (j / 2), 30.0};
        tt_particle_create(w, &pd);
    }
    uint64_t h = 1469598103934665603ull;
    for (int s = 0; s < 120; s++) {
        if (s == 40)
            for (int i = 100; i < 900; i += 37) tt_particle_destroy(w, ps[i]);
        if (s == 60)
            for (int j = 0; j < 10; j++) {
                pd.position = (tt_vec2){-5.0 + j, 40.0};
                tt_particle_create(w, &pd);
            }
        tt_world_step(w, 1.0 / 60);
        tt_stats st;
        tt_world_get_stats(w, &st);
        for (size_t k = 0; k < sizeof st.max_error; k++) h = (h ^ ((const uint8_t *)&st.max_error)[k]) * 1099511628211ull;
    }
    tt_collision_stats cst;
    tt_world_get_collision_stats(w, &cst);
    *pairs = cst.pair_contacts;
    h ^= tt_world_hash(w);
    tt_world_destroy(w);
    return h;
}

/* Also the floating-point exceptions: the lanes must raise none the scalar
 * code does not (a review found divisions by zero in idle lanes, which
 * crash a program that traps them). */
TEST(batched_pair_contacts_in_vector_lanes_are_bit_identical_to_the_scalar_code)
{
    uint32_t pairs, pm;
    const int traps = FE_DIVBYZERO | FE_INVALID | FE_OVERFLOW;
    feclearexcept(FE_ALL_EXCEPT);
    for (int mat = 0; mat < 2; mat++) { /* the world's materials, then each particle its own */
        feclearexcept(FE_ALL_EXCEPT);
        const uint64_t ref = batch_scene(TT__SIMD_SCALAR, mat, &pairs);
        const int raised = fetestexcept(traps);
        ENSURE(ref != 0);
        ENSURE(pairs > 1000); /* a pile, not a cloud */
        const tt__simd_mode modes[] = {TT__SIMD_AUTO, TT__SIMD_AVX2, TT__SIMD_AVX512};
        for (int m = 0; m < 3; m++) {
            feclearexcept(FE_ALL_EXCEPT);
            const uint64_t hm = batch_scene(modes[m], mat, &pm);
            if (hm == 0) continue; /* not in this build or on this processor */
            ENSURE(hm == ref);
            ENSURE(fetestexcept(traps) == raised);
        }
    }
}

/* Found by the sanitizer build in the Galton demo: a world sweeping more than
 * once with collisions on and no particle yet planned its batches from a
 * stamp array never allocated. */
TEST(a_colliding_world_with_no_particles_or_pairs_steps)
{
    tt_world_def wd = tt_world_def_default();
    wd.iterations = 4;
    tt_world *w = tt_world_create(&wd);
    tt_collision_settings cs = tt_collision_settings_default();
    ENSURE(tt_world_set_collision(w, &cs) == TT_OK);
    ground(w, 0.0);
    for (int s = 0; s < 3; s++) ENSURE(tt_world_step(w, 1.0 / 60) == TT_OK);
    tt_particle_def pd = tt_particle_def_default();
    pd.position = (tt_vec2){0, 3};
    tt_particle p = tt_particle_create(w, &pd); /* one particle: no pair */
    for (int s = 0; s < 3; s++) ENSURE(tt_world_step(w, 1.0 / 60) == TT_OK);
    tt_vec2 x;
    tt_particle_get_position(w, p, &x);
    ENSURE(x.y < 3 && x.y > 0);
    tt_world_destroy(w);
}

/* A light particle and a heavy one spawned almost on its centre: the push-out
 * drives the light one toward a shape (sd, plus `floor` when its type is not
 * 0), further than its own size. Returns the light one's largest coordinate
 * along `toward` over 30 steps, to compare with where it must stop. */
static double pushed(tt_integrator in, const tt_shape_def *sd, const tt_shape_def *floor, double rl, tt_vec2 xl, double rh,
                     tt_vec2 xh, tt_vec2 toward)
{
    tt_world_def wd = tt_world_def_default();
    wd.integrator = in;
    wd.gravity = (tt_vec2){0, 0};
    wd.iterations = 4;
    tt_world *w = tt_world_create(&wd);
    tt_collision_settings cs = tt_collision_settings_default();
    tt_world_set_collision(w, &cs);
    tt_shape_create(w, sd);
    if (floor) tt_shape_create(w, floor);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = rl;
    pd.position = xl;
    tt_particle light = tt_particle_create(w, &pd);
    pd.radius = rh;
    pd.position = xh;
    pd.mass = 1e4;
    tt_particle_create(w, &pd);
    double most = -INFINITY;
    for (int s = 0; s < 30; s++) {
        tt_world_step(w, 1.0 / 60);
        tt_vec2 x;
        tt_particle_get_position(w, light, &x);
        most = fmax(most, isfinite(x.x) && isfinite(x.y) ? x.x * toward.x + x.y * toward.y : INFINITY);
    }
    tt_world_destroy(w);
    return most;
}

/* Found in the Galton demo: balls spawned into each other were pushed by
 * the pair projection through a slanted segment wall. Then by a review: a
 * particle touching a thin wall pushed more than its diameter across it, a
 * contact with a floor exempting a particle from the check against a wall,
 * and a push past the middle of a thick shape sending it out the far side.
 * The solver must stop the light particle on its side, every integrator. */
TEST(a_push_out_never_carries_a_particle_through_a_shape)
{
    tt_shape_def wall = tt_shape_def_default(); /* a segment at x = 0 */
    wall.type = TT_SHAPE_SEGMENT;
    wall.a = (tt_vec2){0, -5};
    wall.b = (tt_vec2){0, 5};
    tt_shape_def floor = tt_shape_def_default(); /* a segment under the light particle, touching it */
    floor.type = TT_SHAPE_SEGMENT;
    floor.a = (tt_vec2){-5, -0.5};
    floor.b = (tt_vec2){-0.3, -0.5};
    tt_shape_def capsule = tt_shape_def_default(), slab = tt_shape_def_default(); /* both span y in [-0.3, 0.3] */
    capsule.type = TT_SHAPE_CAPSULE;
    capsule.a = (tt_vec2){-3, 0};
    capsule.b = (tt_vec2){3, 0};
    capsule.radius = 0.3;
    slab.type = TT_SHAPE_AABB;
    slab.a = (tt_vec2){-3, -0.3};
    slab.b = (tt_vec2){3, 0.3};
    const tt_vec2 right = {1, 0}, down = {0, -1};
    for (int k = 0; k < TT_INTEGRATOR_COUNT; k++) {
        const tt_integrator in = (tt_integrator)k;
        /* 0.1 m from the wall, outside the contact margin */
        ENSURE(pushed(in, &wall, NULL, 0.5, (tt_vec2){-0.6, 0}, 0.5, (tt_vec2){-0.65, 0}, right) <= -0.5 + 1e-6);
        /* touching it, pushed 0.55 m: more than its diameter */
        ENSURE(pushed(in, &wall, NULL, 0.1, (tt_vec2){-0.1, 0}, 0.5, (tt_vec2){-0.15, 0}, right) <= -0.1 + 1e-6);
        /* the first, resting on a floor too */
        ENSURE(pushed(in, &wall, &floor, 0.5, (tt_vec2){-0.6, 0}, 0.5, (tt_vec2){-0.65, 0}, right) <= -0.5 + 1e-6);
        /* resting on a thick shape, pushed past its middle */
        ENSURE(pushed(in, &capsule, NULL, 0.1, (tt_vec2){0, 0.4}, 1.0, (tt_vec2){0, 0.9}, down) <= -0.4 + 1e-6);
        ENSURE(pushed(in, &slab, NULL, 0.1, (tt_vec2){0, 0.4}, 1.0, (tt_vec2){0, 0.9}, down) <= -0.4 + 1e-6);
    }
}

/* A particle falling from far above a floor: while no particle can reach a
 * shape, the contacts skip their per-particle work; the landing must be
 * the one a world without that shortcut makes (collisions between
 * particles on turn it off), bit for bit, whatever the integrator. */
TEST(shapes_out_of_reach_cost_nothing_and_change_nothing)
{
    for (int k = 0; k < TT_INTEGRATOR_COUNT; k++) {
        tt_vec2 end[2];
        for (int pairs = 0; pairs < 2; pairs++) {
            tt_world_def wd = tt_world_def_default();
            wd.integrator = (tt_integrator)k;
            tt_world *w = tt_world_create(&wd);
            if (pairs) {
                tt_collision_settings cs = tt_collision_settings_default();
                tt_world_set_collision(w, &cs);
            }
            tt_shape_def sd = tt_shape_def_default();
            sd.type = TT_SHAPE_AABB;
            sd.a = (tt_vec2){-10, -1};
            sd.b = (tt_vec2){10, 0};
            tt_shape_create(w, &sd);
            tt_particle_def pd = tt_particle_def_default();
            pd.radius = 0.5;
            pd.position = (tt_vec2){0.3, 50};
            pd.velocity = (tt_vec2){2, 0};
            tt_particle p = tt_particle_create(w, &pd);
            for (int s = 0; s < 300; s++) tt_world_step(w, 1.0 / 60);
            tt_particle_get_position(w, p, &end[pairs]);
            tt_world_destroy(w);
        }
        ENSURE(end[0].y >= 0.5 - 1e-9 && end[0].y < 0.51); /* landed, resting on the floor */
        ENSURE(memcmp(&end[0], &end[1], sizeof end[0]) == 0);
    }
}

/* The reach test keeps the largest radius from one step to the next
 * (contact_reach.c): a particle grown between steps must still meet the
 * floor it now overlaps, and be pushed out at once. */
TEST(a_particle_grown_between_steps_meets_the_shape_it_now_reaches)
{
    tt_world_def d = tt_world_def_default();
    d.gravity = (tt_vec2){0, 0};
    tt_world *w = tt_world_create(&d);
    tt_shape_def sd = tt_shape_def_default();
    sd.a = (tt_vec2){-10, 0};
    sd.b = (tt_vec2){10, 0};
    ENSURE(tt_shape_is_valid(w, tt_shape_create(w, &sd)));
    tt_particle_def pd = tt_particle_def_default();
    pd.position = (tt_vec2){0, 1};
    pd.radius = 0.1;
    tt_particle p = tt_particle_create(w, &pd);
    for (int s = 0; s < 5; s++) ENSURE_OK(tt_world_step(w, 1.0 / 60)); /* out of reach: nothing moves */
    tt_vec2 x;
    tt_particle_get_position(w, p, &x);
    ENSURE(x.y == 1.0);
    ENSURE_OK(tt_particle_set_radius(w, p, 1.5));
    ENSURE_OK(tt_world_step(w, 1.0 / 60));
    tt_particle_get_position(w, p, &x);
    ENSURE_NEAR(x.y, 1.5, 1e-9);
    tt_world_destroy(w);
}
