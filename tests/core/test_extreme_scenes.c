/* Stability at the extremes, on whole scenes (collisions and constraints
 * on): steps from 1e-5 to 0.1 s, compliance from soft to rigid, mass ratios
 * of 1:10 000 on a link and in a stack, a chain of 1 000 links, 1e4 m/s into
 * a thin wall, coordinates near 1e6 and 1e9 m, and degenerate input (a
 * million steps of an undamped oscillator: test_extremes.c). Each case asserts what must
 * survive (no NaN, no energy made, errors under a stated bound) at the
 * settings named; it prints what it measured at the others, which the
 * README's table quotes ("extremes:" lines of `make test`). */
#include "test.h"
#include "tether.h"

#include <float.h>
#include <stdlib.h>

/* What a run did, over every step of it. */
typedef struct run {
    bool finite;        /* every position and the energy stayed finite */
    double energy_gain; /* largest total energy over the initial one, minus 1 (≤ 0: none made) */
    double overlap;     /* largest overlap of two particles, or of one with the floor y = 0, ÷ radius */
    double stretch;     /* largest relative error of a watched link, |len − rest| / rest */
} run;

typedef struct scene {
    tt_world *w;
    double radius;           /* of every colliding particle; 0: no overlap measured */
    bool floor;              /* an aabb floor under y = 0 */
    tt_particle link[2];     /* a link watched for stretch (null: none) */
    double rest;
} scene;

static tt_world *world(tt_integrator in, uint32_t substeps, uint32_t iterations, tt_vec2 g)
{
    tt_world_def d = tt_world_def_default();
    d.integrator = in;
    d.substeps = substeps;
    d.iterations = iterations;
    d.gravity = g;
    return tt_world_create(&d);
}

static tt_particle ball(tt_world *w, double x, double y, double r, double mass)
{
    tt_particle_def d = tt_particle_def_default();
    d.position = (tt_vec2){x, y};
    d.radius = r;
    d.mass = mass;
    return tt_particle_create(w, &d);
}

static void floor_at(tt_world *w, double x0, double x1, double y)
{
    tt_shape_def d = tt_shape_def_default();
    d.type = TT_SHAPE_AABB;
    d.a = (tt_vec2){x0, y - 1};
    d.b = (tt_vec2){x1, y};
    tt_shape_create(w, &d);
}

static void measure(const scene *s, run *r, double e0)
{
    uint32_t n = tt_world_particle_count(s->w);
    double *xy = malloc(2 * (size_t)n * sizeof *xy + 1);
    tt_world_read_positions(s->w, xy, n);
    for (uint32_t i = 0; i < 2 * n; i++)
        if (!isfinite(xy[i])) r->finite = false;
    if (s->radius > 0) {
        for (uint32_t i = 0; i < n; i++) {
            if (s->floor) r->overlap = fmax(r->overlap, (s->radius - xy[2 * i + 1]) / s->radius);
            for (uint32_t j = i + 1; j < n; j++) {
                double d = hypot(xy[2 * i] - xy[2 * j], xy[2 * i + 1] - xy[2 * j + 1]);
                r->overlap = fmax(r->overlap, (2 * s->radius - d) / s->radius);
            }
        }
    }
    free(xy);
    if (s->link[0].gen) {
        tt_vec2 a, b;
        tt_particle_get_position(s->w, s->link[0], &a);
        tt_particle_get_position(s->w, s->link[1], &b);
        r->stretch = fmax(r->stretch, fabs(hypot(a.x - b.x, a.y - b.y) - s->rest) / s->rest);
    }
    tt_energy e;
    tt_world_get_energy(s->w, &e);
    if (!isfinite(e.total)) r->finite = false;
    r->energy_gain = fmax(r->energy_gain, (e.total - e0) / fabs(e0));
}

/* Steps s for `seconds` at dt, measuring after every step. */
static run simulate(const scene *s, double dt, double seconds)
{
    run r = {true, -INFINITY, 0, 0};
    tt_energy e0;
    tt_world_get_energy(s->w, &e0);
    long steps = lround(seconds / dt);
    for (long k = 0; k < steps; k++) {
        tt_world_step(s->w, dt);
        measure(s, &r, e0.total);
    }
    return r;
}

/* --- steps from 1e-5 to 0.1 s ------------------------------------------------ */

/* Twelve balls dropped in two rows just above a floor (they land within
 * 0.1 s), a rope of 10 links swinging down from a pin beside them:
 * collisions, constraints and gravity at once. */
static scene drop_scene(tt_integrator in)
{
    scene s = {world(in, 1, 8, (tt_vec2){0, -10}), 0.25, true, {{0, 0}, {0, 0}}, 0.0};
    tt_collision_settings cs = tt_collision_settings_default();
    tt_world_set_collision(s.w, &cs);
    floor_at(s.w, -20, 20, 0);
    for (int i = 0; i < 12; i++) ball(s.w, -3 + (i % 6) * 0.51 + 0.25 * (i / 6), 0.3 + 0.55 * (i / 6), 0.25, 1);
    tt_rope_def rd = tt_rope_def_default();
    rd.start = (tt_vec2){8, 6};
    rd.finish = (tt_vec2){13, 6};
    rd.segments = 10;
    tt_composite rope = tt_rope_create(s.w, &rd);
    tt_particle ps[11];
    uint32_t n = 0;
    tt_composite_get_particles(s.w, rope, ps, 11, &n);
    s.link[0] = ps[0];
    s.link[1] = ps[1];
    s.rest = 0.5;
    return s;
}

TEST(extremes_steps_from_1e5_to_a_tenth_of_a_second)
{
    const double dts[] = {1e-5, 1e-4, 1e-3, 1.0 / 60, 0.05, 0.1};
    for (int in = 0; in < TT_INTEGRATOR_COUNT; in++)
        for (int k = 0; k < 6; k++) {
            scene s = drop_scene((tt_integrator)in);
            run r = simulate(&s, dts[k], dts[k] < 1e-4 ? 0.2 : 2.0);
            printf("    extremes: dt %-8g %-16s overlap %6.3f  stretch %8.2e  energy gain %9.2e%s\n", dts[k],
                   tt_integrator_name((tt_integrator)in), r.overlap, r.stretch, r.energy_gain,
                   r.finite ? "" : "  NOT FINITE");
            ENSURE(r.finite);
            if (in != TT_EULER) ENSURE(r.energy_gain < 0.01); /* dissipative scene: nothing may be made */
            if (dts[k] <= 1.0 / 60) ENSURE(r.overlap < 0.05 && r.stretch < 0.03);
            tt_world_destroy(s.w);
        }
}

/* --- compliance from soft to rigid; a chain of 1 000 links -------------------- */

/* A chain of n links 0.1 m long from a pin, laid out level, falling and
 * swinging: the stretch of its first link carries the whole chain's weight.
 * The pin is as high as the chain is long, so the energy it starts with
 * (y = 0 is the zero of gravity's) measures what it may not gain. */
static scene chain_scene(uint32_t n, double compliance, uint32_t substeps, uint32_t iterations)
{
    scene s = {world(TT_VERLET, substeps, iterations, (tt_vec2){0, -10}), 0.0, false, {{0, 0}, {0, 0}}, 0.1};
    const double top = 0.1 * n;
    tt_particle prev = ball(s.w, 0, top, 0, 1), first = prev;
    tt_pin_def pd = tt_pin_def_default();
    pd.particle = prev;
    tt_pin_create(s.w, &pd);
    for (uint32_t i = 1; i <= n; i++) {
        tt_particle p = ball(s.w, 0.1 * i, top, 0, 1);
        tt_distance_def dd = tt_distance_def_default();
        dd.a = prev;
        dd.b = p;
        dd.compliance = compliance;
        tt_distance_create(s.w, &dd);
        if (i == 1) s.link[1] = p;
        prev = p;
    }
    s.link[0] = first;
    return s;
}

/* Stiff compliant links the sweeps do not converge (α = 1e-6 and 1e-9 with
 * 16 sweeps over 20 links: 17 % stretch where the spring they model gives
 * 0.002 %) store ½C²/α of an unreachable stretch: the model's energy then
 * grows (×2 and ×1 000 measured), which is reported, not asserted. Soft
 * links and rigid ones (α = 0, no stored energy) must make none. */
TEST(extremes_compliance_from_soft_to_rigid)
{
    const double alpha[] = {1e-2, 1e-4, 1e-6, 1e-9, 0.0};
    const uint32_t sub[] = {1, 8}, it[] = {16, 2};
    for (int m = 0; m < 2; m++)
        for (int k = 0; k < 5; k++) {
            scene s = chain_scene(20, alpha[k], sub[m], it[m]);
            run r = simulate(&s, 1.0 / 60, 3.0);
            printf("    extremes: 20-link chain, compliance %-6g (%u × %u): stretch %8.2e  energy gain %9.2e%s\n",
                   alpha[k], sub[m], it[m], r.stretch, r.energy_gain, r.finite ? "" : "  NOT FINITE");
            ENSURE(r.finite);
            if (alpha[k] >= 1e-4 || alpha[k] == 0.0) ENSURE(r.energy_gain < 0.01);
            tt_world_destroy(s.w);
        }
}

TEST(extremes_a_chain_of_a_thousand_links)
{
    const uint32_t sub[] = {1, 8}, it[] = {16, 4};
    for (int k = 0; k < 2; k++) {
        scene s = chain_scene(1000, 0.0, sub[k], it[k]);
        run r = simulate(&s, 1.0 / 60, 2.0);
        printf("    extremes: 1 000-link chain, %u × %u: first link stretch %8.2e  energy gain %9.2e%s\n", sub[k], it[k],
               r.stretch, r.energy_gain, r.finite ? "" : "  NOT FINITE");
        ENSURE(r.finite && r.energy_gain < 0.01);
        tt_world_destroy(s.w);
    }
}

/* --- mass ratios of 1:10 000 ---------------------------------------------------- */

/* A 10 000 kg ball resting on three 1 kg balls on a floor. */
static run heavy_on_light(uint32_t substeps, uint32_t iterations)
{
    scene s = {world(TT_VERLET, substeps, iterations, (tt_vec2){0, -10}), 0.25, true, {{0, 0}, {0, 0}}, 0};
    tt_collision_settings cs = tt_collision_settings_default();
    tt_world_set_collision(s.w, &cs);
    floor_at(s.w, -5, 5, 0);
    for (int i = 0; i < 3; i++) ball(s.w, -0.5 + 0.5 * i, 0.25, 0.25, 1);
    ball(s.w, -0.25, 0.25 + 0.5 * sqrt(0.75), 0.25, 1e4);
    run r = simulate(&s, 1.0 / 60, 3.0);
    tt_world_destroy(s.w);
    return r;
}

TEST(extremes_mass_ratio_in_a_stack)
{
    const uint32_t sub[] = {1, 1, 8, 8}, it[] = {10, 64, 1, 8};
    for (int k = 0; k < 4; k++) {
        run r = heavy_on_light(sub[k], it[k]);
        printf("    extremes: 1e4 kg on three 1 kg balls, %u × %u: overlap %6.3f  energy gain %9.2e%s\n", sub[k], it[k],
               r.overlap, r.energy_gain, r.finite ? "" : "  NOT FINITE");
        ENSURE(r.finite && r.energy_gain < 0.01);
        /* No setting holds 1e4 kg on 1 kg balls: the heavy one squeezes them apart and reaches the
         * floor in every one. What is asserted is the overlap on the way (measured: 10.2 % at 1 × 10,
         * 12.1 % at 1 × 64, 5.5 % at 8 × 1, 4.9 % at 8 × 8): substeps hold it best. */
        ENSURE(r.overlap < (sub[k] >= 8 ? 0.06 : 0.13));
    }
}

/* A 10 000 kg ball hanging from a pin by a link, a 1 kg ball hanging under
 * it by another, swinging. */
TEST(extremes_mass_ratio_on_a_link)
{
    tt_world *w = world(TT_VERLET, 1, 16, (tt_vec2){0, -10});
    tt_particle top = ball(w, 0, 3, 0, 1), heavy = ball(w, 1, 3, 0, 1e4), light = ball(w, 2, 3, 0, 1);
    tt_pin_def pd = tt_pin_def_default();
    pd.particle = top;
    tt_pin_create(w, &pd);
    tt_distance_def dd = tt_distance_def_default();
    dd.a = top;
    dd.b = heavy;
    tt_distance_create(w, &dd);
    dd.a = heavy;
    dd.b = light;
    tt_distance_create(w, &dd);
    scene s = {w, 0.0, false, {heavy, light}, 1.0};
    run r = simulate(&s, 1.0 / 60, 5.0);
    printf("    extremes: 1 kg under 1e4 kg on links, 1 × 16: light link stretch %8.2e  energy gain %9.2e%s\n",
           r.stretch, r.energy_gain, r.finite ? "" : "  NOT FINITE");
    ENSURE(r.finite && r.energy_gain < 0.01 && r.stretch < 0.01);
    tt_world_destroy(w);
}

/* --- 1e4 m/s into a thin wall ------------------------------------------------------ */

TEST(extremes_ten_thousand_metres_a_second_into_a_thin_wall)
{
    for (int bullet = 0; bullet < 2; bullet++)
        for (int in = 0; in < TT_INTEGRATOR_COUNT; in++) {
            tt_world *w = world((tt_integrator)in, 1, 4, (tt_vec2){0, 0});
            tt_shape_def sd = tt_shape_def_default();
            sd.a = (tt_vec2){5, -10};
            sd.b = (tt_vec2){5, 10};
            tt_shape_create(w, &sd);
            tt_particle p = ball(w, 0, 0.3, 0.05, 1);
            tt_particle_set_velocity(w, p, (tt_vec2){1e4, 0});
            tt_particle_set_bullet(w, p, bullet);
            bool through = false, finite = true;
            for (int k = 0; k < 60; k++) {
                tt_world_step(w, 1.0 / 60);
                tt_vec2 x;
                tt_particle_get_position(w, p, &x);
                finite = finite && isfinite(x.x) && isfinite(x.y);
                through = through || x.x > 5;
            }
            if (bullet || in == 0)
                printf("    extremes: 1e4 m/s into a segment, %s%s: %s%s\n", tt_integrator_name((tt_integrator)in),
                       bullet ? ", bullet" : "", through ? "went through" : "stopped", finite ? "" : "  NOT FINITE");
            ENSURE(finite);
            if (bullet) ENSURE(!through);
            tt_world_destroy(w);
        }
}

/* --- far from the origin ----------------------------------------------------------- */

/* A ball dropped onto a floor, the whole scene moved to (c, c): it must
 * come to rest where it does at the origin, to within what doubles resolve
 * there (ulp(1e9) = 1.2e-7 m). */
static double rest_height(double c)
{
    scene s = {world(TT_VERLET, 1, 8, (tt_vec2){0, -10}), 0.25, false, {{0, 0}, {0, 0}}, 0};
    tt_collision_settings cs = tt_collision_settings_default();
    tt_world_set_collision(s.w, &cs);
    floor_at(s.w, c - 5, c + 5, c);
    tt_particle p = ball(s.w, c, c + 1, 0.25, 1);
    run r = simulate(&s, 1.0 / 60, 3.0);
    tt_vec2 x;
    tt_particle_get_position(s.w, p, &x);
    tt_world_destroy(s.w);
    return r.finite ? x.y - c : NAN;
}

TEST(extremes_far_from_the_origin)
{
    const double here = rest_height(0), far6 = rest_height(1e6), far9 = rest_height(1e9);
    printf("    extremes: rest height on a floor at 0 / 1e6 / 1e9 m: %.9f / %.9f / %.9f m\n", here, far6, far9);
    ENSURE_NEAR(here, 0.25, 1e-9);
    ENSURE_NEAR(far6, 0.25, 1e-6);
    ENSURE_NEAR(far9, 0.25, 1e-3);
}

/* --- degenerate input ---------------------------------------------------------------- */

/* Zero-length links between coincident particles, coincident colliding
 * particles, a world where everything is pinned, and an empty one, with
 * every integrator: nothing may turn NaN. */
TEST(extremes_degenerate_scenes_stay_finite)
{
    for (int in = 0; in < TT_INTEGRATOR_COUNT; in++) {
        scene s = {world((tt_integrator)in, 2, 8, (tt_vec2){0, -10}), 0.0, false, {{0, 0}, {0, 0}}, 0};
        tt_collision_settings cs = tt_collision_settings_default();
        tt_world_set_collision(s.w, &cs);
        floor_at(s.w, -5, 5, 0);
        tt_particle a = ball(s.w, 1, 1, 0.2, 1), b = ball(s.w, 1, 1, 0.2, 1), c = ball(s.w, 1, 1, 0.2, 1);
        tt_distance_def dd = tt_distance_def_default();
        dd.a = a;
        dd.b = b;
        dd.length = 0;
        tt_distance_create(s.w, &dd);
        dd.b = c;
        dd.length = 0;
        dd.compliance = 1e-3;
        tt_distance_create(s.w, &dd);
        for (int i = 0; i < 5; i++) ball(s.w, -2, 2, 0.2, 1); /* five on one spot */
        tt_particle_def pd = tt_particle_def_default();
        pd.pinned = true;
        for (int i = 0; i < 3; i++) tt_particle_create(s.w, &pd); /* pinned, coincident, radius 0 */
        run r = simulate(&s, 1.0 / 60, 2.0);
        ENSURE(r.finite);
        tt_world_destroy(s.w);
        /* everything pinned; nothing at all */
        tt_world *w = world((tt_integrator)in, 2, 8, (tt_vec2){0, -10});
        tt_world_set_collision(w, &cs);
        for (int i = 0; i < 4; i++) tt_particle_create(w, &pd);
        scene t = {w, 0.0, false, {{0, 0}, {0, 0}}, 0};
        ENSURE(simulate(&t, 1.0 / 60, 1.0).finite);
        tt_world_destroy(w);
        w = world((tt_integrator)in, 2, 8, (tt_vec2){0, -10});
        for (int k = 0; k < 10; k++) ENSURE(tt_world_step(w, 1.0 / 60) == TT_OK);
        tt_world_destroy(w);
    }
}
