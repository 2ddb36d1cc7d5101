/* Forces, impulses, springs, wind, explosions. */
#include "test.h"
#include "tether.h"

#include <string.h>

static tt_world *world0(tt_integrator integ)
{
    tt_world_def d = tt_world_def_default();
    d.gravity = (tt_vec2){0, 0};
    d.integrator = integ;
    return tt_world_create(&d);
}

static tt_particle add(tt_world *w, double x, double y, double mass)
{
    tt_particle_def d = tt_particle_def_default();
    d.position = (tt_vec2){x, y};
    d.mass = mass;
    return tt_particle_create(w, &d);
}

TEST(impulse_changes_velocity_by_j_over_m)
{
    for (int i = 0; i < TT_INTEGRATOR_COUNT; i++) {
        tt_world *w = world0((tt_integrator)i);
        tt_particle p = add(w, 0, 0, 2.0);
        ENSURE_OK(tt_particle_apply_impulse(w, p, (tt_vec2){4, -2}));
        tt_vec2 v;
        tt_particle_get_velocity(w, p, &v);
        ENSURE_NEAR(v.x, 2, 1e-12);
        ENSURE_NEAR(v.y, -1, 1e-12);
        tt_world_step(w, 0.1);
        tt_vec2 x;
        tt_particle_get_position(w, p, &x);
        ENSURE_NEAR(x.x, 0.2, 1e-12);
        tt_world_destroy(w);
    }
}

TEST(applied_force_lasts_one_step)
{
    for (int i = 0; i < TT_INTEGRATOR_COUNT; i++) {
        tt_world *w = world0((tt_integrator)i);
        tt_particle p = add(w, 0, 0, 2.0);
        /* One step first: Verlet starts a freshly set velocity with a Taylor
         * step (x + v·dt + a·dt²/2), which reads back as v + a·dt/2. */
        tt_world_step(w, 0.1);
        tt_particle_apply_force(w, p, (tt_vec2){10, 0});
        tt_particle_apply_force(w, p, (tt_vec2){10, 0}); /* forces add up */
        tt_world_step(w, 0.1);
        tt_vec2 v1, v2;
        tt_particle_get_velocity(w, p, &v1);
        ENSURE_NEAR(v1.x, 20.0 / 2.0 * 0.1, 1e-12); /* Δv = F/m·dt */
        tt_world_step(w, 0.1);
        tt_world_step(w, 0.1);
        tt_particle_get_velocity(w, p, &v2);
        ENSURE_NEAR(v2.x, v1.x, 1e-12);
        tt_world_destroy(w);
    }
}

TEST(wind_pushes_light_particles_more)
{
    tt_world *w = world0(TT_SYMPLECTIC_EULER);
    tt_world_set_wind(w, (tt_vec2){3, 0});
    tt_particle a = add(w, 0, 0, 1.0), b = add(w, 0, 1, 3.0);
    tt_world_step(w, 0.5);
    tt_vec2 va, vb;
    tt_particle_get_velocity(w, a, &va);
    tt_particle_get_velocity(w, b, &vb);
    ENSURE_NEAR(va.x, 1.5, 1e-12);
    ENSURE_NEAR(vb.x, 0.5, 1e-12);
    tt_world_destroy(w);
}

TEST(explosion_is_radial_with_linear_falloff)
{
    tt_world *w = world0(TT_VERLET);
    tt_particle centre = add(w, 5, 5, 1), near = add(w, 6, 5, 1), far = add(w, 5, 2, 2), out = add(w, 5, 9, 1);
    ENSURE_OK(tt_world_explode(w, (tt_vec2){5, 5}, 4.0, 8.0));
    tt_vec2 v;
    tt_particle_get_velocity(w, centre, &v);
    ENSURE(v.x == 0 && v.y == 0);
    tt_particle_get_velocity(w, near, &v);
    ENSURE_NEAR(v.x, 8.0 * (1 - 1.0 / 4), 1e-9);
    ENSURE_NEAR(v.y, 0, 1e-12);
    tt_particle_get_velocity(w, far, &v);
    ENSURE_NEAR(v.y, -8.0 * (1 - 3.0 / 4) / 2.0, 1e-9);
    tt_particle_get_velocity(w, out, &v);
    ENSURE(v.x == 0 && v.y == 0);
    tt_world_destroy(w);
}

TEST(spring_conserves_momentum_and_oscillates)
{
    for (int i = 0; i < TT_INTEGRATOR_COUNT; i++) {
        tt_world *w = world0((tt_integrator)i);
        tt_particle a = add(w, 0, 0, 1.0), b = add(w, 2, 0, 3.0);
        tt_spring_def d = tt_spring_def_default();
        d.a = a;
        d.b = b;
        d.stiffness = 50;
        d.rest_length = 1.5;
        tt_spring s = tt_spring_create(w, &d);
        ENSURE(tt_spring_is_valid(w, s));
        double min_len = 10;
        for (int k = 0; k < 400; k++) {
            tt_world_step(w, 0.002);
            double len;
            tt_spring_get_length(w, s, &len);
            min_len = len < min_len ? len : min_len;
        }
        tt_vec2 xa, xb;
        tt_particle_get_position(w, a, &xa);
        tt_particle_get_position(w, b, &xb);
        ENSURE_NEAR((1.0 * xa.x + 3.0 * xb.x) / 4.0, 1.5, 1e-9); /* centre of mass stays */
        /* 2 → 1 and back, symmetric about rest 1.5; Euler gains ~11 % energy here */
        ENSURE_NEAR(min_len, 1.0, i == TT_EULER ? 0.05 : 0.01);
        tt_world_destroy(w);
    }
}

TEST(spring_damping_removes_energy)
{
    tt_world *w = world0(TT_VERLET);
    tt_particle a = add(w, 0, 0, 1.0), b = add(w, 2, 0, 1.0);
    tt_spring_def d = tt_spring_def_default();
    d.a = a;
    d.b = b;
    d.stiffness = 50;
    d.damping = 2;
    d.rest_length = 1.0;
    tt_spring_create(w, &d);
    tt_energy e0, e1;
    tt_world_get_energy(w, &e0);
    for (int k = 0; k < 2000; k++) tt_world_step(w, 0.005);
    tt_world_get_energy(w, &e1);
    ENSURE(e1.total < 1e-3 * e0.total);
    tt_world_destroy(w);
}

TEST(spring_defaults_and_setters)
{
    tt_world *w = world0(TT_VERLET);
    tt_particle a = add(w, 0, 0, 1.0), b = add(w, 3, 4, 1.0);
    tt_spring_def d = tt_spring_def_default();
    d.a = a;
    d.b = b;
    tt_spring s = tt_spring_create(w, &d);
    tt_spring_def got;
    ENSURE_OK(tt_spring_get_def(w, s, &got));
    ENSURE_NEAR(got.rest_length, 5.0, 1e-12);
    ENSURE(got.stiffness == 100 && got.damping == 0);
    ENSURE_OK(tt_spring_set_stiffness(w, s, 7));
    ENSURE(tt_spring_set_damping(w, s, -1) == TT_EINVAL);
    ENSURE(tt_spring_set_rest_length(w, s, NAN) == TT_EINVAL);
    d.b = a;
    ENSURE(tt_spring_create(w, &d).gen == 0); /* same particle twice */
    ENSURE_OK(tt_spring_destroy(w, s));
    ENSURE(!tt_spring_is_valid(w, s));
    ENSURE(tt_spring_destroy(w, s) == TT_ESTALE);
    tt_world_destroy(w);
}

TEST(removing_a_particle_removes_its_springs)
{
    tt_world *w = world0(TT_VERLET);
    tt_particle a = add(w, 0, 0, 1.0), b = add(w, 1, 0, 1.0), c = add(w, 2, 0, 1.0);
    tt_spring_def d = tt_spring_def_default();
    d.a = a;
    d.b = b;
    tt_spring ab = tt_spring_create(w, &d);
    d.a = b;
    d.b = c;
    tt_spring bc = tt_spring_create(w, &d);
    ENSURE(tt_world_spring_count(w) == 2);
    tt_particle_destroy(w, a);
    ENSURE(!tt_spring_is_valid(w, ab));
    ENSURE(tt_spring_is_valid(w, bc));
    ENSURE(tt_world_spring_count(w) == 1);
    tt_world_step(w, 0.01);
    tt_world_destroy(w);
}

/* A world whose only forces are a few springs integrates the particles no
 * spring reaches with gravity alone (integrate.c, verlet_few): bit for bit
 * what the general loop gives, which a zero force applied every step forces
 * on the twin. Ends pinned, damped, with a fresh velocity; a non-end fresh
 * too; then a changed dt and world damping (the general arithmetic). */
static tt_world *few_springs_world(tt_particle *ps)
{
    tt_world_def d = tt_world_def_default();
    d.gravity = (tt_vec2){1.3, -9.81};
    tt_world *w = tt_world_create(&d);
    for (int i = 0; i < 256; i++) ps[i] = add(w, (i % 16) * 0.5, (i / 16) * 0.5, 1.0 + (i % 3));
    tt_spring_def s = tt_spring_def_default();
    s.a = ps[10];
    s.b = ps[11];
    s.damping = 0.7;
    s.rest_length = 0.2;
    tt_spring_create(w, &s);
    s.a = ps[50];
    s.b = ps[150];
    s.damping = 0;
    tt_spring_create(w, &s);
    tt_particle_set_pinned(w, ps[150], true);
    tt_particle_set_velocity(w, ps[10], (tt_vec2){1.5, 2.0});
    tt_particle_set_velocity(w, ps[20], (tt_vec2){-3.0, 0.25});
    return w;
}

TEST(few_springs_integrate_bit_for_bit_as_the_general_loop)
{
    tt_particle ps[256], qs[256];
    tt_world *a = few_springs_world(ps), *b = few_springs_world(qs);
    for (int s = 0; s < 60; s++) {
        if (s == 30) {
            tt_world_set_damping(a, 0.3);
            tt_world_set_damping(b, 0.3);
        }
        double dt = s < 20 ? 1.0 / 60 : s < 40 ? 1.0 / 50 : 1.0 / 45;
        ENSURE_OK(tt_particle_apply_force(b, qs[0], (tt_vec2){0, 0}));
        ENSURE_OK(tt_world_step(a, dt));
        ENSURE_OK(tt_world_step(b, dt));
    }
    double xa[512], xb[512], va[512], vb[512];
    ENSURE_OK(tt_particles_get_positions(a, ps, 256, xa));
    ENSURE_OK(tt_particles_get_positions(b, qs, 256, xb));
    for (int i = 0; i < 256; i++) {
        tt_vec2 v;
        tt_particle_get_velocity(a, ps[i], &v), va[2 * i] = v.x, va[2 * i + 1] = v.y;
        tt_particle_get_velocity(b, qs[i], &v), vb[2 * i] = v.x, vb[2 * i + 1] = v.y;
    }
    ENSURE(memcmp(xa, xb, sizeof xa) == 0);
    ENSURE(memcmp(va, vb, sizeof va) == 0);
    ENSURE(xa[2 * 10] != 5.0 && xa[2 * 150] == 3.0); /* the spring moved its end; the pinned one stayed */
    tt_world_destroy(a);
    tt_world_destroy(b);
}
