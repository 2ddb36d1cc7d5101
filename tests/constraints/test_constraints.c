/* Position constraints against known answers: rest lengths, the pendulum's
 * period, XPBD's iteration-independent stretch, Gauss-Seidel vs Jacobi,
 * contradictory constraints, areas, tearing, particles linked on one spot,
 * and the bookkeeping around them. */
#include "test.h"
#include "constraints/constraint_internal.h"

#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

static tt_particle add(tt_world *w, double x, double y, double mass, bool pinned)
{
    tt_particle_def pd = tt_particle_def_default();
    pd.position = (tt_vec2){x, y};
    pd.mass = mass;
    pd.pinned = pinned;
    return tt_particle_create(w, &pd);
}

static tt_constraint link(tt_world *w, tt_particle a, tt_particle b, double len)
{
    tt_distance_def d = tt_distance_def_default();
    d.a = a;
    d.b = b;
    d.length = len;
    return tt_distance_create(w, &d);
}

static tt_vec2 pos(const tt_world *w, tt_particle p)
{
    tt_vec2 x = {NAN, NAN};
    tt_particle_get_position(w, p, &x);
    return x;
}

static double dist(const tt_world *w, tt_particle a, tt_particle b)
{
    tt_vec2 x = pos(w, a), y = pos(w, b);
    return hypot(x.x - y.x, x.y - y.y);
}

/* A horizontal rope of n unit links from a pin at the origin. */
static tt_world *rope_world(uint32_t n, uint32_t iterations, tt_solver_order order, tt_particle *ps)
{
    tt_world_def wd = tt_world_def_default();
    wd.iterations = iterations;
    wd.order = order;
    wd.tolerance = 0;
    tt_world *w = tt_world_create(&wd);
    for (uint32_t i = 0; i <= n; i++) ps[i] = add(w, i, 0, 1, i == 0);
    for (uint32_t i = 0; i < n; i++) link(w, ps[i], ps[i + 1], 1.0);
    return w;
}

static double worst_link(const tt_world *w, const tt_particle *ps, uint32_t n)
{
    double e = 0;
    for (uint32_t i = 0; i < n; i++) e = fmax(e, fabs(dist(w, ps[i], ps[i + 1]) - 1.0));
    return e;
}

TEST(rope_settles_at_rest_length_and_error_falls_with_iterations)
{
    enum { N = 10 };
    tt_particle ps[N + 1];
    tt_world *w = rope_world(N, 200, TT_GAUSS_SEIDEL, ps);
    tt_world_set_damping(w, 2.0);
    for (int s = 0; s < 1200; s++) tt_world_step(w, 1.0 / 60);
    ENSURE(worst_link(w, ps, N) < 1e-3); /* 0.1 % of a unit link */
    tt_vec2 end = pos(w, ps[N]);
    ENSURE(fabs(end.x) < 0.05 && end.y < -9.9); /* hangs straight down */
    tt_world_destroy(w);
    /* too few sweeps: the error left after 30 steps shrinks with every doubling */
    double prev = INFINITY;
    for (uint32_t it = 1; it <= 64; it *= 2) {
        tt_world *v = rope_world(N, it, TT_GAUSS_SEIDEL, ps);
        for (int s = 0; s < 30; s++) tt_world_step(v, 1.0 / 60);
        double e = worst_link(v, ps, N);
        ENSURE(e < prev);
        prev = e;
        tt_world_destroy(v);
    }
}

TEST(gauss_seidel_needs_fewer_sweeps_than_jacobi_on_a_hanging_chain)
{
    enum { N = 8 };
    tt_particle ps[N + 1];
    uint32_t used[2];
    for (int k = 0; k < 2; k++) {
        tt_world *w = rope_world(N, 10000, k ? TT_JACOBI : TT_GAUSS_SEIDEL, ps);
        tt_world_set_tolerance(w, 1e-8);
        tt_world_step(w, 1.0 / 60);
        tt_stats st;
        tt_world_get_stats(w, &st);
        ENSURE(st.max_error <= 1e-8);
        ENSURE(worst_link(w, ps, N) <= 1e-7);
        used[k] = st.iterations;
        tt_world_destroy(w);
    }
    ENSURE(used[0] < used[1]);
    ENSURE(used[0] * 2 < used[1]); /* measured: GS 13 vs Jacobi 400+ sweeps */
}

/* Time between upward zero crossings of x, averaged over the run. */
static double pendulum_period(tt_integrator integ, double dt, double theta0, bool pin_constraint)
{
    tt_world_def wd = tt_world_def_default();
    wd.integrator = integ;
    wd.iterations = 50;
    wd.tolerance = 1e-12;
    tt_world *w = tt_world_create(&wd);
    const double L = 1.0;
    tt_particle top = add(w, 0, 0, 1, !pin_constraint);
    tt_particle bob = add(w, L * sin(theta0), -L * cos(theta0), 1, false);
    if (pin_constraint) {
        tt_pin_def pd = tt_pin_def_default();
        pd.particle = top;
        tt_pin_create(w, &pd);
    }
    link(w, top, bob, L);
    double prev = pos(w, bob).x, t = 0, first = -1, last = -1;
    int crossings = 0;
    for (int s = 0; s < (int)(12.0 / dt); s++) {
        tt_world_step(w, dt);
        t += dt;
        double x = pos(w, bob).x;
        if (prev < 0 && x >= 0) {
            double tc = t - dt * x / (x - prev);
            if (first < 0) first = tc;
            else crossings++;
            last = tc;
        }
        prev = x;
    }
    tt_world_destroy(w);
    return crossings ? (last - first) / crossings : -1;
}

TEST(pendulum_swings_with_the_small_angle_period)
{
    const double theta0 = 0.05, T0 = 2 * PI * sqrt(1.0 / 9.81) * (1 + theta0 * theta0 / 16);
    double T = pendulum_period(TT_VERLET, 1.0 / 240, theta0, true);
    ENSURE_NEAR(T, T0, 0.01 * T0);
    /* the other integrators follow through the velocity fix-up, less well (see docs) */
    for (int k = 0; k < TT_INTEGRATOR_COUNT; k++) {
        double Tk = pendulum_period((tt_integrator)k, 1.0 / 240, theta0, false);
        ENSURE_NEAR(Tk, T0, 0.03 * T0);
    }
}

/* A 1 kg weight under a spring to a pin: stretch after settling. */
static double hanging_stretch(double stiffness, double compliance, uint32_t iterations)
{
    tt_world_def wd = tt_world_def_default();
    wd.iterations = iterations;
    wd.tolerance = 0;
    wd.damping = 3.0;
    tt_world *w = tt_world_create(&wd);
    tt_particle a = add(w, 0, 0, 1, true), b = add(w, 0, -1, 1, false);
    tt_distance_def d = tt_distance_def_default();
    d.a = a;
    d.b = b;
    d.stiffness = stiffness;
    d.compliance = compliance;
    tt_distance_create(w, &d);
    for (int s = 0; s < 900; s++) tt_world_step(w, 1.0 / 60);
    double e = dist(w, a, b) - 1.0;
    tt_world_destroy(w);
    return e;
}

TEST(xpbd_stretch_does_not_depend_on_iterations_plain_stiffness_does)
{
    /* Hooke: α·m·g, with g as damped Verlet applies it (g·dt² scaled by 1 − damping·dt) */
    const double alpha = 1e-3, expected = alpha * 1.0 * 9.81 * (1 - 3.0 / 60);
    double e5 = hanging_stretch(1, alpha, 5), e50 = hanging_stretch(1, alpha, 50);
    ENSURE_NEAR(e5, e50, 0.02 * e50);
    ENSURE_NEAR(e50, expected, 0.02 * expected);
    double p5 = hanging_stretch(0.1, 0, 5), p50 = hanging_stretch(0.1, 0, 50);
    ENSURE(fabs(p5 - p50) > 0.5 * p5);
}

/* A compliant link is a spring of stiffness 1/α: a particle on one, pulled
 * 0.1 m past its length and let go, swings with its energy moving between
 * motion and the link. The world's energy counts what the link stores (½
 * C²/α). XPBD's solve is implicit, so the swing is damped: the total never
 * rises, and what it loses in 2 s falls in proportion to the substep
 * (measured, 4 iterations: 70 %, 45 %, 26 %, 14 % at 4, 8, 16, 32 substeps). */
static double xpbd_swing(int substeps, double *stored, double *kmax, double *rise)
{
    tt_world_def wd = tt_world_def_default();
    wd.gravity = (tt_vec2){0, 0};
    wd.substeps = (uint32_t)substeps;
    wd.iterations = 4;
    wd.tolerance = 0;
    tt_world *w = tt_world_create(&wd);
    tt_particle a = add(w, 0, 0, 1, true), b = add(w, 1.1, 0, 1, false);
    tt_distance_def d = tt_distance_def_default();
    d.a = a;
    d.b = b;
    d.length = 1.0;
    d.compliance = 1.0 / 144.0; /* k = 144 N/m: ω = 12 rad/s, a period of 0.52 s */
    tt_distance_create(w, &d);
    tt_energy e;
    tt_world_get_energy(w, &e);
    *stored = e.constraint;
    const double e0 = e.total;
    double prev = e0;
    *kmax = *rise = 0;
    for (int s = 0; s < 120; s++) { /* two seconds, about four periods */
        tt_world_step(w, 1.0 / 60);
        tt_world_get_energy(w, &e);
        *kmax = fmax(*kmax, e.kinetic);
        *rise = fmax(*rise, e.total - prev);
        prev = e.total;
    }
    tt_world_destroy(w);
    return (e0 - e.total) / e0;
}

TEST(xpbd_link_stores_energy_and_its_damping_falls_with_the_substep)
{
    double stored, kmax, rise;
    const double lost16 = xpbd_swing(16, &stored, &kmax, &rise);
    ENSURE_NEAR(stored, 0.5 * 0.1 * 0.1 * 144.0, 1e-9); /* all of it in the link at the start */
    ENSURE(kmax > 0.5 * stored);                         /* it went into motion */
    ENSURE(rise <= 1e-12);                               /* and never came back more than it was */
    const double lost32 = xpbd_swing(32, &stored, &kmax, &rise);
    ENSURE(rise <= 1e-12);
    ENSURE(lost32 > 0.0);
    ENSURE(lost16 / lost32 > 1.6 && lost16 / lost32 < 2.4); /* first order in h */
}

TEST(xpbd_chain_of_compliant_links_matches_hooke)
{
    /* two links, two 1 kg weights: the top one carries 2 m g, the lower m g */
    for (uint32_t it = 5; it <= 50; it *= 10) {
        tt_world_def wd = tt_world_def_default();
        wd.iterations = it;
        wd.tolerance = 0;
        wd.damping = 3.0;
        tt_world *w = tt_world_create(&wd);
        tt_particle p[3] = {add(w, 0, 0, 1, true), add(w, 0, -1, 1, false), add(w, 0, -2, 1, false)};
        for (int i = 0; i < 2; i++) {
            tt_distance_def d = tt_distance_def_default();
            d.a = p[i];
            d.b = p[i + 1];
            d.compliance = 1e-3;
            tt_distance_create(w, &d);
        }
        for (int s = 0; s < 900; s++) tt_world_step(w, 1.0 / 60);
        const double g = 9.81 * (1 - 3.0 / 60); /* as damped Verlet applies it */
        ENSURE_NEAR(dist(w, p[0], p[1]) - 1, 2e-3 * g, 0.02 * 2e-3 * g);
        ENSURE_NEAR(dist(w, p[1], p[2]) - 1, 1e-3 * g, 0.02 * 1e-3 * g);
        tt_world_destroy(w);
    }
}

TEST(contradictory_constraints_stay_finite_and_report_their_error)
{
    for (int order = 0; order < 2; order++) {
        tt_world_def wd = tt_world_def_default();
        wd.order = (tt_solver_order)order;
        wd.iterations = 10;
        tt_world *w = tt_world_create(&wd);
        tt_particle a = add(w, 0, 0, 1, false), b = add(w, 2, 0, 1, false);
        link(w, a, b, 1.0);
        link(w, a, b, 3.0);
        for (int s = 0; s < 600; s++) tt_world_step(w, 1.0 / 60);
        tt_stats st;
        tt_world_get_stats(w, &st);
        ENSURE(st.iterations == 10);
        ENSURE(st.max_error >= 0.9 && st.max_error <= 2.0);
        double d = dist(w, a, b);
        ENSURE(d >= 1.0 && d <= 3.0);
        tt_vec2 x = pos(w, a);
        ENSURE(fabs(x.x) < 100 && fabs(x.y) < 1e4); /* falls under gravity, no explosion */
        ENSURE(st.diverged == 0);
        tt_world_destroy(w);
    }
}

static double area_of(const tt_world *w, const tt_particle *ps, uint32_t n)
{
    double a = 0;
    for (uint32_t i = 0; i < n; i++) {
        tt_vec2 p = pos(w, ps[i]), q = pos(w, ps[(i + 1) % n]);
        a += p.x * q.y - q.x * p.y;
    }
    return 0.5 * a;
}

TEST(soft_body_on_the_floor_keeps_its_area)
{
    tt_world_def wd = tt_world_def_default();
    wd.damping = 1.0;
    tt_world *w = tt_world_create(&wd);
    tt_soft_body_def sd = tt_soft_body_def_default();
    sd.center = (tt_vec2){0, 3};
    sd.common.stiffness = 0.5;
    tt_composite c = tt_soft_body_create(w, &sd);
    ENSURE(c.gen != 0);
    tt_bounds_def bd = tt_bounds_def_default();
    bd.min = (tt_vec2){-10, 0};
    bd.friction = 0.5;
    ENSURE(tt_bounds_create(w, &bd).gen != 0);
    tt_particle ps[16];
    uint32_t n;
    ENSURE_OK(tt_composite_get_particles(w, c, ps, 16, &n));
    ENSURE(n == 16);
    const double rest = area_of(w, ps, n);
    ENSURE_NEAR(rest, 8 * sin(2 * PI / 16), 1e-12);
    for (int s = 0; s < 600; s++) tt_world_step(w, 1.0 / 60);
    double lowest = INFINITY;
    for (uint32_t i = 0; i < n; i++) lowest = fmin(lowest, pos(w, ps[i]).y);
    ENSURE(lowest >= -1e-9 && lowest < 0.01); /* resting on the floor */
    tt_vec2 v;
    tt_particle_get_velocity(w, ps[0], &v);
    ENSURE(hypot(v.x, v.y) < 0.05);
    ENSURE_NEAR(area_of(w, ps, n), rest, 0.05 * rest);
    /* with pressure 1.5 the body inflates toward 1.5 × rest */
    tt_soft_body_def s2 = sd;
    s2.center = (tt_vec2){5, 3};
    s2.pressure = 1.5;
    s2.common.stiffness = 0.02;
    tt_composite c2 = tt_soft_body_create(w, &s2);
    for (int s = 0; s < 600; s++) tt_world_step(w, 1.0 / 60);
    tt_composite_get_particles(w, c2, ps, 16, &n);
    ENSURE(area_of(w, ps, n) > 1.15 * rest);
    tt_world_destroy(w);
}

TEST(cloth_pulled_hard_tears_and_reports_break_events)
{
    tt_world *w = tt_world_create(NULL);
    tt_cloth_def cd = tt_cloth_def_default();
    cd.columns = cd.rows = 10;
    cd.break_strain = 0.3;
    tt_composite c = tt_cloth_create(w, &cd);
    ENSURE(c.gen != 0);
    const uint32_t links = tt_world_constraint_count(w);
    ENSURE(links == 2 * 9 * 10 + 2 * 81 + 2 * 8 * 10);
    const tt_break_event *ev;
    uint32_t nev;
    tt_world_step(w, 1.0 / 60);
    ENSURE_OK(tt_world_get_break_events(w, &ev, &nev));
    ENSURE(nev == 0); /* its own weight does not tear it */
    tt_particle ps[100];
    uint32_t n;
    tt_composite_get_particles(w, c, ps, 100, &n);
    tt_pin_def pd = tt_pin_def_default();
    pd.particle = ps[95]; /* bottom row */
    pd.anchor_here = false;
    pd.anchor = (tt_vec2){0.5, -20};
    tt_constraint grab = tt_pin_create(w, &pd);
    uint32_t total = 0;
    for (int s = 0; s < 60; s++) {
        tt_world_step(w, 1.0 / 60);
        ENSURE_OK(tt_world_get_break_events(w, &ev, &nev));
        for (uint32_t k = 0; k < nev; k++) {
            ENSURE(ev[k].strain > 0.3);
            ENSURE(!tt_constraint_is_valid(w, ev[k].constraint));
            ENSURE(tt_particle_is_valid(w, ev[k].a) && tt_particle_is_valid(w, ev[k].b));
        }
        total += nev;
    }
    ENSURE(total > 0);
    ENSURE(tt_world_constraint_count(w) == links + 1 - total);
    ENSURE(tt_constraint_is_valid(w, grab));
    tt_world_destroy(w);
}

TEST(pinned_particles_never_move_and_heavier_ones_move_less)
{
    tt_world_def wd = tt_world_def_default();
    wd.gravity = (tt_vec2){0, 0};
    wd.iterations = 1;
    tt_world *w = tt_world_create(&wd);
    tt_particle a = add(w, 0, 0, 1, false), b = add(w, 2, 0, 3, false);
    tt_particle p = add(w, 0, 5, 1, true), q = add(w, 3, 5, 1, false);
    link(w, a, b, 1.0);
    link(w, p, q, 1.0);
    tt_world_step(w, 1.0 / 60);
    ENSURE_NEAR(pos(w, a).x, 0.75, 1e-12); /* the light one moves 3× as far */
    ENSURE_NEAR(pos(w, b).x, 1.75, 1e-12);
    ENSURE(pos(w, p).x == 0 && pos(w, p).y == 5);
    ENSURE_NEAR(pos(w, q).x, 1.0, 1e-12);
    tt_world_destroy(w);
}

TEST(distance_modes_rope_goes_slack_strut_only_pushes)
{
    tt_world_def wd = tt_world_def_default();
    wd.gravity = (tt_vec2){0, 0};
    tt_world *w = tt_world_create(&wd);
    tt_particle a = add(w, 0, 0, 1, true), b = add(w, 0.5, 0, 1, false), c = add(w, 3, 0, 1, false);
    tt_distance_def d = tt_distance_def_default();
    d.a = a;
    d.b = b;
    d.length = 1;
    d.mode = TT_DISTANCE_MAX;
    tt_constraint slack = tt_distance_create(w, &d);
    d.b = c;
    d.mode = TT_DISTANCE_MIN;
    d.length = 4;
    tt_constraint strut = tt_distance_create(w, &d);
    double e;
    ENSURE_OK(tt_constraint_get_error(w, slack, &e));
    ENSURE(e == 0);
    ENSURE_OK(tt_constraint_get_error(w, strut, &e));
    ENSURE_NEAR(e, 1.0, 1e-15);
    tt_world_step(w, 1.0 / 60);
    ENSURE_NEAR(dist(w, a, b), 0.5, 1e-15); /* slack: untouched */
    ENSURE_NEAR(dist(w, a, c), 4.0, 1e-12);
    tt_particle_set_position(w, c, (tt_vec2){5, 0}, TT_MOVE_RESET_VELOCITY);
    tt_world_step(w, 1.0 / 60);
    ENSURE_NEAR(dist(w, a, c), 5.0, 1e-12); /* longer than 4 is allowed */
    tt_world_destroy(w);
}

TEST(pin_anchor_drags_its_particle)
{
    tt_world *w = tt_world_create(NULL);
    tt_particle p = add(w, 1, 1, 1, false);
    tt_pin_def pd = tt_pin_def_default();
    pd.particle = p;
    tt_constraint pin = tt_pin_create(w, &pd);
    for (int s = 0; s < 10; s++) tt_world_step(w, 1.0 / 60);
    ENSURE_NEAR(pos(w, p).x, 1, 1e-12);
    ENSURE_NEAR(pos(w, p).y, 1, 1e-12);
    ENSURE_OK(tt_pin_set_anchor(w, pin, (tt_vec2){4, -2}));
    tt_world_step(w, 1.0 / 60);
    ENSURE_NEAR(pos(w, p).x, 4, 1e-12);
    ENSURE_NEAR(pos(w, p).y, -2, 1e-12);
    tt_vec2 anc;
    ENSURE_OK(tt_pin_get_anchor(w, pin, &anc));
    ENSURE(anc.x == 4 && anc.y == -2);
    ENSURE(tt_pin_set_anchor(w, pin, (tt_vec2){NAN, 0}) == TT_EINVAL);
    tt_constraint_kind k;
    ENSURE_OK(tt_constraint_get_kind(w, pin, &k));
    ENSURE(k == TT_CONSTRAINT_PIN);
    ENSURE(tt_distance_set_length(w, pin, 1) == TT_EINVAL); /* wrong kind */
    tt_world_destroy(w);
}

TEST(bounds_keep_particles_inside_and_blocks_keep_them_out)
{
    tt_world *w = tt_world_create(NULL);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.25f;
    pd.position = (tt_vec2){0, 5};
    pd.velocity = (tt_vec2){3, 0};
    tt_particle p = tt_particle_create(w, &pd);
    pd.position = (tt_vec2){5, 5};
    pd.velocity = (tt_vec2){0, 0};
    tt_particle q = tt_particle_create(w, &pd);
    tt_bounds_def bd = tt_bounds_def_default();
    bd.min = (tt_vec2){-1, 0};
    bd.max = (tt_vec2){2, 10};
    bd.particles = &p;
    bd.count = 1;
    tt_constraint box = tt_bounds_create(w, &bd);
    tt_bounds_def block = tt_bounds_def_default();
    block.min = (tt_vec2){4, 0};
    block.max = (tt_vec2){6, 2};
    block.outside = true;
    block.particles = &q;
    block.count = 1;
    tt_constraint solid = tt_bounds_create(w, &block);
    for (int s = 0; s < 300; s++) {
        tt_world_step(w, 1.0 / 60);
        tt_vec2 x = pos(w, p);
        ENSURE(x.x <= 2 - 0.25 + 1e-12 && x.y >= 0.25 - 1e-12);
    }
    ENSURE_NEAR(pos(w, q).y, 2.25, 1e-9); /* sits on top of the block */
    ENSURE_NEAR(pos(w, p).y, 0.25, 1e-9);
    double e;
    ENSURE_OK(tt_constraint_get_error(w, box, &e));
    ENSURE(e < 1e-9);
    ENSURE_OK(tt_constraint_get_error(w, solid, &e));
    ENSURE(e < 1e-9);
    bd.min = (tt_vec2){3, 0};
    ENSURE(tt_bounds_create(w, &bd).gen == 0); /* min > max */
    ENSURE(strstr(tt_last_error(w), "min < max"));
    tt_world_destroy(w);
}

TEST(angle_limit_keeps_an_elbow_from_bending_backwards)
{
    tt_world_def wd = tt_world_def_default();
    wd.gravity = (tt_vec2){0, 0};
    tt_world *w = tt_world_create(&wd);
    tt_particle a = add(w, -1, 0, 1, true), b = add(w, 0, 0, 1, true), c = add(w, 1, 0.5, 1, false);
    tt_angle_def ad = tt_angle_def_default();
    ad.a = a;
    ad.b = b;
    ad.c = c;
    ad.use_current = false;
    ad.min = PI / 2; /* c may swing from straight down (π/2 from a's direction) … */
    ad.max = PI;     /* … to the straight line, never above it */
    tt_constraint lim = tt_angle_create(w, &ad);
    link(w, b, c, -1);
    double e;
    ENSURE_OK(tt_constraint_get_error(w, lim, &e));
    ENSURE_NEAR(e, atan(0.5), 1e-12); /* the angle from (−1,0) to (1,0.5) is −π + atan(0.5): that far past π */
    tt_world_step(w, 1.0 / 60);
    ENSURE_OK(tt_constraint_get_error(w, lim, &e));
    ENSURE(e < 1e-9);
    tt_vec2 x = pos(w, c);
    ENSURE(x.y <= 1e-9); /* pushed back onto the line */
    tt_world_destroy(w);
}

TEST(collinear_pulls_the_middle_particle_onto_the_line)
{
    tt_world_def wd = tt_world_def_default();
    wd.gravity = (tt_vec2){0, 0};
    tt_world *w = tt_world_create(&wd);
    tt_particle a = add(w, 0, 0, 1, true), b = add(w, 1, 0.3, 1, false), c = add(w, 2, 0, 1, true);
    tt_collinear_def cd = tt_collinear_def_default();
    cd.a = a;
    cd.b = b;
    cd.c = c;
    cd.stiffness = 0.5;
    tt_constraint k = tt_collinear_create(w, &cd);
    double e;
    ENSURE_OK(tt_constraint_get_error(w, k, &e));
    ENSURE_NEAR(e, 0.3, 1e-15);
    tt_world_set_iterations(w, 1);
    tt_world_step(w, 1.0 / 60);
    ENSURE_NEAR(pos(w, b).y, 0.15, 1e-12); /* half the error per sweep */
    tt_world_set_iterations(w, 60);
    tt_world_step(w, 1.0 / 60);
    ENSURE(fabs(pos(w, b).y) < 1e-12);
    tt_world_destroy(w);
}

TEST(removing_a_particle_drops_its_constraints_and_collision_exclusions)
{
    tt_world *w = tt_world_create(NULL);
    tt_particle a = add(w, 0, 0, 1, false), b = add(w, 1, 0, 1, false), c = add(w, 2, 0, 1, false);
    tt_constraint ab = link(w, a, b, -1), bc = link(w, b, c, -1);
    tt_distance_def d = tt_distance_def_default();
    d.a = a;
    d.b = c;
    d.collide = true;
    tt_constraint ac = tt_distance_create(w, &d);
    ENSURE(tt__constraint_pair_excluded(w, a.index, b.index) && tt__constraint_pair_excluded(w, c.index, b.index));
    ENSURE(!tt__constraint_pair_excluded(w, a.index, c.index)); /* collide = true */
    tt_bounds_def bd = tt_bounds_def_default();
    tt_particle abc[3] = {a, b, c};
    bd.particles = abc;
    bd.count = 3;
    tt_constraint box = tt_bounds_create(w, &bd);
    ENSURE(tt_world_constraint_count(w) == 4);
    ENSURE_OK(tt_particle_destroy(w, b));
    ENSURE(!tt_constraint_is_valid(w, ab) && !tt_constraint_is_valid(w, bc) && tt_constraint_is_valid(w, ac));
    ENSURE(tt_constraint_is_valid(w, box));
    uint32_t n;
    ENSURE_OK(tt_constraint_get_particles(w, box, NULL, 0, &n));
    ENSURE(n == 2);
    ENSURE(!tt__constraint_pair_excluded(w, a.index, b.index));
    ENSURE(tt_constraint_destroy(w, ab) == TT_ESTALE);
    /* a new particle in b's slot is not bound by the old constraints */
    tt_particle e = add(w, 5, 5, 1, false);
    ENSURE(e.index == b.index);
    ENSURE(!tt__constraint_pair_excluded(w, a.index, e.index));
    ENSURE(tt_world_constraint_count(w) == 2);
    tt_world_destroy(w);
}

TEST(excluded_pairs_survive_many_adds_and_removes)
{
    tt_world_def wd = tt_world_def_default();
    wd.gravity = (tt_vec2){0, 0};
    tt_world *w = tt_world_create(&wd);
    enum { N = 300 };
    tt_particle ps[N];
    for (int i = 0; i < N; i++) ps[i] = add(w, i, 0, 1, false);
    tt_constraint cs[N - 1];
    for (int i = 0; i + 1 < N; i++) cs[i] = link(w, ps[i], ps[i + 1], -1);
    link(w, ps[0], ps[1], -1); /* a second constraint on the same pair */
    for (int i = 0; i + 1 < N; i += 2) tt_constraint_destroy(w, cs[i]);
    for (int i = 0; i + 1 < N; i++) ENSURE(tt__constraint_pair_excluded(w, ps[i].index, ps[i + 1].index) == (i % 2 == 1 || i == 0));
    ENSURE(!tt__constraint_pair_excluded(w, ps[0].index, ps[2].index));
    tt_world_destroy(w);
}

TEST(constraints_work_with_every_integrator_and_jacobi)
{
    for (int order = 0; order < 2; order++)
        for (int k = 0; k < TT_INTEGRATOR_COUNT; k++) {
            tt_world_def wd = tt_world_def_default();
            wd.integrator = (tt_integrator)k;
            wd.order = (tt_solver_order)order;
            wd.iterations = order ? 200 : 40;
            wd.damping = 1;
            tt_world *w = tt_world_create(&wd);
            tt_rope_def rd = tt_rope_def_default();
            rd.segments = 5;
            tt_composite r = tt_rope_create(w, &rd);
            tt_particle ps[6];
            uint32_t n;
            tt_composite_get_particles(w, r, ps, 6, &n);
            for (int s = 0; s < 600; s++) tt_world_step(w, 1.0 / 60);
            for (int i = 0; i < 5; i++) ENSURE_NEAR(dist(w, ps[i], ps[i + 1]), 0.2, 2e-3);
            ENSURE(pos(w, ps[0]).x == 0 && pos(w, ps[0]).y == 0);
            ENSURE(pos(w, ps[5]).y < -0.95); /* hangs */
            tt_world_destroy(w);
        }
}

TEST(lines_errors_and_bad_input)
{
    tt_world *w = tt_world_create(NULL);
    tt_particle a = add(w, 0, 0, 1, false), b = add(w, 3, 4, 1, false);
    tt_constraint c = link(w, a, b, 4);
    tt_pin_def pd = tt_pin_def_default();
    pd.particle = a;
    pd.anchor_here = false;
    pd.anchor = (tt_vec2){-1, 0};
    tt_pin_create(w, &pd);
    double xy[8];
    ENSURE(tt_world_read_constraint_lines(w, NULL, 0) == 2);
    ENSURE(tt_world_read_constraint_lines(w, xy, 2) == 2);
    ENSURE(xy[0] == 0 && xy[1] == 0 && xy[2] == 3 && xy[3] == 4);
    ENSURE(xy[4] == 0 && xy[5] == 0 && xy[6] == -1 && xy[7] == 0);
    double e;
    ENSURE_OK(tt_constraint_get_error(w, c, &e));
    ENSURE_NEAR(e, 1.0, 1e-15);
    double len;
    ENSURE_OK(tt_distance_get_length(w, c, &len));
    ENSURE(len == 4);
    tt_distance_def d = tt_distance_def_default();
    d.a = a;
    d.b = a;
    ENSURE(tt_distance_create(w, &d).gen == 0 && strstr(tt_last_error(w), "distinct"));
    d.b = b;
    d.stiffness = 1.5;
    ENSURE(tt_distance_create(w, &d).gen == 0 && strstr(tt_last_error(w), "stiffness"));
    d.stiffness = NAN;
    ENSURE(tt_distance_create(w, &d).gen == 0);
    d.stiffness = 1;
    d.compliance = INFINITY;
    ENSURE(tt_distance_create(w, &d).gen == 0 && strstr(tt_last_error(w), "compliance"));
    d.compliance = 0;
    d.length = -2;
    ENSURE(tt_distance_create(w, &d).gen == 0 && strstr(tt_last_error(w), "length"));
    ENSURE(tt_constraint_set_stiffness(w, c, -0.1) == TT_EINVAL);
    ENSURE_OK(tt_constraint_set_compliance(w, c, 0.01));
    tt_area_def ad = tt_area_def_default();
    tt_particle two[2] = {a, b};
    ad.particles = two;
    ad.count = 2;
    ENSURE(tt_area_create(w, &ad).gen == 0);
    ENSURE(tt_constraint_get_error(w, (tt_constraint){99, 1}, &e) == TT_ESTALE);
    tt_world *other = tt_world_create(NULL);
    ENSURE(!tt_constraint_is_valid(other, c)); /* another world (and one without constraints) */
    tt_world_destroy(other);
    tt_world_destroy(w);
}

TEST(constraint_worlds_are_deterministic_and_cost_nothing_unused)
{
    uint64_t h[2];
    for (int r = 0; r < 2; r++) {
        tt_world *w = tt_world_create(NULL);
        tt_cloth_def cd = tt_cloth_def_default();
        cd.break_strain = 0.2;
        tt_composite c = tt_cloth_create(w, &cd);
        tt_particle ps[256];
        uint32_t n;
        tt_composite_get_particles(w, c, ps, 256, &n);
        tt_pin_def pd = tt_pin_def_default();
        pd.particle = ps[250];
        pd.anchor_here = false;
        pd.anchor = (tt_vec2){3, -5};
        tt_pin_create(w, &pd);
        for (int s = 0; s < 120; s++) tt_world_step(w, 1.0 / 60);
        h[r] = tt_world_hash(w);
        tt_memory m;
        tt_world_get_memory(w, &m);
        ENSURE(m.total > 256 * 40);
        tt_world_destroy(w);
    }
    ENSURE(h[0] == h[1]);
    tt_world *w = tt_world_create(NULL);
    ENSURE(tt_world_constraint_count(w) == 0 && w->group_count == 1 && strcmp(w->groups[0].ops->name, "sleep") == 0);
    ENSURE(tt_world_read_constraint_lines(w, NULL, 0) == 0);
    tt_world_destroy(w);
}

TEST(removing_particles_keeps_constraint_references_exact)
{
    /* a 64² cloth and 2000 free particles (removing those skips the scan of the links) */
    tt_world *w = tt_world_create(NULL);
    tt_cloth_def cd = tt_cloth_def_default();
    cd.columns = cd.rows = 64;
    tt_composite c = tt_cloth_create(w, &cd);
    tt_particle free_ps[2000];
    for (int i = 0; i < 2000; i++) free_ps[i] = add(w, i, 10, 1, false);
    const uint32_t links = tt_world_constraint_count(w);
    for (int i = 0; i < 2000; i++) ENSURE_OK(tt_particle_destroy(w, free_ps[i]));
    ENSURE(tt_world_constraint_count(w) == links);
    /* removing a cloth particle still drops exactly its links: a corner has 2 + 1 + 2 */
    tt_particle corner;
    uint32_t n;
    tt_composite_get_particles(w, c, &corner, 1, &n);
    ENSURE_OK(tt_particle_destroy(w, corner));
    ENSURE(tt_world_constraint_count(w) == links - 5);
    ENSURE_OK(tt_composite_destroy(w, c)); /* its links first, then particles: no scans */
    ENSURE(tt_world_constraint_count(w) == 0 && tt_world_particle_count(w) == 0);
    /* a bounds list and an area that lose a member */
    tt_particle p[4] = {add(w, 0, 0, 1, false), add(w, 1, 0, 1, false), add(w, 1, 1, 1, false), add(w, 0, 1, 1, false)};
    tt_bounds_def bd = tt_bounds_def_default();
    bd.particles = p;
    bd.count = 4;
    tt_constraint box = tt_bounds_create(w, &bd);
    tt_area_def ad = tt_area_def_default();
    ad.particles = p;
    ad.count = 4;
    tt_constraint area = tt_area_create(w, &ad);
    ENSURE_OK(tt_particle_destroy(w, p[2]));
    ENSURE(tt_constraint_is_valid(w, box) && !tt_constraint_is_valid(w, area));
    ENSURE_OK(tt_particle_destroy(w, p[0]));
    ENSURE_OK(tt_particle_destroy(w, p[1]));
    ENSURE_OK(tt_particle_destroy(w, p[3]));
    ENSURE(!tt_constraint_is_valid(w, box)); /* emptied */
    ENSURE(tt_world_constraint_count(w) == 0);
    tt_world_destroy(w);
}

/* ---- the SIMD Gauss-Seidel sweep against the scalar loop ------------------- */

/* A scene that reaches every branch of the distance sweep inside vector
 * blocks: a cloth with a pinned top row (links between two pinned particles:
 * no mass to move), runs of four or more extra links that are max-only (slack
 * ones: c = 0), min-only, compliant (XPBD) or soft, and pairs of particles on
 * one spot linked at 0.3 m (length 0: no direction, so the lanes take the
 * scalar's fixed one; without it a lane there turns NaN), and pinned pairs
 * far from their length (no error counted). Along the way the script changes
 * lengths, stiffness and compliance, destroys links and a particle, and
 * tears the cloth, so the plan and its copies are rebuilt and updated.
 * with_pin adds pins (other constraint kinds in the group: the rows go back
 * to the world every sweep).
 * Returns the world hash folded with every step's largest error; *vec: how
 * many links the last plan solved in vector blocks; *bad: calls that failed. */
static uint64_t simd_scene(tt__simd_mode mode, bool with_pin, uint32_t *vec, uint32_t *torn, int *bad)
{
    tt_world_def wd = tt_world_def_default();
    wd.iterations = 6;
    wd.substeps = 2;
    wd.tolerance = 0;
    tt_world *w = tt_world_create(&wd);
    if (!tt__constraints_set_simd(w, mode)) {
        tt_world_destroy(w);
        return 0;
    }
    enum { C = 24, R = 18 };
    tt_cloth_def cd = tt_cloth_def_default();
    cd.columns = C;
    cd.rows = R;
    cd.width = 2.3;
    cd.height = 1.7;
    cd.pin_top_row = true;
    cd.break_strain = 0.15;
    cd.common.mass = 0.01;
    tt_composite cl = tt_cloth_create(w, &cd);
    tt_particle ps[C * R];
    uint32_t n;
    tt_composite_get_particles(w, cl, ps, C * R, &n);
    tt_constraint extra[4][8];
    for (int kind = 0; kind < 4; kind++)
        for (int j = 0; j < 8; j++) { /* rows 4 + 3·kind and the next: all 32 links disjoint */
            tt_distance_def d = tt_distance_def_default();
            d.a = ps[(4 + 3 * kind) * C + 2 * j];
            d.b = ps[(5 + 3 * kind) * C + 2 * j + 1];
            tt_vec2 pa = pos(w, d.a), pb = pos(w, d.b);
            double len = hypot(pb.x - pa.x, pb.y - pa.y);
            if (kind == 0) d.mode = TT_DISTANCE_MAX, d.length = len * (j % 2 ? 1.5 : 0.7);
            if (kind == 1) d.mode = TT_DISTANCE_MIN, d.length = len * (j % 2 ? 0.8 : 1.3);
            if (kind == 2) d.compliance = 1e-4 * (1 + j);
            if (kind == 3) d.stiffness = 0.3, d.length = j % 3 ? len * 0.9 : 0.0;
            extra[kind][j] = tt_distance_create(w, &d);
        }
    for (int j = 0; j < 4; j++) { /* pinned pairs held 4 m from their length: no mass, so no error either */
        tt_distance_def d = tt_distance_def_default();
        d.a = add(w, -5 - j, 2, 1, true);
        d.b = add(w, -5 - j, 3, 1, true);
        d.length = 5;
        tt_distance_create(w, &d);
    }
    for (int j = 0; j < 8; j++) { /* 8 pairs on one spot each: blocks of length-0 lanes */
        tt_particle a = add(w, 5 + j, 1, 1, false), b = add(w, 5 + j, 1, 2, false);
        tt_distance_def d = tt_distance_def_default();
        d.a = a;
        d.b = b;
        d.length = 0.3;
        tt_distance_create(w, &d);
    }
    if (with_pin) {
        tt_pin_def pd = tt_pin_def_default();
        pd.particle = ps[(R - 1) * C + C / 2]; /* drags the hem down: the cloth tears */
        pd.anchor_here = false;
        pd.anchor = (tt_vec2){1.0, -6};
        tt_pin_create(w, &pd);
    }
    uint64_t h = 1469598103934665603ull;
    *torn = 0;
    for (int s = 0; s < 90; s++) {
        if (s == 20) {
            *bad += tt_distance_set_length(w, extra[0][2], 0.01) != TT_OK;
            *bad += tt_constraint_set_stiffness(w, extra[3][1], 0.9) != TT_OK;
            *bad += tt_constraint_set_compliance(w, extra[2][3], 0.0) != TT_OK;
            *bad += tt_constraint_set_compliance(w, extra[3][4], 2e-3) != TT_OK;
        }
        if (s == 40) {
            *bad += tt_constraint_destroy(w, extra[1][5]) != TT_OK;
            *bad += tt_particle_destroy(w, ps[9 * C + 7]) != TT_OK;
        }
        if (s == 60) { /* no compliant link left: the kernels without the XPBD branch */
            for (int j = 0; j < 8; j++) *bad += tt_constraint_set_compliance(w, extra[2][j], 0.0) != TT_OK;
            *bad += tt_constraint_set_compliance(w, extra[3][4], 0.0) != TT_OK;
        }
        tt_world_step(w, 1.0 / 60);
        tt_stats st;
        tt_world_get_stats(w, &st);
        for (size_t k = 0; k < sizeof st.max_error; k++) h = (h ^ ((const uint8_t *)&st.max_error)[k]) * 1099511628211ull;
        const tt_break_event *ev;
        uint32_t nev;
        tt_world_get_break_events(w, &ev, &nev);
        *torn += nev;
    }
    const tt__cgroup *g = tt__cgroup_peek(w);
    *vec = 0;
    if (g->scr.plan_ok && mode != TT__SIMD_SCALAR)
        for (uint32_t k = 0; k < g->scr.nplan; k += 2) *vec += 4 * (g->scr.plan[k + 1] & 0x7fffffffu);
    h ^= tt_world_hash(w);
    tt_world_destroy(w);
    return h;
}

TEST(simd_sweep_is_bit_identical_to_the_scalar_loop)
{
    for (int pin = 0; pin < 2; pin++) {
        uint32_t vec, torn, tv;
        int bad = 0;
        const uint64_t ref = simd_scene(TT__SIMD_SCALAR, pin, &vec, &torn, &bad);
        ENSURE(ref != 0 && bad == 0);
        if (pin) ENSURE(torn > 0);
        const tt__simd_mode modes[] = {TT__SIMD_AUTO, TT__SIMD_AVX2, TT__SIMD_AVX512};
        for (int m = 0; m < 3; m++) {
            const uint64_t hm = simd_scene(modes[m], pin, &vec, &tv, &bad);
            if (hm == 0) continue; /* not in this build or on this processor */
            ENSURE(bad == 0);
            ENSURE(hm == ref);
            ENSURE(tv == torn);
            if (modes[m] != TT__SIMD_AUTO) /* (auto is the scalar loop where there is no vector path) */
                ENSURE(vec > 1000); /* the comparison is not vacuous: most links went through the vector path */
        }
    }
}

/* n pairs of particles, each pair on one spot (pair k at (3k, 1)), joined
 * by distance constraints of length 1 made as def says; a of each pair in
 * ps[2k], b in ps[2k + 1]. */
static tt_world *coincident_pairs(tt_integrator integ, tt_solver_order order, tt__simd_mode mode, int n,
                                  const tt_distance_def *def, tt_particle *ps)
{
    tt_world_def wd = tt_world_def_default();
    wd.integrator = integ;
    wd.order = order;
    tt_world *w = tt_world_create(&wd);
    if (!tt__constraints_set_simd(w, mode)) {
        tt_world_destroy(w);
        return NULL;
    }
    for (int k = 0; k < n; k++) {
        ps[2 * k] = add(w, 3.0 * k, 1, 1, false);
        ps[2 * k + 1] = add(w, 3.0 * k, 1, 1 + k % 3, false);
        tt_distance_def d = *def;
        d.a = ps[2 * k];
        d.b = ps[2 * k + 1];
        d.length = 1;
        tt_distance_create(w, &d);
    }
    return w;
}

/* Issue 14, finding 10: two particles on one spot have no direction between
 * them, and the sweep skipped the link, so a length-1 link between them
 * never separated them (the error stayed 1 for ever). Still together when
 * a substep's sweeps begin, they now part along +x (b to the right of a),
 * with every integrator, Gauss-Seidel and Jacobi, rigid, strut and XPBD. */
TEST(coincident_particles_joined_by_a_link_separate)
{
    tt_distance_def modes[3] = {tt_distance_def_default(), tt_distance_def_default(), tt_distance_def_default()};
    modes[1].mode = TT_DISTANCE_MIN; /* a strut pushes them apart too */
    modes[2].compliance = 1e-7;      /* XPBD: as far as its compliance lets it */
    tt_particle ps[2];
    for (int i = 0; i < TT_INTEGRATOR_COUNT; i++)
        for (int order = 0; order < 2; order++)
            for (int m = 0; m < 3; m++) {
                const tt_solver_order o = order ? TT_JACOBI : TT_GAUSS_SEIDEL;
                tt_world *w = coincident_pairs((tt_integrator)i, o, TT__SIMD_AUTO, 1, &modes[m], ps);
                ENSURE(w);
                ENSURE_OK(tt_world_step(w, 1.0 / 60));
                const double d1 = dist(w, ps[0], ps[1]);
                for (int s = 0; s < 30; s++) ENSURE_OK(tt_world_step(w, 1.0 / 60));
                tt_vec2 a = pos(w, ps[0]), b = pos(w, ps[1]);
                /* the strut's push leaves them moving apart, and it never pulls back */
                const double d = m == 1 ? fmin(dist(w, ps[0], ps[1]), 1.0) : dist(w, ps[0], ps[1]);
                if (!(fabs(d1 - 1.0) < 1e-2 && fabs(d - 1.0) < 1e-3 && b.x > a.x && a.y == b.y))
                    tt_test_fail(__FILE__, __LINE__, "%s, %s, link %d: a (%g, %g), b (%g, %g)",
                                 tt_integrator_name((tt_integrator)i), order ? "Jacobi" : "Gauss-Seidel", m, a.x, a.y, b.x, b.y);
                tt_world_destroy(w);
            }
}

/* The same in blocks of vector lanes: every mode moves each pair exactly as the scalar loop does. */
TEST(coincident_pairs_separate_the_same_in_vector_lanes)
{
    enum { N = 24 };
    tt_particle ps[2 * N];
    for (int x = 0; x < 2; x++) {
        tt_distance_def d = tt_distance_def_default();
        d.compliance = x ? 1e-6 : 0.0;
        uint64_t ref = 0;
        const tt__simd_mode modes[] = {TT__SIMD_SCALAR, TT__SIMD_AVX2, TT__SIMD_AVX512};
        for (int m = 0; m < 3; m++) {
            tt_world *w = coincident_pairs(TT_VERLET, TT_GAUSS_SEIDEL, modes[m], N, &d, ps);
            if (!w) continue; /* not in this build or on this processor */
            ENSURE_OK(tt_world_step(w, 1.0 / 60));
            for (int k = 0; k < N; k++) ENSURE_NEAR(dist(w, ps[2 * k], ps[2 * k + 1]), 1.0, x ? 1e-2 : 1e-12);
            const tt__cgroup *g = tt__cgroup_peek(w);
            uint32_t vec = 0;
            for (uint32_t k = 0; g->scr.plan_ok && k < g->scr.nplan; k += 2) vec += 4 * (g->scr.plan[k + 1] & 0x7fffffffu);
            ENSURE(m == 0 || vec >= N / 2); /* not vacuous: the vector blocks had such pairs */
            for (int s = 0; s < 10; s++) ENSURE_OK(tt_world_step(w, 1.0 / 60));
            const uint64_t h = tt_world_hash(w);
            if (m == 0) ref = h;
            ENSURE(h == ref);
            tt_world_destroy(w);
        }
    }
}
