/* Integrators against known answers: projectile, oscillator energy, convergence order. */
#include "test.h"
#include "tether.h"

#include <float.h>
#include <math.h>

static tt_world *world_with(tt_integrator integ, tt_vec2 g)
{
    tt_world_def d = tt_world_def_default();
    d.integrator = integ;
    d.gravity = g;
    return tt_world_create(&d);
}

static tt_particle add(tt_world *w, double x, double y, double vx, double vy)
{
    tt_particle_def d = tt_particle_def_default();
    d.position = (tt_vec2){x, y};
    d.velocity = (tt_vec2){vx, vy};
    return tt_particle_create(w, &d);
}

/* Max |x − parabola| over n steps of dt, then n2 of dt2, of a projectile
 * (x0, v0 under g), against the parabola whose start velocity is v0 + (0,
 * shift): the exact one for shift 0; symplectic Euler's samples lie on the
 * one with g·dt/2 (the velocity it keeps is the mean over the step it ended). */
static double parabola_error(tt_integrator integ, double shift, double dt, int n, double dt2, int n2)
{
    const double g = -9.81, x0 = 1, y0 = 2, vx = 3, vy = 4;
    tt_world *w = world_with(integ, (tt_vec2){0, g});
    tt_particle p = add(w, x0, y0, vx, vy);
    double t = 0, worst = 0;
    for (int k = 0; k < n + n2; k++) {
        double h = k < n ? dt : dt2;
        tt_world_step(w, h);
        t += h;
        tt_vec2 x;
        tt_particle_get_position(w, p, &x);
        double ex = x0 + vx * t, ey = y0 + (vy + shift) * t + 0.5 * g * t * t;
        worst = fmax(worst, fmax(fabs(x.x - ex), fabs(x.y - ey)));
    }
    tt_world_destroy(w);
    return worst;
}

static double projectile_error(tt_integrator integ, double dt, int n, double dt2, int n2)
{
    return parabola_error(integ, 0.0, dt, n, dt2, n2);
}

TEST(projectile_exact_for_verlet_leapfrog_rk4)
{
    tt_integrator exact[] = {TT_VERLET, TT_LEAPFROG, TT_RK4};
    /* "Exact" = round-off only: Verlet's two-step recurrence lets rounding
     * grow like n²·ε·|x| (3.6e-8 m here, |y| ≤ 450 m after 600 steps), seven
     * orders under the first-order integrators' 0.8 m. */
    const double roundoff = 600.0 * 600.0 * DBL_EPSILON * 450;
    for (int k = 0; k < 3; k++) {
        ENSURE(projectile_error(exact[k], 1.0 / 60, 600, 0, 0) < roundoff);
        /* and when dt changes half way (time-corrected Verlet) */
        ENSURE(projectile_error(exact[k], 1.0 / 60, 100, 1.0 / 97, 100) < roundoff);
    }
    /* The Euler pair is first order: off by g·dt·t/2 at t = 10 s. */
    double e = 0.5 * 9.81 * (1.0 / 60) * 10;
    ENSURE_NEAR(projectile_error(TT_SYMPLECTIC_EULER, 1.0 / 60, 600, 0, 0), e, 1e-9);
    ENSURE_NEAR(projectile_error(TT_EULER, 1.0 / 60, 600, 0, 0), e, 1e-9);
}

/* A change of step length (the user's dt, or substeps by speed) kicks by
 * the mean of the two steps, so the samples stay on their parabola: the
 * plain v += g·dt jumped by g·(dt − dt_prev)/2 at each change (0.032 m off
 * 100 steps after 1/60 → 1/97, and a ball's rebound 9.6 % short where
 * max_travel changed the substeps between the fall and the climb). With
 * one dt the arithmetic is the plain one, bit for bit: (dt + dt)/2 = dt. */
TEST(symplectic_euler_stays_on_its_parabola_when_dt_changes)
{
    const double roundoff = 1e-10;
    const double shift = 0.5 * -9.81 / 60; /* g·dt/2 of the first dt */
    ENSURE(parabola_error(TT_SYMPLECTIC_EULER, shift, 1.0 / 60, 600, 0, 0) < roundoff);
    ENSURE(parabola_error(TT_SYMPLECTIC_EULER, shift, 1.0 / 60, 100, 1.0 / 97, 100) < roundoff);
    ENSURE(parabola_error(TT_SYMPLECTIC_EULER, shift, 1.0 / 60, 50, 1.0 / 13, 50) < roundoff);
}

TEST(symplectic_euler_matches_its_discrete_formula)
{
    /* The formula BUILD-NOTES measured for Box2D: y = 10 − g·dt²·n(n+1)/2. */
    tt_world *w = world_with(TT_SYMPLECTIC_EULER, (tt_vec2){0, -10});
    tt_particle p = add(w, 0, 10, 0, 0);
    for (int k = 0; k < 60; k++) tt_world_step(w, 1.0 / 60);
    tt_vec2 x;
    tt_particle_get_position(w, p, &x);
    ENSURE_NEAR(x.y, 4.916666666666667, 1e-12);
    tt_world_destroy(w);
}

/* A unit mass on a spring (k) to a pinned anchor at the origin: a 2D
 * harmonic oscillator x = (cos ωt, (v0/ω) sin ωt) with ω = √k. */
typedef struct osc {
    tt_world *w;
    tt_particle p;
} osc;

static osc oscillator(tt_integrator integ, double k, double vy)
{
    osc o;
    o.w = world_with(integ, (tt_vec2){0, 0});
    tt_particle_def d = tt_particle_def_default();
    d.pinned = true;
    tt_particle anchor = tt_particle_create(o.w, &d);
    o.p = add(o.w, 1, 0, 0, vy);
    tt_spring_def s = tt_spring_def_default();
    s.a = o.p;
    s.b = anchor;
    s.stiffness = k;
    s.rest_length = 0;
    tt_spring_create(o.w, &s);
    return o;
}

static double energy(tt_world *w)
{
    tt_energy e;
    tt_world_get_energy(w, &e);
    return e.total;
}

TEST(oscillator_energy_euler_grows_symplectic_bounded)
{
    const double dt = 0.01;
    const int steps = 100000; /* 1000 s, 159 periods */
    tt_integrator integ[] = {TT_EULER, TT_SYMPLECTIC_EULER, TT_LEAPFROG, TT_VERLET, TT_RK4};
    for (int k = 0; k < 5; k++) {
        osc o = oscillator(integ[k], 1.0, 0.5);
        double e0 = energy(o.w), worst = 0, early = 0, late = 0;
        for (int s = 0; s < steps; s++) {
            tt_world_step(o.w, dt);
            double e = energy(o.w);
            worst = fmax(worst, fabs(e / e0 - 1));
            if (s < 1000) early += e / 1000;
            if (s >= steps - 1000) late += e / 1000;
        }
        if (integ[k] == TT_EULER) {
            ENSURE(late / e0 > 1000); /* (1 + ω²dt²)^n = e^10 ≈ 22 000 */
        } else {
            ENSURE(worst < 0.01);                   /* bounded oscillation, O(ω·dt) */
            ENSURE(fabs(late / early - 1) < 1e-3);  /* no secular drift */
        }
        tt_world_destroy(o.w);
    }
}

static double oscillator_error(tt_integrator integ, double dt, double t_end)
{
    osc o = oscillator(integ, 1.0, 0.5);
    int n = (int)lround(t_end / dt);
    for (int s = 0; s < n; s++) tt_world_step(o.w, dt);
    tt_vec2 x;
    tt_particle_get_position(o.w, o.p, &x);
    tt_world_destroy(o.w);
    return hypot(x.x - cos(t_end), x.y - 0.5 * sin(t_end));
}

TEST(convergence_order_per_integrator)
{
    const struct { tt_integrator integ; double order; } cases[] = {
        {TT_EULER, 1}, {TT_SYMPLECTIC_EULER, 1}, {TT_LEAPFROG, 2}, {TT_VERLET, 2}, {TT_RK4, 4}};
    for (int c = 0; c < 5; c++) {
        double sum = 0;
        const double dts[] = {0.04, 0.02, 0.01, 0.005};
        for (int j = 0; j < 3; j++)
            sum += log2(oscillator_error(cases[c].integ, dts[j], 2.0) /
                        oscillator_error(cases[c].integ, dts[j + 1], 2.0));
        double order = sum / 3;
        if (!(fabs(order - cases[c].order) <= 0.2))
            printf("    %s: measured order %.3f, expected %.0f\n", tt_integrator_name(cases[c].integ), order, cases[c].order);
        ENSURE_NEAR(order, cases[c].order, 0.2);
    }
}

TEST(switching_integrator_keeps_velocity)
{
    tt_world *w = world_with(TT_VERLET, (tt_vec2){0, -9.81});
    tt_particle p = add(w, 0, 0, 2, 3);
    for (int k = 0; k < 10; k++) tt_world_step(w, 1.0 / 60);
    tt_vec2 v0, v;
    tt_particle_get_velocity(w, p, &v0);
    for (int i = 0; i < TT_INTEGRATOR_COUNT; i++) {
        ENSURE_OK(tt_world_set_integrator(w, (tt_integrator)i));
        tt_particle_get_velocity(w, p, &v);
        ENSURE_NEAR(v.x, v0.x, 1e-12);
        ENSURE_NEAR(v.y, v0.y, 1e-12);
    }
    ENSURE_OK(tt_world_set_integrator(w, TT_VERLET));
    tt_particle_get_velocity(w, p, &v);
    ENSURE_NEAR(v.y, v0.y, 1e-12);
    tt_world_destroy(w);
}

TEST(damping_scales_velocity_each_step)
{
    for (int i = 0; i < TT_INTEGRATOR_COUNT; i++) {
        tt_world *w = world_with((tt_integrator)i, (tt_vec2){0, 0});
        tt_world_set_damping(w, 2.0);
        tt_particle p = add(w, 0, 0, 1, 0);
        for (int k = 0; k < 30; k++) tt_world_step(w, 0.01);
        tt_vec2 v;
        tt_particle_get_velocity(w, p, &v);
        ENSURE_NEAR(v.x, pow(1 - 2.0 * 0.01, 30), 1e-12);
        tt_world_destroy(w);
    }
}

TEST(pinned_particles_never_move)
{
    for (int i = 0; i < TT_INTEGRATOR_COUNT; i++) {
        tt_world *w = world_with((tt_integrator)i, (tt_vec2){0, -9.81});
        tt_particle_def d = tt_particle_def_default();
        d.pinned = true;
        d.position = (tt_vec2){1, 1};
        tt_particle p = tt_particle_create(w, &d);
        tt_particle q = add(w, 2, 1, 0, 0);
        tt_spring_def s = tt_spring_def_default();
        s.a = p;
        s.b = q;
        s.rest_length = 0.5;
        tt_spring_create(w, &s);
        tt_particle_apply_impulse(w, p, (tt_vec2){5, 5});
        tt_particle_apply_force(w, p, (tt_vec2){5, 5});
        for (int k = 0; k < 50; k++) tt_world_step(w, 0.01);
        tt_vec2 x;
        tt_particle_get_position(w, p, &x);
        ENSURE(x.x == 1 && x.y == 1);
        tt_world_destroy(w);
    }
}

TEST(divergence_is_stopped_without_nan)
{
    for (int i = 0; i < TT_INTEGRATOR_COUNT; i++) {
        osc o = oscillator((tt_integrator)i, 1e12, 0); /* ω·dt = 1e4: every integrator blows up */
        uint32_t stopped = 0;
        for (int s = 0; s < 200; s++) {
            ENSURE_OK(tt_world_step(o.w, 0.01));
            tt_stats st;
            tt_world_get_stats(o.w, &st);
            stopped += st.diverged;
            tt_vec2 x, v;
            tt_particle_get_position(o.w, o.p, &x);
            tt_particle_get_velocity(o.w, o.p, &v);
            ENSURE(fabs(x.x) <= TT_DIVERGED && fabs(x.y) <= TT_DIVERGED);
            ENSURE(isfinite(v.x) && isfinite(v.y));
        }
        ENSURE(isfinite(energy(o.w)));
        ENSURE(stopped > 0);
        tt_world_destroy(o.w);
    }
}
