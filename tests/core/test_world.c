/* The world: stats, energy, memory, determinism; empty worlds step with every feature. */
#include "test.h"
#include "tether.h"

/* A scene touching every part of the core: springs, forces, impulses, an
 * explosion, removals, and an integrator switch half way. */
static tt_world *scene(tt_integrator integ, int steps)
{
    tt_world_def d = tt_world_def_default();
    d.integrator = integ;
    d.damping = 0.1;
    d.wind = (tt_vec2){0.3, 0};
    tt_world *w = tt_world_create(&d);
    tt_particle prev = {0, 0};
    for (int k = 0; k < 200; k++) {
        tt_particle_def pd = tt_particle_def_default();
        pd.position = (tt_vec2){k * 0.1, (k * 37 % 11) * 0.2};
        pd.velocity = (tt_vec2){(k % 7) * 0.3, -(k % 5) * 0.1};
        pd.mass = 1 + (k % 3);
        pd.pinned = k % 50 == 0;
        tt_particle p = tt_particle_create(w, &pd);
        if (prev.gen) {
            tt_spring_def sd = tt_spring_def_default();
            sd.a = prev;
            sd.b = p;
            sd.damping = 0.5;
            tt_spring_create(w, &sd);
        }
        prev = p;
    }
    tt_particle list[200];
    tt_world_list_particles(w, list, 200);
    for (int s = 0; s < steps; s++) {
        tt_particle_apply_force(w, list[s % 200], (tt_vec2){1, 2});
        if (s % 60 == 0) tt_world_explode(w, (tt_vec2){10, 1}, 5, 3);
        if (s == steps / 2) {
            tt_particle_destroy(w, list[17]);
            tt_world_set_integrator(w, integ == TT_VERLET ? TT_RK4 : TT_VERLET);
        }
        tt_world_step(w, 1.0 / 60);
    }
    return w;
}

TEST(same_inputs_give_bit_identical_state)
{
    for (int i = 0; i < TT_INTEGRATOR_COUNT; i++) {
        tt_world *a = scene((tt_integrator)i, 300), *b = scene((tt_integrator)i, 300), *c = scene((tt_integrator)i, 299);
        ENSURE(tt_world_hash(a) == tt_world_hash(b));
        ENSURE(tt_world_hash(a) != tt_world_hash(c));
        tt_world_destroy(a);
        tt_world_destroy(b);
        tt_world_destroy(c);
    }
}

TEST(stats_report_the_last_step)
{
    tt_world *w = scene(TT_RK4, 10);
    tt_stats s;
    ENSURE_OK(tt_world_get_stats(w, &s));
    ENSURE(s.steps == 10);
    ENSURE_NEAR(s.time, 10.0 / 60, 1e-12);
    ENSURE(s.particles == 199);
    ENSURE(s.springs == 197);
    ENSURE(s.force_evaluations == 1); /* switched to Verlet half way: one evaluation */
    ENSURE(s.step_ms >= 0 && s.stage_ms[TT_STAGE_INTEGRATE] >= 0 && s.stage_ms[TT_STAGE_FORCES] > 0);
    ENSURE(s.stage_ms[TT_STAGE_COLLIDE] == 0 && s.stage_ms[TT_STAGE_SOLVE] == 0);
    tt_world_destroy(w);

    /* gravity alone evaluates no force at all */
    w = tt_world_create(NULL);
    tt_particle_def pd = tt_particle_def_default();
    tt_particle_create(w, &pd);
    tt_world_step(w, 0.01);
    tt_world_get_stats(w, &s);
    ENSURE(s.force_evaluations == 0 && s.stage_ms[TT_STAGE_FORCES] == 0);
    tt_world_set_integrator(w, TT_RK4);
    tt_world_set_wind(w, (tt_vec2){1, 0});
    tt_world_step(w, 0.01);
    tt_world_get_stats(w, &s);
    ENSURE(s.force_evaluations == 4);
    tt_world_destroy(w);
}

TEST(energy_of_a_falling_particle_is_conserved_by_verlet)
{
    tt_world *w = tt_world_create(NULL);
    tt_particle_def pd = tt_particle_def_default();
    pd.position = (tt_vec2){0, 100};
    pd.mass = 2;
    tt_particle_create(w, &pd);
    tt_energy e0, e1;
    tt_world_get_energy(w, &e0);
    ENSURE_NEAR(e0.gravity, 2 * 9.81 * 100, 1e-9);
    ENSURE(e0.kinetic == 0);
    for (int k = 0; k < 120; k++) tt_world_step(w, 1.0 / 60);
    tt_world_get_energy(w, &e1);
    /* Verlet's backward-difference velocity lags by g·dt/2: KE is off by O(dt). */
    ENSURE_NEAR(e1.total, e0.total, 2 * 9.81 * 9.81 * 2 / 60);
    tt_world_destroy(w);
}

TEST(memory_is_reported_and_small)
{
    tt_world *w = tt_world_create(NULL);
    tt_particle_def pd = tt_particle_def_default();
    for (int k = 0; k < 1000; k++) tt_particle_create(w, &pd);
    tt_memory m;
    ENSURE_OK(tt_world_get_memory(w, &m));
    ENSURE(m.capacity >= 1000);
    ENSURE(m.bytes_per_particle <= 64);
    ENSURE(m.total >= m.particles);
    tt_world_destroy(w);
}

/* Integration time excludes the force evaluations inside it: with several
 * substeps each one subtracted the forces of all the substeps before it,
 * and the stage went negative (−3.9 ms with RK4 × 16). */
TEST(stage_times_are_never_negative_with_substeps)
{
    tt_world_def d = tt_world_def_default();
    d.integrator = TT_RK4;
    d.substeps = 16;
    tt_world *w = tt_world_create(&d);
    tt_particle_def pd = tt_particle_def_default();
    tt_particle prev = tt_particle_create(w, &pd);
    for (int i = 1; i < 2000; i++) { /* a chain of springs: forces cost as much as integrating */
        pd.position = (tt_vec2){i * 0.1, 0};
        tt_particle p = tt_particle_create(w, &pd);
        tt_spring_def sd = tt_spring_def_default();
        sd.a = prev;
        sd.b = p;
        tt_spring_create(w, &sd);
        prev = p;
    }
    for (int s = 0; s < 5; s++) {
        ENSURE_OK(tt_world_step(w, 1.0 / 60));
        tt_stats st;
        tt_world_get_stats(w, &st);
        double sum = 0;
        for (int k = 0; k < TT_STAGE_COUNT; k++) {
            ENSURE(st.stage_ms[k] >= 0.0);
            sum += st.stage_ms[k];
        }
        ENSURE(st.stage_ms[TT_STAGE_FORCES] > 0.0);
        ENSURE(sum <= st.step_ms * 1.01 + 1e-3);
    }
    tt_world_destroy(w);
}

/* --- empty worlds ----------------------------------------------------------- */

enum {
    EMPTY_FORCES = 1 << 0,  /* wind and damping */
    EMPTY_BOUNDS = 1 << 1,  /* a bounds constraint over every particle (none) */
    EMPTY_OUTSIDE = 1 << 2, /* and one keeping them out of a box */
    EMPTY_PAIRS = 1 << 3,   /* particle collisions, grid broadphase */
    EMPTY_BRUTE = 1 << 4,   /* particle collisions, brute force */
    EMPTY_SHAPES = 1 << 5,  /* a floor and a circle, with contact events */
    EMPTY_JACOBI = 1 << 6,
    EMPTY_SUBSTEPS = 1 << 7, /* four substeps of one sweep each */
    EMPTY_HOLE = 1 << 8,    /* a particle made and destroyed first: slots, none alive */
    EMPTY_ALL = (1 << 9) - 1
};

static void empty_world_features(tt_world *w, unsigned f)
{
    if (f & EMPTY_FORCES) {
        tt_world_set_wind(w, (tt_vec2){0.5, 0});
        tt_world_set_damping(w, 0.2);
    }
    if (f & (EMPTY_BOUNDS | EMPTY_OUTSIDE)) {
        tt_bounds_def bd = tt_bounds_def_default();
        if (f & EMPTY_BOUNDS) tt_bounds_create(w, &bd);
        bd.outside = true;
        bd.min = (tt_vec2){-1, -1};
        bd.max = (tt_vec2){1, 1};
        if (f & EMPTY_OUTSIDE) tt_bounds_create(w, &bd);
    }
    if (f & (EMPTY_PAIRS | EMPTY_BRUTE | EMPTY_SHAPES)) {
        tt_collision_settings cs = tt_collision_settings_default();
        cs.particles = (f & (EMPTY_PAIRS | EMPTY_BRUTE)) != 0;
        cs.broadphase = f & EMPTY_BRUTE ? TT_BROADPHASE_BRUTE : TT_BROADPHASE_GRID;
        cs.events = TT_EVENT_BEGIN | TT_EVENT_PERSIST | TT_EVENT_END;
        tt_world_set_collision(w, &cs);
    }
    if (f & EMPTY_SHAPES) {
        tt_shape_def sd = tt_shape_def_default();
        sd.type = TT_SHAPE_AABB;
        sd.a = (tt_vec2){-10, -1};
        sd.b = (tt_vec2){10, 0};
        tt_shape_create(w, &sd);
        sd.type = TT_SHAPE_CIRCLE;
        sd.a = (tt_vec2){0, 3};
        sd.radius = 1;
        tt_shape_create(w, &sd);
    }
    if (f & EMPTY_JACOBI) tt_world_set_solver_order(w, TT_JACOBI);
    if (f & EMPTY_SUBSTEPS) {
        tt_world_set_substeps(w, 4);
        tt_world_set_iterations(w, 1);
    }
    if (f & EMPTY_HOLE) {
        tt_particle_def pd = tt_particle_def_default();
        pd.radius = 0.1;
        tt_particle_destroy(w, tt_particle_create(w, &pd));
    }
}

/* Steps and reads an empty world: false when any call fails or it gained particles. */
static bool empty_world_works(tt_integrator integ, unsigned f)
{
    tt_world_def d = tt_world_def_default();
    d.integrator = integ;
    tt_world *w = tt_world_create(&d);
    if (!w) return false;
    empty_world_features(w, f);
    bool ok = true;
    for (int s = 0; s < 3; s++) ok = ok && tt_world_step(w, 1.0 / 60) == TT_OK;
    tt_stats st;
    tt_energy en;
    tt_memory mem;
    ok = ok && tt_world_get_stats(w, &st) == TT_OK && st.particles == 0 && st.steps == 3;
    ok = ok && tt_world_get_energy(w, &en) == TT_OK && en.total == 0.0;
    ok = ok && tt_world_get_memory(w, &mem) == TT_OK;
    ok = ok && tt_world_explode(w, (tt_vec2){0, 0}, 5, 1) == TT_OK;
    ok = ok && tt_world_particle_count(w) == 0 && tt_world_read_positions(w, NULL, 0) == 0;
    if (f & (EMPTY_PAIRS | EMPTY_BRUTE | EMPTY_SHAPES)) {
        tt_ray_hit hit;
        uint32_t np = 1, ns = 0, ne = 1;
        ok = ok && tt_world_raycast(w, (tt_vec2){-5, 5}, (tt_vec2){5, -5}, 0xFFFF, &hit) == TT_OK;
        ok = ok && hit.hit == ((f & EMPTY_SHAPES) != 0);
        ok = ok && tt_world_query_point(w, (tt_vec2){0, 3}, 0xFFFF, NULL, 0, &np, NULL, 0, &ns) == TT_OK && np == 0;
        ok = ok && tt_world_query_aabb(w, (tt_vec2){-9, -9}, (tt_vec2){9, 9}, 0xFFFF, NULL, 0, &np, NULL, 0, &ns) == TT_OK;
        ok = ok && np == 0 && ns == ((f & EMPTY_SHAPES) ? 2u : 0u);
        tt_world_get_contact_events(w, &ne);
        ok = ok && ne == 0;
        tt_collision_stats cst;
        ok = ok && tt_world_get_collision_stats(w, &cst) == TT_OK && cst.pair_contacts == 0 && cst.shape_contacts == 0;
    }
    tt_world_hash(w);
    tt_world_destroy(w);
    return ok;
}

/* Issue 14, finding 4: an empty world, stepped with any integrator and any
 * feature, copied and cleared zero bytes through NULL arrays (memcpy with
 * NULL is undefined even for 0 bytes; the sanitizer build stops on it).
 * Every single feature, and all of them together, with every integrator. */
TEST(empty_worlds_step_with_every_integrator_and_feature)
{
    for (int i = 0; i < TT_INTEGRATOR_COUNT; i++) {
        const tt_integrator integ = (tt_integrator)i;
        const unsigned sets[] = {0, EMPTY_ALL, EMPTY_ALL & ~EMPTY_HOLE};
        for (unsigned k = 0; k < 3; k++)
            if (!empty_world_works(integ, sets[k]))
                tt_test_fail(__FILE__, __LINE__, "%s, features %#x", tt_integrator_name(integ), sets[k]);
        for (unsigned f = 1; f <= EMPTY_ALL; f <<= 1)
            if (!empty_world_works(integ, f)) tt_test_fail(__FILE__, __LINE__, "%s, feature %#x", tt_integrator_name(integ), f);
    }
}
