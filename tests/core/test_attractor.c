/* Point attractors against Kepler's laws and the softened potential. */
#include <stdlib.h>

#include "test.h"
#include "tether.h"

#define PI 3.14159265358979323846

static tt_world *world0(tt_integrator integ)
{
    tt_world_def d = tt_world_def_default();
    d.gravity = (tt_vec2){0, 0};
    d.integrator = integ;
    return tt_world_create(&d);
}

static tt_particle add(tt_world *w, double x, double y, double vx, double vy, double mass)
{
    tt_particle_def d = tt_particle_def_default();
    d.position = (tt_vec2){x, y};
    d.velocity = (tt_vec2){vx, vy};
    d.mass = mass;
    return tt_particle_create(w, &d);
}

/* GM = 1, a = 1, e = 0.5 from perihelion (0.5, 0) at √3 m/s: period 2π,
 * energy −GM/(2a) = −0.5 J/kg. */
static tt_world *kepler(tt_integrator integ, double mass, tt_particle *p)
{
    tt_world *w = world0(integ);
    tt_attractor a = {{0, 0}, 1.0, 0.0};
    if (tt_world_set_attractor(w, 0, a) != TT_OK) return NULL;
    *p = add(w, 0.5, 0, 0, sqrt(3.0), mass);
    return w;
}

TEST(attractor_kepler_orbit_closes_after_one_period)
{
    const int n = 4000;
    for (int k = 0; k < 2; k++) {
        tt_particle p;
        tt_world *w = kepler(TT_RK4, k ? 7.0 : 1.0, &p); /* the pull does not depend on mass */
        ENSURE(w);
        tt_energy e;
        ENSURE_OK(tt_world_get_energy(w, &e));
        ENSURE_NEAR(e.attractor, -2.0 * (k ? 7.0 : 1.0), 1e-12);
        ENSURE_NEAR(e.total, -0.5 * (k ? 7.0 : 1.0), 1e-12);
        double far = 0.0;
        for (int i = 0; i < n; i++) {
            ENSURE_OK(tt_world_step(w, 2 * PI / n));
            tt_vec2 x;
            tt_particle_get_position(w, p, &x);
            if (-x.x > far) far = -x.x;
        }
        tt_vec2 x;
        tt_particle_get_position(w, p, &x);
        ENSURE_NEAR(x.x, 0.5, 1e-6);
        ENSURE_NEAR(x.y, 0.0, 1e-6);
        ENSURE_NEAR(far, 1.5, 1e-4); /* aphelion a(1 + e) */
        ENSURE_OK(tt_world_get_energy(w, &e));
        ENSURE_NEAR(e.total, -0.5 * (k ? 7.0 : 1.0), 1e-8);
        tt_world_destroy(w);
    }
}

/* The symplectic integrators keep the orbit's energy bounded over many
 * orbits; explicit Euler gains it. */
TEST(attractor_energy_over_ten_orbits_per_integrator)
{
    const int n = 1000;
    for (int i = 0; i < TT_INTEGRATOR_COUNT; i++) {
        tt_particle p;
        tt_world *w = kepler((tt_integrator)i, 1.0, &p);
        ENSURE(w);
        double worst = 0.0;
        for (int s = 0; s < 10 * n; s++) {
            ENSURE_OK(tt_world_step(w, 2 * PI / n));
            tt_energy e;
            tt_world_get_energy(w, &e);
            if (fabs(e.total + 0.5) > worst) worst = fabs(e.total + 0.5);
        }
        if (i == TT_EULER) {
            ENSURE(worst > 0.05);
        } else if (i == TT_RK4) {
            ENSURE(worst < 1e-5);
        } else {
            ENSURE(worst < 0.1); /* Verlet's lagging velocity reads the most, near perihelion */
        }
        tt_world_destroy(w);
    }
}

/* Softened: a particle released at rest at r falls through the centre with
 * the speed the potential −GM/√(r² + ε²) gives, and stops at −r. */
TEST(attractor_softened_fall_through_the_centre)
{
    tt_world *w = world0(TT_RK4);
    const double gm = 2.0, eps = 0.1, r = 1.0;
    ENSURE_OK(tt_world_set_attractor(w, 3, (tt_attractor){{0, 0}, gm, eps}));
    tt_particle p = add(w, r, 0, 0, 0, 1.0);
    double vmax = 0.0, xmin = r;
    for (int s = 0; s < 20000; s++) {
        ENSURE_OK(tt_world_step(w, 1e-4));
        tt_vec2 x, v;
        tt_particle_get_position(w, p, &x);
        tt_particle_get_velocity(w, p, &v);
        if (fabs(v.x) > vmax) vmax = fabs(v.x);
        if (x.x < xmin) xmin = x.x;
        ENSURE(x.y == 0.0);
    }
    ENSURE_NEAR(vmax, sqrt(2 * gm * (1 / eps - 1 / sqrt(r * r + eps * eps))), 1e-4); /* sampled at steps */
    ENSURE_NEAR(xmin, -r, 1e-6);
    tt_world_destroy(w);
}

TEST(attractor_repels_with_negative_strength_and_spares_pinned)
{
    tt_world *w = world0(TT_VERLET);
    ENSURE_OK(tt_world_set_attractor(w, 0, (tt_attractor){{0, 0}, -1.0, 0.0}));
    tt_particle p = add(w, 1, 0, 0, 0, 1.0);
    tt_particle_def d = tt_particle_def_default();
    d.position = (tt_vec2){0, 1};
    d.pinned = true;
    tt_particle q = tt_particle_create(w, &d);
    for (int s = 0; s < 10; s++) ENSURE_OK(tt_world_step(w, 0.01));
    tt_vec2 x;
    tt_particle_get_position(w, p, &x);
    ENSURE(x.x > 1.0 + 1e-4);
    tt_particle_get_position(w, q, &x);
    ENSURE(x.x == 0.0 && x.y == 1.0);
    tt_world_destroy(w);
}

static void *saved(tt_world *w, size_t *n)
{
    if (tt_world_save(w, NULL, 0, n) != TT_ENOMEM) return NULL;
    void *b = malloc(*n);
    if (b && tt_world_save(w, b, *n, n) != TT_OK) { free(b); return NULL; }
    return b;
}

/* Bad input changes nothing; a cleared slot leaves the world hashing as if
 * there never was one; a loaded world goes on pulling bit for bit the same. */
TEST(attractor_validation_hash_and_snapshot)
{
    tt_world *w = world0(TT_VERLET);
    add(w, 1, 0, 0, 1, 1.0);
    uint64_t h0 = tt_world_hash(w);
    ENSURE(tt_world_set_attractor(w, TT_MAX_ATTRACTORS, (tt_attractor){{0, 0}, 1, 0}) == TT_EINVAL);
    ENSURE(tt_world_set_attractor(w, 0, (tt_attractor){{NAN, 0}, 1, 0}) == TT_EINVAL);
    ENSURE(tt_world_set_attractor(w, 0, (tt_attractor){{0, 0}, INFINITY, 0}) == TT_EINVAL);
    ENSURE(tt_world_set_attractor(w, 0, (tt_attractor){{0, 0}, 1, -1}) == TT_EINVAL);
    ENSURE(tt_world_set_attractor(NULL, 0, (tt_attractor){{0, 0}, 1, 0}) == TT_EINVAL);
    ENSURE(tt_world_get_attractor(w, 0, NULL) == TT_EINVAL);
    ENSURE(tt_world_hash(w) == h0);
    ENSURE_OK(tt_world_set_attractor(w, 5, (tt_attractor){{2, 3}, 4, 0.5}));
    ENSURE(tt_world_hash(w) != h0);
    tt_attractor a;
    ENSURE_OK(tt_world_get_attractor(w, 5, &a));
    ENSURE(a.center.x == 2 && a.center.y == 3 && a.strength == 4 && a.softening == 0.5);
    ENSURE_OK(tt_world_set_attractor(w, 5, (tt_attractor){{7, 7}, 0, 1}));
    ENSURE(tt_world_hash(w) == h0);
    ENSURE_OK(tt_world_get_attractor(w, 5, &a));
    ENSURE(a.center.x == 0 && a.strength == 0 && a.softening == 0);

    ENSURE_OK(tt_world_set_attractor(w, 2, (tt_attractor){{0, 0}, 1, 0.01}));
    tt_world_step(w, 0.01);
    size_t n;
    void *b = saved(w, &n);
    ENSURE(b);
    tt_world *c = tt_world_load(b, n);
    free(b);
    ENSURE(c);
    ENSURE(tt_world_hash(c) == tt_world_hash(w));
    for (int s = 0; s < 100; s++) {
        tt_world_step(w, 0.01);
        tt_world_step(c, 0.01);
    }
    ENSURE(tt_world_hash(c) == tt_world_hash(w));
    ENSURE_OK(tt_world_get_attractor(c, 2, &a));
    ENSURE(a.strength == 1 && a.softening == 0.01);
    tt_world_destroy(c);
    tt_world_destroy(w);
}
