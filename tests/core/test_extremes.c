/* Numerical stability at the extremes, against known answers: the
 * stability limits of each integrator on an undamped oscillator (ω·dt < 2 for
 * the symplectic trio, < 2√2 for RK4, none for explicit Euler), mass ratios
 * of 1:10 000, tiny and huge steps, huge speeds. Nothing may ever produce NaN. */
#include "test.h"
#include "tether.h"

#include <float.h>
#include <stdlib.h>

/* A unit mass on a spring (ω = 1) to a pinned anchor, at x = 1. */
static tt_world *oscillator(tt_integrator integ, tt_particle *p)
{
    tt_world_def d = tt_world_def_default();
    d.integrator = integ;
    d.gravity = (tt_vec2){0, 0};
    tt_world *w = tt_world_create(&d);
    tt_particle_def pd = tt_particle_def_default();
    pd.pinned = true;
    tt_particle anchor = tt_particle_create(w, &pd);
    pd.pinned = false;
    pd.position = (tt_vec2){1, 0};
    *p = tt_particle_create(w, &pd);
    tt_spring_def sd = tt_spring_def_default();
    sd.a = *p;
    sd.b = anchor;
    sd.stiffness = 1;
    sd.rest_length = 0;
    tt_spring_create(w, &sd);
    return w;
}

/* The oscillator's particles stopped by the divergence guard over `steps`
 * steps of ω·dt = wdt. */
static uint32_t oscillate(tt_integrator integ, double wdt, int steps, double *max_abs_x)
{
    tt_particle p;
    tt_world *w = oscillator(integ, &p);
    uint32_t stopped = 0;
    *max_abs_x = 0;
    for (int s = 0; s < steps; s++) {
        tt_world_step(w, wdt);
        tt_stats st;
        tt_world_get_stats(w, &st);
        stopped += st.diverged;
        tt_vec2 x;
        tt_particle_get_position(w, p, &x);
        if (!isfinite(x.x) || !isfinite(x.y)) *max_abs_x = INFINITY;
        else *max_abs_x = fmax(*max_abs_x, fmax(fabs(x.x), fabs(x.y)));
    }
    tt_world_destroy(w);
    return stopped;
}

TEST(stability_limits_match_theory)
{
    const struct { tt_integrator integ; double limit; } cases[] = {
        {TT_SYMPLECTIC_EULER, 2.0}, {TT_LEAPFROG, 2.0}, {TT_VERLET, 2.0}, {TT_RK4, 2.0 * M_SQRT2}};
    for (int c = 0; c < 4; c++) {
        double xmax;
        /* just under the limit: bounded for 10 000 steps (symplectic Euler's orbit is a stretched ellipse there) */
        ENSURE(oscillate(cases[c].integ, cases[c].limit * 0.99, 10000, &xmax) == 0);
        ENSURE(xmax < 20);
        /* just over: grows without bound, and the guard stops it without NaN */
        ENSURE(oscillate(cases[c].integ, cases[c].limit * 1.01, 10000, &xmax) > 0);
        ENSURE(xmax <= TT_DIVERGED);
    }
    double xmax;
    ENSURE(oscillate(TT_EULER, 0.5, 10000, &xmax) > 0); /* explicit Euler: unstable at any ω·dt */
    ENSURE(xmax <= TT_DIVERGED);
}

TEST(mass_ratio_ten_thousand_to_one)
{
    const tt_integrator symplectic[] = {TT_SYMPLECTIC_EULER, TT_LEAPFROG, TT_VERLET};
    for (int k = 0; k < 3; k++) {
        tt_world_def d = tt_world_def_default();
        d.integrator = symplectic[k];
        d.gravity = (tt_vec2){0, 0};
        tt_world *w = tt_world_create(&d);
        tt_particle_def pd = tt_particle_def_default();
        pd.mass = 1e4;
        tt_particle heavy = tt_particle_create(w, &pd);
        pd.mass = 1;
        pd.position = (tt_vec2){1.5, 0};
        pd.velocity = (tt_vec2){0, 3};
        tt_particle light = tt_particle_create(w, &pd);
        tt_spring_def sd = tt_spring_def_default();
        sd.a = light;
        sd.b = heavy;
        sd.stiffness = 900; /* ω ≈ 30 /s with the reduced mass: ω·dt = 0.5 at dt = 1/60 */
        sd.rest_length = 1;
        tt_spring_create(w, &sd);
        tt_energy e0, e;
        tt_world_get_energy(w, &e0);
        double worst = 0;
        for (int s = 0; s < 100000; s++) {
            tt_world_step(w, 1.0 / 60);
            tt_world_get_energy(w, &e);
            worst = fmax(worst, fabs(e.total / e0.total - 1));
        }
        tt_vec2 vh, vl;
        tt_particle_get_velocity(w, heavy, &vh);
        tt_particle_get_velocity(w, light, &vl);
        /* momentum conserved to round-off (the heavy side magnifies it 10⁴×; 3.4e-9 measured) */
        ENSURE_NEAR(1e4 * vh.x + vl.x, 0.0, 1e-8);
        ENSURE_NEAR(1e4 * vh.y + vl.y, 3.0, 1e-8);
        ENSURE(worst < 0.5); /* bounded (O(ω·dt) for these integrators), never growing */
        tt_stats st;
        tt_world_get_stats(w, &st);
        ENSURE(st.diverged == 0);
        tt_world_destroy(w);
    }
}

static double projectile_y_error(tt_integrator integ, double dt, int steps)
{
    tt_world_def d = tt_world_def_default();
    d.integrator = integ;
    d.dt_hint = dt;
    tt_world *w = tt_world_create(&d);
    tt_particle_def pd = tt_particle_def_default();
    pd.position = (tt_vec2){0, 100};
    pd.velocity = (tt_vec2){3, 4};
    tt_particle p = tt_particle_create(w, &pd);
    for (int s = 0; s < steps; s++) tt_world_step(w, dt);
    tt_vec2 x;
    tt_particle_get_position(w, p, &x);
    tt_world_destroy(w);
    double t = dt * steps;
    return fabs(x.y - (100 + 4 * t - 0.5 * 9.81 * t * t));
}

TEST(tiny_steps_round_off_is_measured)
{
    /* dt = 1e-5 for 10 s (10⁶ steps) at ~100 m from the origin. Position
     * Verlet keeps velocity as a difference of positions, so its velocity
     * resolution is ulp(x)/dt and rounding biases it: 9.7e-4 m measured,
     * growing as n². Leapfrog stores v: 7e-9 m. Use leapfrog for tiny dt. */
    double verlet = projectile_y_error(TT_VERLET, 1e-5, 1000000);
    double leapfrog = projectile_y_error(TT_LEAPFROG, 1e-5, 1000000);
    ENSURE(leapfrog < 1e-7);
    ENSURE(verlet < 5e-3);
    ENSURE(verlet > 100 * leapfrog);
    /* at a game's dt = 1/60 the same effect is invisible: exact to round-off */
    ENSURE(projectile_y_error(TT_VERLET, 1.0 / 60, 600) < 600.0 * 600.0 * DBL_EPSILON * 450);
}

TEST(huge_steps_and_speeds_stay_exact)
{
    /* the largest dt allowed, 10 s, for 100 steps: still exact under gravity */
    tt_integrator exact[] = {TT_VERLET, TT_LEAPFROG, TT_RK4};
    for (int k = 0; k < 3; k++) {
        ENSURE(projectile_y_error(exact[k], 10.0, 100) < 1e-9 * 0.5 * 9.81 * 1000 * 1000);
        /* 1e6 m/s for 10 000 steps: straight line, 1.7e8 m away */
        tt_world_def d = tt_world_def_default();
        d.integrator = exact[k];
        d.gravity = (tt_vec2){0, 0};
        tt_world *w = tt_world_create(&d);
        tt_particle_def pd = tt_particle_def_default();
        pd.velocity = (tt_vec2){1e6, -1e6};
        tt_particle p = tt_particle_create(w, &pd);
        for (int s = 0; s < 10000; s++) tt_world_step(w, 1.0 / 60);
        tt_vec2 x;
        tt_particle_get_position(w, p, &x);
        ENSURE_NEAR(x.x, 1e6 * 10000 / 60.0, 1e-6 * 1e6 * 10000 / 60.0 * 1e-3);
        ENSURE_NEAR(x.y, -x.x, 1e-9 * fabs(x.x));
        tt_world_destroy(w);
    }
}

/* A unit mass on a spring (ω = 1, ω·dt = 0.1) for 10⁶ steps: the symplectic
 * integrators keep the energy within O(ω·dt) of its start for ever; RK4
 * loses it slowly; explicit Euler gains until the guard stops it. */
static double oscillator_drift(tt_integrator in, bool *finite)
{
    tt_particle p;
    tt_world *w = oscillator(in, &p);
    tt_energy e0, e;
    tt_world_get_energy(w, &e0);
    double worst = 0;
    for (long k = 0; k < 1000000; k++) {
        tt_world_step(w, 0.1);
        if (k % 1000 == 999) {
            tt_world_get_energy(w, &e);
            worst = fmax(worst, fabs(e.total / e0.total - 1));
        }
    }
    tt_vec2 x;
    tt_particle_get_position(w, p, &x);
    *finite = isfinite(x.x) && isfinite(x.y) && isfinite(e.total);
    tt_world_destroy(w);
    return worst;
}

TEST(extremes_a_million_steps_of_an_undamped_oscillator)
{
    /* five million steps of arithmetic on two particles: nothing for
     * valgrind to find that the other tests miss, and minutes under it */
    if (getenv("TT_MEMCHECK")) return;
    for (int in = 0; in < TT_INTEGRATOR_COUNT; in++) {
        bool finite;
        double drift = oscillator_drift((tt_integrator)in, &finite);
        printf("    extremes: oscillator, 1e6 steps at ω·dt 0.1, %-16s largest energy error %9.2e%s\n",
               tt_integrator_name((tt_integrator)in), drift, finite ? "" : "  NOT FINITE");
        ENSURE(finite);
        if (in == TT_VERLET || in == TT_LEAPFROG || in == TT_SYMPLECTIC_EULER) ENSURE(drift < 0.06);
        if (in == TT_RK4) ENSURE(drift < 0.02); /* 1 − (ω·dt)⁶/72 a step in energy: 1.4 % in 10⁶ */
    }
}

