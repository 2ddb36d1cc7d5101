/* Memory inside a step. What a step needs that follows from how many
 * objects there are is reserved before it changes anything, so running out
 * there fails the step with the world as it was; a world at steady state
 * allocates nothing per step; and an allocation refused inside a step (the
 * few buffers that follow the number of contacts) is never silent: the step
 * returns TT_ENOMEM. */
#include "test.h"
#include "alloc_fail.h"
#include "tether.h"

#include <math.h>
#include <string.h>

static tt_particle add(tt_world *w, double x, double y, double r)
{
    tt_particle_def d = tt_particle_def_default();
    d.position = (tt_vec2){x, y};
    d.radius = r;
    return tt_particle_create(w, &d);
}

static void add_shape(tt_world *w, tt_shape_type type, tt_vec2 at, const tt_vec2 *pts, uint32_t n)
{
    tt_shape_def d = tt_shape_def_default();
    d.type = type;
    d.position = at;
    d.points = pts;
    d.count = n;
    if (type == TT_SHAPE_AABB) {
        d.a = (tt_vec2){-1, -0.5};
        d.b = (tt_vec2){1, 0.5};
    }
    tt_shape_create(w, &d);
}

/* Every feature a step runs: a pile on shapes of every kind (one moved by
 * the script each step), a bullet, a torn and a whole rope, a cloth, a
 * ragdoll, a soft body, a lattice, each constraint kind, a spring, events. */
static tt_world *every_feature(tt_integrator in, tt_solver_order order, tt_shape *kinematic)
{
    tt_world_def wd = tt_world_def_default();
    wd.integrator = in;
    wd.order = order;
    wd.substeps = 2;
    wd.iterations = 4;
    tt_world *w = tt_world_create(&wd);
    tt_collision_settings cs = tt_collision_settings_default();
    cs.events = TT_EVENT_BEGIN | TT_EVENT_PERSIST | TT_EVENT_END;
    tt_world_set_collision(w, &cs);
    static const tt_vec2 chain[] = {{-20, 0}, {-10, -1}, {0, -1.5}, {10, -1}, {20, 0}};
    static const tt_vec2 tri[] = {{0, 0}, {2, 0}, {1, 1.5}};
    add_shape(w, TT_SHAPE_CHAIN, (tt_vec2){0, 0}, chain, 5);
    add_shape(w, TT_SHAPE_SEGMENT, (tt_vec2){-8, 2}, NULL, 0);
    add_shape(w, TT_SHAPE_CIRCLE, (tt_vec2){-5, 1}, NULL, 0);
    add_shape(w, TT_SHAPE_CAPSULE, (tt_vec2){5, 1}, NULL, 0);
    add_shape(w, TT_SHAPE_AABB, (tt_vec2){-12, 1}, NULL, 0);
    add_shape(w, TT_SHAPE_POLYGON, (tt_vec2){8, 1}, tri, 3);
    tt_shape_def box = tt_shape_def_default();
    box.type = TT_SHAPE_BOX;
    box.position = (tt_vec2){12, 1};
    *kinematic = tt_shape_create(w, &box);
    for (int i = 0; i < 120; i++) add(w, -6 + (i % 12) * 1.0 + (i / 12 % 2) * 0.3, 2 + (i / 12) * 0.9, 0.4);
    tt_particle bullet = add(w, 0, 30, 0.1);
    tt_particle_set_velocity(w, bullet, (tt_vec2){0, -200});
    tt_particle_set_bullet(w, bullet, true);
    tt_rope_def rd = tt_rope_def_default();
    rd.start = (tt_vec2){-18, 12};
    rd.finish = (tt_vec2){-10, 12};
    rd.segments = 8;
    rd.break_strain = 0.05;
    rd.pin_finish = true;
    tt_rope_create(w, &rd);
    tt_cloth_def cd = tt_cloth_def_default();
    cd.origin = (tt_vec2){12, 14};
    cd.columns = cd.rows = 6;
    tt_cloth_create(w, &cd);
    tt_ragdoll_def gd = tt_ragdoll_def_default();
    gd.position = (tt_vec2){-14, 8};
    tt_ragdoll_create(w, &gd);
    tt_soft_body_def sd = tt_soft_body_def_default();
    sd.center = (tt_vec2){14, 6};
    tt_soft_body_create(w, &sd);
    tt_lattice_def ld = tt_lattice_def_default();
    ld.center = (tt_vec2){-2, 16};
    ld.common.radius = 0.25;
    tt_lattice_create(w, &ld);
    tt_particle a = add(w, 18, 20, 0.1), b = add(w, 19, 20, 0.1), c = add(w, 20, 21, 0.1);
    tt_bounds_def bd = tt_bounds_def_default();
    bd.min = (tt_vec2){-40, -20};
    bd.max = (tt_vec2){40, 60};
    tt_bounds_create(w, &bd);
    tt_angle_def ad = tt_angle_def_default();
    ad.a = a;
    ad.b = b;
    ad.c = c;
    tt_angle_create(w, &ad);
    tt_collinear_def ld2 = tt_collinear_def_default();
    ld2.a = a;
    ld2.b = b;
    ld2.c = c;
    ld2.stiffness = 0.1;
    tt_collinear_create(w, &ld2);
    tt_spring_def sp = tt_spring_def_default();
    sp.a = a;
    sp.b = c;
    tt_spring_create(w, &sp);
    return w;
}

/* The kinematic box swings to and fro and rocks (a box spinning on for
 * ever stirs the piles for ever: no steady state to test). */
static void step(tt_world *w, tt_shape kinematic, int s)
{
    tt_shape_set_transform(w, kinematic, (tt_vec2){12 + sin(s * 0.05), 1}, 0.3 * sin(s * 0.05));
    tt_world_step(w, 1.0 / 60);
}

/* After 5 s the piles have settled under the swinging box: the contact
 * arrays have the room the reserve gives the most contacts seen (half as
 * many again), and a step allocates nothing. */
TEST(a_world_at_steady_state_allocates_nothing_per_step)
{
    long worst = 0;
    for (int in = 0; in < TT_INTEGRATOR_COUNT; in++)
        for (int order = 0; order < 2; order++) {
            tt_shape k;
            tt_world *w = every_feature((tt_integrator)in, order ? TT_JACOBI : TT_GAUSS_SEIDEL, &k);
            for (int s = 0; s < 300; s++) step(w, k, s);
            long before = tt_test_alloc_calls();
            for (int s = 300; s < 360; s++) step(w, k, s);
            long made = tt_test_alloc_calls() - before;
            if (made != 0)
                printf("    integrator %d, %s: %ld allocations in 60 steps\n", in, order ? "jacobi" : "gauss-seidel", made);
            worst = made > worst ? made : worst;
            tt_world_destroy(w);
        }
    ENSURE(worst == 0);
}

static bool finite_state(const tt_world *w)
{
    uint32_t n = tt_world_particle_count(w);
    static double xy[2 * 4096];
    if (n > 4096) return false;
    tt_world_read_positions(w, xy, n);
    for (uint32_t i = 0; i < 2 * n; i++)
        if (!isfinite(xy[i])) return false;
    return true;
}

/* Step `s` of the every-feature scene with the k-th allocation from the
 * step's start on refused: a refusal is never silent, one before the step
 * leaves the world as it was, one inside it leaves a valid world; a step
 * that lost nothing is the step a twin took. *refused: whether one was
 * (k past the step's allocations: none). */
static void step_with_refusal(tt_integrator in, tt_solver_order order, int at, long k, bool *refused)
{
    tt_shape ka, kb;
    tt_world *a = every_feature(in, order, &ka), *b = every_feature(in, order, &kb);
    for (int s = 0; s < at; s++) {
        step(a, ka, s);
        step(b, kb, s);
    }
    tt_stats before;
    tt_world_get_stats(a, &before);
    tt_shape_set_transform(a, ka, (tt_vec2){12 + sin(at * 0.05), 1}, 0.3 * sin(at * 0.05));
    uint64_t h0 = tt_world_hash(a);
    tt_test_alloc_fail_from(k);
    tt_result r = tt_world_step(a, 1.0 / 60);
    *refused = tt_test_alloc_ok();
    char msg[256];
    snprintf(msg, sizeof msg, "%s", tt_last_error(a) ? tt_last_error(a) : "");
    step(b, kb, at);
    tt_stats after;
    tt_world_get_stats(a, &after);
    if (!*refused) {
        ENSURE(r == TT_OK);
        ENSURE(tt_world_hash(a) == tt_world_hash(b));
    } else if (strstr(msg, "before the step")) {
        ENSURE(r == TT_ENOMEM && after.steps == before.steps);
        ENSURE(tt_world_hash(a) == h0);
    } else {
        if (r != TT_ENOMEM)
            printf("    step %d, allocation %ld (asked for at %p) refused, step returned %d: %s\n", at, k,
                   tt_test_alloc_refused_at(), (int)r, msg);
        ENSURE(r == TT_ENOMEM && strstr(msg, "the step ran without it") != NULL);
        ENSURE(after.steps == before.steps + 1 && finite_state(a));
    }
    tt_world_destroy(a);
    tt_world_destroy(b);
}

TEST(no_allocation_refused_in_a_step_goes_unreported)
{
    for (int in = 0; in < TT_INTEGRATOR_COUNT; in++)
        for (int order = 0; order < 2; order++)
            for (int at = 0; at <= 30; at += 30) /* the first step (everything grows) and one later */
                for (long k = 0; k < 1000; k++) {
                    bool refused = false;
                    step_with_refusal((tt_integrator)in, order ? TT_JACOBI : TT_GAUSS_SEIDEL, at, k, &refused);
                    if (!refused) break;
                }
}
