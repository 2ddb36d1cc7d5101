/* tether — fixed-point positions (tt_world_def.fixed_point, src/core/fixed_point.c):
 * position Verlet on a lattice of 2^-k m runs backwards bit for bit (the
 * spring network the float test of test_reverse.c only brings back to
 * rounding); positions stay on the lattice whatever moves them; what is out
 * of range or does not fit is refused with the world unchanged; a world
 * without the option saves and hashes as before. */
#include "test.h"
#include "core/scenes.h"

#include <tether.h>

#include <stdlib.h>
#include <string.h>

enum { COLS = 40, ROWS = 25, N = COLS * ROWS };

/* The network of test_reverse.c: 40 × 25 particles 0.5 m apart, undamped
 * springs (k = 200) to the right and below, the top row pinned, g = −9.81. */
static tt_world *network(double quantum)
{
    tt_world_def wd = tt_world_def_default();
    wd.gravity = (tt_vec2){0, -9.81};
    wd.fixed_point = quantum;
    tt_world *w = tt_world_create(&wd);
    if (w) scene_spring_network(w, COLS, ROWS);
    return w;
}

/* Positions and velocities (x − x_old over dt: the whole Verlet state). */
static void read_state(const tt_world *w, double *xy, double *v)
{
    tt_particle ids[N];
    uint32_t n = tt_world_list_particles(w, ids, N);
    tt_world_read_positions(w, xy, N);
    for (uint32_t i = 0; i < n; i++) {
        tt_vec2 u;
        tt_particle_get_velocity(w, ids[i], &u);
        v[2 * i] = u.x;
        v[2 * i + 1] = u.y;
    }
}

static bool on_lattice(const double *xy, uint32_t n, double q)
{
    for (uint32_t i = 0; i < 2 * n; i++)
        if (fmod(xy[i], q) != 0.0) return false;
    return true;
}

TEST(fixed_point_spring_network_reverses_bit_for_bit_over_10000_steps)
{
    const double q = TT_FIXED_POINT_QUANTUM, dt = 1.0 / 60;
    tt_world *w = network(q);
    ENSURE(w);
    ENSURE(tt_world_get_fixed_point(w) == q);
    tt_world_step(w, dt); /* the first step of a set velocity is a Taylor start, not a Verlet step */
    static double xy0[2 * N], v0[2 * N], xy[2 * N], v[2 * N];
    read_state(w, xy0, v0);
    ENSURE(on_lattice(xy0, N, q));
    for (int s = 0; s < 10000; s++) ENSURE_OK(tt_world_step(w, dt));
    tt_world_read_positions(w, xy, N);
    ENSURE(on_lattice(xy, N, q));
    double moved = 0; /* where the forward run ended, as test_reverse.c measures it */
    for (int i = 0; i < 2 * N; i++) moved = fmax(moved, fabs(xy[i] - xy0[i]));
    ENSURE_OK(tt_world_reverse(w));
    for (int s = 0; s < 10000; s++) ENSURE_OK(tt_world_step(w, dt));
    ENSURE_OK(tt_world_reverse(w));
    read_state(w, xy, v);
    printf("fixed point: 1000-particle spring network, 10000 steps at 1/60 s forward and back: "
           "positions and velocities %s (it moved up to %.3g m)\n",
           memcmp(xy, xy0, sizeof xy) == 0 && memcmp(v, v0, sizeof v) == 0 ? "bit for bit" : "DIFFER", moved);
    ENSURE(moved > 0.1); /* a real excursion, not a network at rest */
    ENSURE(memcmp(xy, xy0, sizeof xy) == 0);
    ENSURE(memcmp(v, v0, sizeof v) == 0);
    tt_world_destroy(w);
}

TEST(fixed_point_quantum_must_be_a_power_of_two_and_the_integrator_verlet)
{
    const double bad[] = {0.001, 1.0, 0x1p-61, -0x1p-32, 3 * 0x1p-32, NAN, INFINITY};
    for (unsigned k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        tt_world_def wd = tt_world_def_default();
        wd.fixed_point = bad[k];
        ENSURE(tt_world_create(&wd) == NULL);
        ENSURE(strstr(tt_last_error(NULL), "fixed_point"));
    }
    tt_world_def wd = tt_world_def_default();
    wd.fixed_point = 0x1p-1;
    tt_world *w = tt_world_create(&wd);
    ENSURE(w);
    tt_world_destroy(w);
    wd.fixed_point = TT_FIXED_POINT_QUANTUM;
    wd.integrator = TT_RK4;
    ENSURE(tt_world_create(&wd) == NULL);
    ENSURE(strstr(tt_last_error(NULL), "verlet"));
    wd.integrator = TT_VERLET;
    w = tt_world_create(&wd);
    tt_particle_def pd = tt_particle_def_default();
    pd.velocity = (tt_vec2){1, 0};
    tt_particle_create(w, &pd);
    const uint64_t h = tt_world_hash(w);
    ENSURE(tt_world_set_integrator(w, TT_LEAPFROG) == TT_ESTATE);
    ENSURE(strstr(tt_last_error(w), "fixed_point"));
    ENSURE(tt_world_get_integrator(w) == TT_VERLET && tt_world_hash(w) == h);
    ENSURE(tt_world_get_fixed_point(NULL) == 0.0);
    tt_world_destroy(w);
}

TEST(fixed_point_positions_are_rounded_onto_the_lattice_and_refused_outside_its_range)
{
    tt_world_def wd = tt_world_def_default();
    wd.fixed_point = 0x1p-20; /* range 2^31 m */
    tt_world *w = tt_world_create(&wd);
    tt_particle_def pd = tt_particle_def_default();
    pd.position = (tt_vec2){0.1, -1.0 / 3};
    tt_particle a = tt_particle_create(w, &pd);
    tt_vec2 at;
    tt_particle_get_position(w, a, &at);
    ENSURE(at.x == round(0.1 * 0x1p20) / 0x1p20 && at.y == round(-0x1p20 / 3) / 0x1p20);
    const uint64_t h = tt_world_hash(w);
    pd.position = (tt_vec2){0x1p31 + 1, 0};
    tt_particle none = tt_particle_create(w, &pd);
    ENSURE(none.gen == 0 && strstr(tt_last_error(w), "fixed-point range"));
    ENSURE(tt_particle_set_position(w, a, (tt_vec2){0, -0x1p32}, TT_MOVE_KEEP_VELOCITY) == TT_EINVAL);
    const double xy[4] = {1, 1, 0x1p40, 0};
    tt_particle two[2] = {a, a};
    ENSURE(tt_particles_set_positions(w, two, 2, xy, TT_MOVE_RESET_VELOCITY) == TT_EINVAL);
    tt_rope_def rd = tt_rope_def_default();
    rd.finish = (tt_vec2){0x1p32, 0};
    ENSURE(tt_rope_create(w, &rd).gen == 0 && strstr(tt_last_error(w), "fixed-point range"));
    ENSURE(tt_world_hash(w) == h && tt_world_particle_count(w) == 1); /* every refusal left it as it was */
    ENSURE_OK(tt_particle_set_position(w, a, (tt_vec2){0x1p31, 1e-9}, TT_MOVE_KEEP_VELOCITY)); /* the edge is in */
    tt_particle_get_position(w, a, &at);
    ENSURE(at.x == 0x1p31 && at.y == 0.0);
    /* a particle about to leave the range is stopped there, like one past TT_DIVERGED */
    ENSURE_OK(tt_particle_set_velocity(w, a, (tt_vec2){1e6, 0}));
    tt_world_step(w, 1.0 / 60);
    tt_stats st;
    tt_world_get_stats(w, &st);
    tt_particle_get_position(w, a, &at);
    ENSURE(st.diverged == 1 && at.x == 0x1p31);
    tt_world_destroy(w);
}

/* An impulse moves x_old off the lattice; reversing then makes it the
 * position, rounded back onto the lattice. */
TEST(fixed_point_reverse_after_an_impulse_keeps_positions_on_the_lattice)
{
    const double q = 0x1p-20;
    tt_world_def wd = tt_world_def_default();
    wd.fixed_point = q;
    tt_world *w = tt_world_create(&wd);
    tt_particle_def pd = tt_particle_def_default();
    tt_particle p = tt_particle_create(w, &pd);
    tt_world_step(w, 1.0 / 60);
    ENSURE_OK(tt_particle_apply_impulse(w, p, (tt_vec2){0.1, 0.3}));
    ENSURE_OK(tt_world_reverse(w));
    double xy[2];
    tt_world_read_positions(w, xy, 1);
    ENSURE(on_lattice(xy, 1, q));
    tt_world_step(w, 1.0 / 60);
    tt_world_read_positions(w, xy, 1);
    ENSURE(on_lattice(xy, 1, q));
    tt_world_destroy(w);
}

/* Constraints and contacts correct positions by amounts off the lattice:
 * they are rounded back onto it after the sweeps. */
TEST(fixed_point_stays_on_the_lattice_with_constraints_and_collisions)
{
    const double q = 0x1p-24;
    tt_world_def wd = tt_world_def_default();
    wd.fixed_point = q;
    wd.damping = 0.5;
    tt_world *w = tt_world_create(&wd);
    tt_rope_def rd = tt_rope_def_default();
    rd.start = (tt_vec2){0, 1.5};
    rd.finish = (tt_vec2){2.3, 1.6};
    rd.segments = 12;
    rd.common.radius = 0.1;
    ENSURE(tt_rope_create(w, &rd).gen != 0);
    tt_shape_def sd = tt_shape_def_default();
    sd.a = (tt_vec2){-5, 0};
    sd.b = (tt_vec2){5, 0};
    ENSURE(tt_shape_create(w, &sd).gen != 0);
    for (int s = 0; s < 240; s++) ENSURE_OK(tt_world_step(w, 1.0 / 60));
    double xy[2 * 13];
    uint32_t n = tt_world_read_positions(w, xy, 13);
    ENSURE(n == 13 && on_lattice(xy, n, q));
    double lowest = 1e9;
    for (uint32_t i = 0; i < n; i++) lowest = fmin(lowest, xy[2 * i + 1]);
    ENSURE(lowest > 0.05 && lowest < 0.2); /* hanging onto the ground, not through it */
    tt_world_destroy(w);
}

TEST(fixed_point_is_saved_restored_and_hashed_only_when_set)
{
    tt_world *plain = network(0), *fixed = network(0x1p-16);
    ENSURE(plain && fixed);
    /* on a lattice of 2^-16 the start (multiples of 0.5) is the same: only the option differs */
    ENSURE(tt_world_hash(plain) != tt_world_hash(fixed));
    for (int s = 0; s < 30; s++) tt_world_step(fixed, 1.0 / 60);
    size_t size = 0;
    ENSURE(tt_world_save(fixed, NULL, 0, &size) == TT_ENOMEM);
    void *buf = malloc(size);
    ENSURE_OK(tt_world_save(fixed, buf, size, &size));
    tt_world *copy = tt_world_load(buf, size);
    ENSURE(copy && tt_world_get_fixed_point(copy) == 0x1p-16 && tt_world_hash(copy) == tt_world_hash(fixed));
    ENSURE_OK(tt_world_restore(plain, buf, size));
    ENSURE(tt_world_get_fixed_point(plain) == 0x1p-16);
    for (int s = 0; s < 30; s++) { tt_world_step(fixed, 1.0 / 60); tt_world_step(copy, 1.0 / 60); }
    ENSURE(tt_world_hash(copy) == tt_world_hash(fixed));
    free(buf);
    tt_world_destroy(copy);
    tt_world_destroy(plain);
    tt_world_destroy(fixed);
}
