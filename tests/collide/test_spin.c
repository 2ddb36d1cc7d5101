/* Particles that turn (tt_world_def.spin): a disc rolling down a slope, one
 * sliding without friction, a spinning disc set down on a floor, against
 * the rigid-disc answers; extremes without NaN; the spin in snapshots. */
#include "test.h"
#include "tether.h"

#include <stdlib.h>

static tt_world *spin_world(uint32_t substeps, uint32_t iterations)
{
    tt_world_def wd = tt_world_def_default();
    wd.spin = true;
    wd.sleep = false;
    wd.substeps = substeps;
    wd.iterations = iterations;
    return tt_world_create(&wd);
}

/* A disc (r 0.5) on a slope of angle θ through the origin, touching it. */
static tt_particle disc_on_slope(tt_world *w, double theta, double mu)
{
    tt_shape_def sd = tt_shape_def_default();
    sd.a = (tt_vec2){-100 * cos(theta), -100 * sin(theta)};
    sd.b = (tt_vec2){100 * cos(theta), 100 * sin(theta)};
    sd.friction_static = sd.friction_kinetic = mu;
    tt_shape_create(w, &sd);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.5;
    pd.position = (tt_vec2){-0.5 * sin(theta), 0.5 * cos(theta)};
    tt_particle p = tt_particle_create(w, &pd);
    tt_particle_set_material(w, p, 0, mu, mu);
    return p;
}

/* Rolling without slipping: a = (2/3) g sin θ (a solid disc), and r·ω = v. */
TEST(spin_disc_rolls_down_a_slope_at_two_thirds_g_sin_theta)
{
    const double thetas[] = {0.2, 0.35, 0.6};
    for (int k = 0; k < 3; k++) {
        const double th = thetas[k];
        tt_world *w = spin_world(1, 8);
        tt_particle p = disc_on_slope(w, th, 1.0); /* μ ≥ tan θ / 3 */
        for (int s = 0; s < 120; s++) ENSURE_OK(tt_world_step(w, 1.0 / 60));
        tt_vec2 v;
        double om, ang;
        ENSURE_OK(tt_particle_get_velocity(w, p, &v));
        ENSURE_OK(tt_particle_get_spin(w, p, &om));
        ENSURE_OK(tt_particle_get_angle(w, p, &ang));
        const double down = -(v.x * cos(th) + v.y * sin(th)); /* speed down the slope */
        ENSURE_NEAR(down / 2.0 / (2.0 / 3.0 * 9.81 * sin(th)), 1.0, 0.02);
        ENSURE_NEAR(om * 0.5 / down, 1.0, 0.02); /* rolls: counter-clockwise going left */
        ENSURE(ang >= -M_PI && ang <= M_PI);
        tt_world_destroy(w);
    }
}

/* Without friction the disc slides at g sin θ and never turns. */
TEST(spin_disc_without_friction_slides_and_does_not_turn)
{
    const double th = 0.35;
    tt_world *w = spin_world(1, 8);
    tt_particle p = disc_on_slope(w, th, 0.0);
    for (int s = 0; s < 120; s++) ENSURE_OK(tt_world_step(w, 1.0 / 60));
    tt_vec2 v;
    double om, ang;
    tt_particle_get_velocity(w, p, &v);
    tt_particle_get_spin(w, p, &om);
    tt_particle_get_angle(w, p, &ang);
    ENSURE_NEAR(-(v.x * cos(th) + v.y * sin(th)) / 2.0 / (9.81 * sin(th)), 1.0, 0.02);
    ENSURE(om == 0.0 && ang == 0.0);
    tt_world_destroy(w);
}

/* A disc spinning at ω0 set down on a floor with friction skids, then
 * rolls: its angular momentum about the contact point is kept, so it ends
 * at v = r·ω0/3, ω = ω0/3 (the disc's contact moves forward: it goes back). */
TEST(spin_spinning_disc_on_a_floor_ends_rolling_at_a_third)
{
    tt_world *w = spin_world(1, 8);
    tt_shape_def sd = tt_shape_def_default();
    sd.type = TT_SHAPE_AABB;
    sd.a = (tt_vec2){-100, -1};
    sd.b = (tt_vec2){100, 0};
    sd.friction_static = sd.friction_kinetic = 0.3;
    tt_shape_create(w, &sd);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.5;
    pd.position = (tt_vec2){0, 0.5};
    tt_particle p = tt_particle_create(w, &pd);
    tt_particle_set_material(w, p, 0, 0.3, 0.3);
    const double w0 = 12.0;
    ENSURE_OK(tt_particle_set_spin(w, p, w0));
    tt_energy e0, e1;
    ENSURE_OK(tt_world_get_energy(w, &e0));
    ENSURE_NEAR(e0.kinetic, 0.25 * 0.25 * w0 * w0, 1e-12); /* ½·(m r²/2)·ω0² */
    for (int s = 0; s < 180; s++) ENSURE_OK(tt_world_step(w, 1.0 / 60));
    ENSURE_OK(tt_world_get_energy(w, &e1));
    ENSURE_NEAR(e1.kinetic / e0.kinetic, 1.0 / 3.0, 0.01); /* rolling at ω0/3 keeps a third: the skid took the rest */
    tt_vec2 v;
    double om;
    tt_particle_get_velocity(w, p, &v);
    tt_particle_get_spin(w, p, &om);
    ENSURE_NEAR(v.x / (-0.5 * w0 / 3.0), 1.0, 0.02);
    ENSURE_NEAR(om / (w0 / 3.0), 1.0, 0.02);
    ENSURE(fabs(v.y) < 1e-6);
    tt_world_destroy(w);
}

/* Extremes: a huge spin, μ 100, radii from 1e-6 to 0 in a small heap:
 * every position, velocity, angle and spin stays finite. */
TEST(spin_extremes_stay_finite)
{
    tt_world *w = spin_world(2, 4);
    tt_collision_settings cs = tt_collision_settings_default();
    cs.friction_static = cs.friction_kinetic = 100;
    ENSURE_OK(tt_world_set_collision(w, &cs));
    tt_shape_def sd = tt_shape_def_default();
    sd.type = TT_SHAPE_AABB;
    sd.a = (tt_vec2){-5, -1};
    sd.b = (tt_vec2){5, 0};
    sd.friction_static = sd.friction_kinetic = 100;
    tt_shape_create(w, &sd);
    tt_particle ps[40];
    tt_particle_def pd = tt_particle_def_default();
    for (int i = 0; i < 40; i++) {
        pd.radius = i % 4 == 0 ? 0.0 : i % 4 == 1 ? 1e-6 : 0.3;
        pd.position = (tt_vec2){-2 + (i % 8) * 0.5, 0.2 + (i / 8) * 0.4};
        ps[i] = tt_particle_create(w, &pd);
        /* a point does not turn: refused, the others spin as fast as allowed */
        ENSURE(tt_particle_set_spin(w, ps[i], i % 2 ? 1e12 : -1e12) == (pd.radius > 0 ? TT_OK : TT_ESTATE));
    }
    ENSURE(tt_particle_set_spin(w, ps[1], 2e12) == TT_EINVAL);
    ENSURE(tt_particle_set_spin(w, ps[1], NAN) == TT_EINVAL);
    for (int s = 0; s < 120; s++) ENSURE_OK(tt_world_step(w, 1.0 / 60));
    for (int i = 0; i < 40; i++) {
        tt_vec2 x, v;
        double a, om;
        tt_particle_get_position(w, ps[i], &x);
        tt_particle_get_velocity(w, ps[i], &v);
        tt_particle_get_angle(w, ps[i], &a);
        tt_particle_get_spin(w, ps[i], &om);
        ENSURE(isfinite(x.x) && isfinite(x.y) && isfinite(v.x) && isfinite(v.y) && isfinite(om));
        ENSURE(a >= -M_PI && a <= M_PI);
    }
    tt_world_destroy(w);
}

/* A world without the option has no spin to read or set; a stale handle is refused. */
TEST(spin_calls_are_validated)
{
    tt_world *w = tt_world_create(NULL);
    const tt_particle_def pd = tt_particle_def_default();
    tt_particle p = tt_particle_create(w, &pd);
    double x;
    ENSURE(tt_particle_get_angle(w, p, &x) == TT_ESTATE);
    ENSURE(tt_particle_set_spin(w, p, 1.0) == TT_ESTATE);
    tt_world_destroy(w);
    w = spin_world(1, 4);
    p = tt_particle_create(w, &pd);
    ENSURE(tt_particle_get_spin(w, p, NULL) == TT_EINVAL);
    ENSURE_OK(tt_particle_destroy(w, p));
    ENSURE(tt_particle_get_spin(w, p, &x) == TT_ESTALE);
    ENSURE(tt_particle_get_angle(NULL, p, &x) == TT_EINVAL);
    tt_world_destroy(w);
}

/* The spin is world state: a saved world goes on exactly as the original,
 * and a spin changes the hash. */
TEST(spin_snapshot_round_trip)
{
    tt_world *w = spin_world(1, 8);
    tt_particle p = disc_on_slope(w, 0.3, 0.8);
    for (int s = 0; s < 30; s++) tt_world_step(w, 1.0 / 60);
    size_t size;
    ENSURE(tt_world_save(w, NULL, 0, &size) != TT_OK || size > 0);
    void *buf = malloc(size);
    ENSURE_OK(tt_world_save(w, buf, size, &size));
    tt_world *u = tt_world_load(buf, size);
    free(buf);
    ENSURE(u != NULL);
    ENSURE(tt_world_hash(u) == tt_world_hash(w));
    for (int s = 0; s < 30; s++) {
        tt_world_step(w, 1.0 / 60);
        tt_world_step(u, 1.0 / 60);
    }
    ENSURE(tt_world_hash(u) == tt_world_hash(w));
    double a, b;
    tt_particle_get_angle(w, p, &a);
    tt_particle_get_angle(u, p, &b);
    ENSURE(a == b && a != 0.0);
    const uint64_t h = tt_world_hash(w);
    tt_particle_set_spin(w, p, 1.0);
    ENSURE(tt_world_hash(w) != h);
    tt_world_destroy(u);
    tt_world_destroy(w);
}

/* Time reversal turns the spin round with the velocities: a turning
 * particle's angle comes back (within rounding). */
TEST(spin_reverse_turns_back)
{
    tt_world *w = spin_world(1, 4);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.5;
    tt_particle p = tt_particle_create(w, &pd);
    ENSURE_OK(tt_particle_set_spin(w, p, 2.5));
    for (int s = 0; s < 60; s++) ENSURE_OK(tt_world_step(w, 1.0 / 60));
    double a, om;
    tt_particle_get_angle(w, p, &a);
    ENSURE_NEAR(a, remainder(2.5, 2 * M_PI), 1e-9);
    ENSURE_OK(tt_world_reverse(w));
    tt_particle_get_spin(w, p, &om);
    ENSURE(om == -2.5);
    for (int s = 0; s < 60; s++) ENSURE_OK(tt_world_step(w, 1.0 / 60));
    tt_particle_get_angle(w, p, &a);
    ENSURE_NEAR(a, 0.0, 1e-9);
    tt_world_destroy(w);
}

/* A disc spinning in place on a frictionless floor stays awake while its
 * rim moves faster than the sleep speed (asleep, its angle would stop
 * while it still reported its spin); the same disc not spinning sleeps. */
TEST(spin_a_spinning_disc_does_not_fall_asleep)
{
    for (int spinning = 0; spinning < 2; spinning++) {
        tt_world_def wd = tt_world_def_default();
        wd.spin = true; /* sleeping on: the default */
        tt_world *w = tt_world_create(&wd);
        tt_particle p = disc_on_slope(w, 0.0, 0.0);
        ENSURE_OK(tt_particle_set_spin(w, p, spinning ? 10.0 : 0.0));
        for (int s = 0; s < 240; s++) ENSURE_OK(tt_world_step(w, 1.0 / 60));
        bool asleep = false;
        double a0, a1;
        ENSURE_OK(tt_particle_get_asleep(w, p, &asleep));
        ENSURE(asleep == !spinning);
        ENSURE_OK(tt_particle_get_angle(w, p, &a0));
        ENSURE_OK(tt_world_step(w, 1.0 / 60));
        ENSURE_OK(tt_particle_get_angle(w, p, &a1));
        ENSURE(spinning ? fabs(remainder(a1 - a0 - 10.0 / 60, 2 * M_PI)) < 1e-9 : a1 == a0);
        tt_world_destroy(w);
    }
}

/* As set_velocity refuses a pinned particle, set_spin does, and a point
 * (radius 0) has no rim to turn; both leave the world as it was. Pinning a
 * turning particle or making it a point stops it. */
TEST(spin_pinned_particles_and_points_do_not_turn)
{
    tt_world *w = spin_world(1, 8);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.2;
    tt_particle a = tt_particle_create(w, &pd);
    pd.pinned = true;
    tt_particle pinned = tt_particle_create(w, &pd);
    pd.pinned = false;
    pd.radius = 0;
    tt_particle point = tt_particle_create(w, &pd);
    const uint64_t h0 = tt_world_hash(w);
    ENSURE(tt_particle_set_spin(w, pinned, 3.0) == TT_ESTATE);
    ENSURE(tt_particle_set_spin(w, point, 3.0) == TT_ESTATE);
    ENSURE_OK(tt_particle_set_spin(w, point, 0.0));
    ENSURE(tt_world_hash(w) == h0);
    double om;
    ENSURE_OK(tt_particle_set_spin(w, a, 3.0));
    ENSURE_OK(tt_particle_set_pinned(w, a, true));
    ENSURE_OK(tt_particle_get_spin(w, a, &om));
    ENSURE(om == 0.0);
    ENSURE_OK(tt_particle_set_pinned(w, a, false));
    ENSURE_OK(tt_particle_set_spin(w, a, 3.0));
    ENSURE_OK(tt_particle_set_radius(w, a, 0.0));
    ENSURE_OK(tt_particle_get_spin(w, a, &om));
    ENSURE(om == 0.0);
    tt_world_destroy(w);
}
