/* Particles: handles, validation, reads and writes, bulk access. */
#include "test.h"
#include "tether.h"

#include <stdlib.h>
#include <string.h>

static tt_particle add(tt_world *w, double x, double y)
{
    tt_particle_def d = tt_particle_def_default();
    d.position = (tt_vec2){x, y};
    return tt_particle_create(w, &d);
}

TEST(handles_go_stale_and_are_never_reused)
{
    tt_world *w = tt_world_create(NULL);
    tt_particle a = add(w, 1, 2);
    ENSURE(tt_particle_is_valid(w, a));
    ENSURE_OK(tt_particle_destroy(w, a));
    ENSURE(!tt_particle_is_valid(w, a));
    tt_vec2 x;
    ENSURE(tt_particle_get_position(w, a, &x) == TT_ESTALE);
    ENSURE(strstr(tt_last_error(w), "stale particle handle") != NULL);
    ENSURE(tt_particle_destroy(w, a) == TT_ESTALE);
    tt_particle b = add(w, 3, 4); /* takes the freed slot, with a new generation */
    ENSURE(b.index == a.index && b.gen != a.gen);
    ENSURE(!tt_particle_is_valid(w, a));
    ENSURE(tt_particle_is_valid(w, b));
    tt_particle none = {0, 0}, forged = {b.index + 100, 1}, next_gen = {b.index, b.gen + 1};
    ENSURE(!tt_particle_is_valid(w, none));
    ENSURE(!tt_particle_is_valid(w, forged));
    ENSURE(!tt_particle_is_valid(w, next_gen));
    ENSURE(!tt_particle_is_valid(NULL, b));
    ENSURE(tt_world_particle_count(w) == 1);
    tt_world_destroy(w);
}

TEST(a_handle_from_another_world_is_stale)
{
    tt_world *a = tt_world_create(NULL), *b = tt_world_create(NULL);
    tt_particle pa = add(a, 1, 1), pb = add(b, 2, 2); /* same slot index in both */
    ENSURE(pa.index == pb.index);
    ENSURE(!tt_particle_is_valid(b, pa));
    ENSURE(!tt_particle_is_valid(a, pb));
    tt_vec2 x;
    ENSURE(tt_particle_get_position(b, pa, &x) == TT_ESTALE);
    ENSURE(tt_particle_destroy(b, pa) == TT_ESTALE);
    tt_spring_def sd = tt_spring_def_default();
    sd.a = add(a, 0, 0);
    sd.b = pa;
    tt_spring s = tt_spring_create(a, &sd);
    ENSURE(tt_spring_is_valid(a, s));
    ENSURE(!tt_spring_is_valid(b, s));
    /* identical worlds still hash identically: the tag is not simulation state */
    tt_world *c = tt_world_create(NULL);
    add(c, 2, 2);
    ENSURE(tt_world_hash(b) == tt_world_hash(c));
    tt_world_destroy(a);
    tt_world_destroy(b);
    tt_world_destroy(c);
}

TEST(creation_rejects_bad_input)
{
    tt_world *w = tt_world_create(NULL);
    tt_particle_def d = tt_particle_def_default();
    tt_particle_def bad[6];
    for (int k = 0; k < 6; k++) bad[k] = d;
    bad[0].position.x = NAN;
    bad[1].velocity.y = INFINITY;
    bad[2].mass = 0;
    bad[3].mass = -1;
    bad[4].radius = -0.5;
    bad[5].position.y = 1e300;
    for (int k = 0; k < 6; k++) {
        tt_particle p = tt_particle_create(w, &bad[k]);
        ENSURE(p.gen == 0);
        ENSURE(strlen(tt_last_error(w)) > 0);
    }
    ENSURE(tt_particle_create(w, NULL).gen == 0);
    ENSURE(tt_particle_create(NULL, &d).gen == 0);
    ENSURE(tt_world_particle_count(w) == 0);
    tt_particle p = tt_particle_create(w, &d);
    ENSURE(tt_particle_set_position(w, p, (tt_vec2){NAN, 0}, TT_MOVE_KEEP_VELOCITY) == TT_EINVAL);
    ENSURE(tt_particle_set_position(w, p, (tt_vec2){0, 0}, (tt_move_mode)7) == TT_EINVAL);
    ENSURE(tt_particle_set_velocity(w, p, (tt_vec2){0, -INFINITY}) == TT_EINVAL);
    ENSURE(tt_particle_set_mass(w, p, NAN) == TT_EINVAL);
    ENSURE(tt_particle_set_mass(w, p, 1e10) == TT_EINVAL);
    ENSURE(tt_particle_set_radius(w, p, INFINITY) == TT_EINVAL);
    ENSURE(tt_particle_apply_force(w, p, (tt_vec2){NAN, 0}) == TT_EINVAL);
    ENSURE(tt_particle_apply_impulse(w, p, (tt_vec2){0, 2e12}) == TT_EINVAL);
    ENSURE(tt_particle_get_position(w, p, NULL) == TT_EINVAL);
    tt_vec2 x;
    tt_particle_get_position(w, p, &x);
    ENSURE(x.x == 0 && x.y == 0);
    tt_world_destroy(w);
}

TEST(world_rejects_bad_settings)
{
    tt_world_def d = tt_world_def_default();
    d.gravity.y = NAN;
    ENSURE(tt_world_create(&d) == NULL);
    ENSURE(strstr(tt_last_error(NULL), "gravity") != NULL);
    d = tt_world_def_default();
    d.dt_hint = 0;
    ENSURE(tt_world_create(&d) == NULL);
    d = tt_world_def_default();
    d.integrator = (tt_integrator)99;
    ENSURE(tt_world_create(&d) == NULL);
    d = tt_world_def_default();
    d.damping = -1;
    ENSURE(tt_world_create(&d) == NULL);
    tt_world *w = tt_world_create(NULL);
    ENSURE(tt_world_step(w, 0) == TT_EINVAL);
    ENSURE(tt_world_step(w, NAN) == TT_EINVAL);
    ENSURE(tt_world_step(w, 11) == TT_EINVAL);
    ENSURE(tt_world_step(w, -0.01) == TT_EINVAL);
    ENSURE(tt_world_step(NULL, 0.01) == TT_EINVAL);
    ENSURE(tt_world_set_gravity(w, (tt_vec2){INFINITY, 0}) == TT_EINVAL);
    ENSURE(tt_world_set_wind(w, (tt_vec2){0, NAN}) == TT_EINVAL);
    ENSURE(tt_world_set_damping(w, NAN) == TT_EINVAL);
    ENSURE(tt_world_set_integrator(w, (tt_integrator)-1) == TT_EINVAL);
    ENSURE(tt_world_explode(w, (tt_vec2){0, 0}, NAN, 1) == TT_EINVAL);
    ENSURE(tt_world_get_gravity(w).y == -9.81);
    tt_integrator i;
    ENSURE(tt_integrator_from_name("rk5", &i) == TT_EINVAL);
    ENSURE_OK(tt_integrator_from_name("leapfrog", &i));
    ENSURE(i == TT_LEAPFROG);
    tt_world_destroy(w);
    tt_world_destroy(NULL);
}

TEST(round_trips)
{
    tt_world *w = tt_world_create(NULL);
    tt_particle p = add(w, 1, 2);
    double m, r;
    bool pinned;
    uint16_t cat, mask;
    uint64_t user;
    ENSURE_OK(tt_particle_set_mass(w, p, 3.5));
    ENSURE_OK(tt_particle_get_mass(w, p, &m));
    ENSURE(m == 3.5);
    ENSURE_OK(tt_particle_set_radius(w, p, 0.25));
    ENSURE_OK(tt_particle_get_radius(w, p, &r));
    ENSURE(r == 0.25);
    ENSURE_OK(tt_particle_set_filter(w, p, 4, 0x00F0));
    ENSURE_OK(tt_particle_get_filter(w, p, &cat, &mask));
    ENSURE(cat == 4 && mask == 0x00F0);
    ENSURE_OK(tt_particle_get_user(w, p, &user));
    ENSURE(user == 0);
    ENSURE_OK(tt_particle_set_user(w, p, 0xDEADBEEFCAFEull));
    ENSURE_OK(tt_particle_get_user(w, p, &user));
    ENSURE(user == 0xDEADBEEFCAFEull);
    ENSURE_OK(tt_particle_set_velocity(w, p, (tt_vec2){-1, 0.5}));
    tt_vec2 v;
    ENSURE_OK(tt_particle_get_velocity(w, p, &v));
    ENSURE_NEAR(v.x, -1, 1e-12); /* Verlet keeps v as x − x_old: exact to rounding */
    ENSURE_NEAR(v.y, 0.5, 1e-12);
    /* pin: stops, infinite mass, set_velocity refused; unpin: mass comes back */
    ENSURE_OK(tt_particle_set_pinned(w, p, true));
    ENSURE_OK(tt_particle_get_pinned(w, p, &pinned));
    ENSURE(pinned);
    ENSURE(tt_particle_set_velocity(w, p, (tt_vec2){1, 0}) == TT_ESTATE);
    tt_particle_get_velocity(w, p, &v);
    ENSURE(v.x == 0 && v.y == 0);
    ENSURE_OK(tt_particle_set_pinned(w, p, false));
    tt_particle_get_mass(w, p, &m);
    ENSURE(m == 3.5);
    ENSURE_OK(tt_particle_apply_impulse(w, p, (tt_vec2){7, 0}));
    tt_particle_get_velocity(w, p, &v);
    ENSURE_NEAR(v.x, 2.0, 1e-12);
    tt_world_destroy(w);
}

TEST(teleport_keeps_or_resets_velocity)
{
    for (int i = 0; i < TT_INTEGRATOR_COUNT; i++) {
        tt_world_def d = tt_world_def_default();
        d.integrator = (tt_integrator)i;
        tt_world *w = tt_world_create(&d);
        tt_particle p = add(w, 0, 0);
        tt_particle_set_velocity(w, p, (tt_vec2){2, 1});
        tt_world_step(w, 1.0 / 60);
        tt_vec2 v0, v, x;
        tt_particle_get_velocity(w, p, &v0);
        ENSURE_OK(tt_particle_set_position(w, p, (tt_vec2){10, 10}, TT_MOVE_KEEP_VELOCITY));
        tt_particle_get_position(w, p, &x);
        tt_particle_get_velocity(w, p, &v);
        ENSURE(x.x == 10 && x.y == 10);
        ENSURE_NEAR(v.x, v0.x, 1e-12);
        ENSURE_NEAR(v.y, v0.y, 1e-12);
        ENSURE_OK(tt_particle_set_position(w, p, (tt_vec2){-5, 3}, TT_MOVE_RESET_VELOCITY));
        tt_particle_get_velocity(w, p, &v);
        ENSURE(v.x == 0 && v.y == 0);
        tt_world_destroy(w);
    }
}

TEST(bulk_reads_match_single_reads)
{
    tt_world *w = tt_world_create(NULL);
    tt_particle ids[100];
    for (int k = 0; k < 100; k++) ids[k] = add(w, k, -k);
    for (int k = 0; k < 100; k += 3) tt_particle_destroy(w, ids[k]);
    uint32_t n = tt_world_list_particles(w, NULL, 0);
    ENSURE(n == 66);
    tt_particle *list = malloc(n * sizeof *list);
    double *xy = malloc(2 * n * sizeof *xy), *xy2 = malloc(2 * n * sizeof *xy2);
    ENSURE(tt_world_list_particles(w, list, n) == n);
    ENSURE(tt_world_read_positions(w, xy, n) == n);
    ENSURE_OK(tt_particles_get_positions(w, list, n, xy2));
    for (uint32_t k = 0; k < n; k++) {
        tt_vec2 x;
        tt_particle_get_position(w, list[k], &x);
        ENSURE(xy[2 * k] == x.x && xy[2 * k + 1] == x.y && xy2[2 * k] == x.x);
        xy[2 * k] += 100;
    }
    ENSURE_OK(tt_particles_set_positions(w, list, n, xy, TT_MOVE_RESET_VELOCITY));
    tt_vec2 x;
    tt_particle_get_position(w, list[5], &x);
    ENSURE(x.x == xy[10]);
    /* all or nothing: one bad value changes nothing */
    xy[7] = NAN;
    ENSURE(tt_particles_set_positions(w, list, n, xy, TT_MOVE_KEEP_VELOCITY) == TT_EINVAL);
    tt_particle_get_position(w, list[0], &x);
    ENSURE(x.x == xy[0]);
    list[3] = ids[0]; /* stale */
    ENSURE(tt_particles_get_positions(w, list, n, xy2) == TT_ESTALE);
    free(list);
    free(xy);
    free(xy2);
    tt_world_destroy(w);
}

TEST(grows_to_a_million_particles)
{
    tt_world_def d = tt_world_def_default();
    tt_world *w = tt_world_create(&d);
    const uint32_t n = 1000000;
    tt_particle last = {0, 0};
    tt_particle_def pd = tt_particle_def_default();
    for (uint32_t k = 0; k < n; k++) {
        pd.position = (tt_vec2){(double)(k % 1000), (double)(k / 1000)};
        last = tt_particle_create(w, &pd);
        if (last.gen == 0) break;
    }
    ENSURE(tt_world_particle_count(w) == n);
    ENSURE_OK(tt_world_step(w, 1.0 / 60));
    tt_vec2 x;
    ENSURE_OK(tt_particle_get_position(w, last, &x));
    ENSURE_NEAR(x.y, 999 - 0.5 * 9.81 / 3600, 1e-9);
    tt_memory m;
    tt_world_get_memory(w, &m);
    ENSURE(m.bytes_per_particle <= 64);
    tt_world_destroy(w);
}

TEST(max_particles_is_enforced)
{
    tt_world_def d = tt_world_def_default();
    d.max_particles = 10;
    tt_world *w = tt_world_create(&d);
    for (int k = 0; k < 10; k++) ENSURE(add(w, k, 0).gen != 0);
    ENSURE(add(w, 0, 0).gen == 0);
    ENSURE(strstr(tt_last_error(w), "full") != NULL);
    tt_world_destroy(w);
}

/* Found by the C fuzzer (seed 23, call 5167): a create refused because the
 * world is full, with user data in its def, had already made the user
 * array, and an array of zeros changed the world's stream and hash. The
 * state is the values, not whether their array exists. */
TEST(a_refused_create_with_user_data_leaves_the_hash)
{
    tt_world_def wd = tt_world_def_default();
    wd.max_particles = 1;
    tt_world *w = tt_world_create(&wd);
    tt_particle_def d = tt_particle_def_default();
    ENSURE(tt_particle_create(w, &d).gen != 0);
    uint64_t h0 = tt_world_hash(w);
    d.user = 42;
    ENSURE(tt_particle_create(w, &d).gen == 0);
    ENSURE(tt_world_hash(w) == h0);
    tt_world_destroy(w);
}

/* Found by the C fuzzer (seed 1796183327, call 38006): an impulse of 1e9 N·s
 * on a particle of 1e-9 kg left it at 1e18 m/s, past TT_DIVERGED, until the
 * next step stopped it. An impulse (or an explosion) is refused when its
 * change of velocity is one tt_particle_set_velocity would refuse, or when
 * it leaves the particle past TT_DIVERGED; the world is left as it was. */
TEST(an_impulse_past_the_velocity_limit_is_refused)
{
    tt_world *w = tt_world_create(NULL);
    tt_particle_def pd = tt_particle_def_default();
    pd.mass = 1e-9;
    tt_particle light = tt_particle_create(w, &pd);
    pd.mass = 1;
    pd.position = (tt_vec2){0.5, 0};
    tt_particle heavy = tt_particle_create(w, &pd);
    ENSURE(light.gen && heavy.gen);
    const uint64_t h = tt_world_hash(w);
    ENSURE(tt_particle_apply_impulse(w, light, (tt_vec2){1e9, 0}) == TT_EINVAL);
    ENSURE(strstr(tt_last_error(w), "velocity") != NULL);
    ENSURE(tt_world_explode(w, (tt_vec2){-0.1, 0}, 2.0, 1e9) == TT_EINVAL);
    ENSURE(tt_world_hash(w) == h);
    ENSURE_OK(tt_particle_apply_impulse(w, heavy, (tt_vec2){1e9, 0})); /* 1e9 m/s: within the limit */
    tt_vec2 v;
    ENSURE_OK(tt_particle_get_velocity(w, heavy, &v));
    ENSURE(v.x == 1e9);
    tt_world_destroy(w);
}
