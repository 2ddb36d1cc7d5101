/* Memory inside a step. What a step needs that follows from how many
 * objects there are is reserved before it changes anything; a world at
 * steady state allocates nothing per step; and an allocation refused inside
 * a step (the few buffers that follow the number of contacts) fails the
 * step with TT_ENOMEM and the world as it was before it: its hash, and every
 * step after, those of a twin that never ran out. */
#include "test.h"
#include "alloc_fail.h"
#include "tether.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static tt_particle add(tt_world *w, double x, double y, double r)
{
    tt_particle_def d = tt_particle_def_default();
    d.position = (tt_vec2){x, y};
    d.radius = r;
    return tt_particle_create(w, &d);
}

static tt_shape add_shape(tt_world *w, tt_shape_type type, tt_vec2 at, const tt_vec2 *pts, uint32_t n)
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
    return tt_shape_create(w, &d);
}

/* Every feature a step runs: a pile on shapes of every kind (one moved by
 * the script each step), a bullet, a torn and a whole rope, a cloth, a
 * ragdoll, a soft body, a lattice, each constraint kind, a spring, events. */
/* What the script moves each step: a kinematic box and a pin's anchor. */
typedef struct moved {
    tt_shape box, chain;
    tt_constraint pin;
} moved;

static tt_world *every_feature(tt_integrator in, tt_solver_order order, moved *kinematic)
{
    tt_world_def wd = tt_world_def_default();
    wd.integrator = in;
    wd.order = order;
    wd.substeps = 2;
    wd.iterations = 4;
    wd.sleep = in == TT_VERLET; /* the pile's corner falls asleep, the swinging box wakes it */
    wd.sleep_time = 0.2;
    wd.spin = (in + order) % 2 == 1; /* half the worlds' particles turn (their friction lists its contacts) */
    tt_world *w = tt_world_create(&wd);
    tt_collision_settings cs = tt_collision_settings_default();
    cs.events = TT_EVENT_BEGIN | TT_EVENT_PERSIST | TT_EVENT_END;
    tt_world_set_collision(w, &cs);
    static const tt_vec2 chain[] = {{-20, 0}, {-10, -1}, {0, -1.5}, {10, -1}, {20, 0}};
    static const tt_vec2 tri[] = {{0, 0}, {2, 0}, {1, 1.5}};
    kinematic->chain = add_shape(w, TT_SHAPE_CHAIN, (tt_vec2){0, 0}, chain, 5);
    add_shape(w, TT_SHAPE_SEGMENT, (tt_vec2){-8, 2}, NULL, 0);
    add_shape(w, TT_SHAPE_CIRCLE, (tt_vec2){-5, 1}, NULL, 0);
    add_shape(w, TT_SHAPE_CAPSULE, (tt_vec2){5, 1}, NULL, 0);
    add_shape(w, TT_SHAPE_AABB, (tt_vec2){-12, 1}, NULL, 0);
    add_shape(w, TT_SHAPE_POLYGON, (tt_vec2){8, 1}, tri, 3);
    tt_shape_def box = tt_shape_def_default();
    box.type = TT_SHAPE_BOX;
    box.position = (tt_vec2){12, 1};
    kinematic->box = tt_shape_create(w, &box);
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
    /* a terrain ledge under a few grains, and a pin the script drags (a moving target) */
    tt_mask *m = tt_mask_create(80, 10, true);
        tt_terrain_def td = tt_terrain_def_default();
    td.solid = m;
    td.pixel = 0.1;
    td.origin = (tt_vec2){22, 4};
    tt_terrain_create(w, &td);
    tt_mask_destroy(m);
    for (int i = 0; i < 6; i++) add(w, 23 + i * 0.9, 4.5 + (i % 2) * 0.9, 0.4);
    tt_pin_def pd = tt_pin_def_default();
    pd.particle = a;
    pd.anchor = (tt_vec2){18, 20};
    pd.max_rate = 1.0;
    kinematic->pin = tt_pin_create(w, &pd);
    return w;
}

/* The kinematic box swings to and fro and rocks (a box spinning on for
 * ever stirs the piles for ever: no steady state to test). */
static void set_inputs(tt_world *w, moved kinematic, int s)
{
    tt_shape_set_transform(w, kinematic.box, (tt_vec2){12 + sin(s * 0.05), 1}, 0.3 * sin(s * 0.05));
    if (s % 20 == 0) tt_pin_set_anchor(w, kinematic.pin, (tt_vec2){18 + (s / 20 % 2), 20}); /* dragged to and fro */
}

static tt_result step(tt_world *w, moved kinematic, int s)
{
    set_inputs(w, kinematic, s);
    return tt_world_step(w, 1.0 / 60);
}

/* After 5 s the piles have settled under the swinging box: the contact
 * arrays have the room the reserve gives the most contacts seen (half as
 * many again), and a step allocates nothing. */
TEST(a_world_at_steady_state_allocates_nothing_per_step)
{
    long worst = 0;
    for (int in = 0; in < TT_INTEGRATOR_COUNT; in++)
        for (int order = 0; order < 2; order++) {
            moved k;
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

/* A burst of new things before a step, so that it needs more contacts than
 * the steps before it made room for: grains apart from one another on the
 * chain and on the terrain ledge (shape and terrain contacts), a clump of
 * grains in one another on the circle (pairs), and a link that breaks in
 * the step. */
static void burst(tt_world *w, moved k)
{
    for (int i = 0; i < 20; i++) {
        double x = -19.5 + i, y = x < -10 ? -0.1 * (x + 20) : -1 - 0.05 * (x + 10);
        add(w, x, y + 0.38, 0.4);
    }
    for (int i = 0; i < 8; i++) add(w, 22.5 + i, 4.35, 0.4);
    for (int i = 0; i < 12; i++) add(w, -5.5 + (i % 6) * 0.15, 1.6 + (i / 6) * 0.3, 0.3);
    tt_particle_def pd = tt_particle_def_default(); /* both ends pinned: nothing shortens it */
    pd.pinned = true;
    pd.position = (tt_vec2){0, 12};
    tt_distance_def dd = tt_distance_def_default();
    dd.a = tt_particle_create(w, &pd);
    pd.position = (tt_vec2){3, 12};
    dd.b = tt_particle_create(w, &pd);
    dd.length = 1.0;
    dd.break_strain = 0.1;
    tt_distance_create(w, &dd);
    /* the chain nudged up: what sleeps on it (Verlet) wakes as the step begins */
    tt_shape_set_transform(w, k.chain, (tt_vec2){0, 0.01}, 0.0);
}

/* The every-feature scene before step `at`, its inputs for that step set:
 * built (at 0) or loaded from a snapshot taken once (later: a loaded world
 * steps as the one it was saved from, and has made room for no contacts
 * yet, so its step grows more inside). */
typedef struct scene_at {
    tt_integrator in;
    tt_solver_order order;
    int at;
    bool burst;
    void *snap;
    size_t size;
    moved k;
} scene_at;

static tt_world *scene_make(scene_at *sc, moved *k)
{
    if (sc->snap) {
        *k = sc->k; /* a loaded world keeps the handles of the one saved */
        return tt_world_load(sc->snap, sc->size);
    }
    tt_world *w = every_feature(sc->in, sc->order, k);
    for (int s = 0; s < sc->at; s++) step(w, *k, s);
    if (sc->burst) burst(w, *k);
    set_inputs(w, *k, sc->at);
    if (sc->at == 0) return w;
    sc->k = *k;
    tt_world_save(w, NULL, 0, &sc->size);
    sc->snap = malloc(sc->size);
    tt_world_save(w, sc->snap, sc->size, &sc->size);
    tt_world_destroy(w);
    return scene_make(sc, k);
}

/* The hashes of the twin that never runs out: after step `at`, and after
 * the three steps that follow it (computed once per scene, not per refusal). */
typedef struct twin {
    uint64_t step, on;
} twin;

static twin twin_of(scene_at *sc)
{
    moved k;
    tt_world *b = scene_make(sc, &k);
    twin t = {0, 0};
    if (tt_world_step(b, 1.0 / 60) == TT_OK) t.step = tt_world_hash(b);
    for (int s = sc->at + 1; s < sc->at + 4; s++)
        if (step(b, k, s) != TT_OK) t.step = 0;
    t.on = tt_world_hash(b);
    tt_world_destroy(b);
    return t;
}

/* Step `at` of the every-feature scene with the k-th allocation from the
 * step's start on refused. A step that gets all it asks for is the step the
 * twin took; one refused memory fails with TT_ENOMEM and the world as it
 * was before it, in its hash and in the steps that follow: retried with
 * memory, it goes on exactly as the twin. *refused: whether one was (k past
 * the step's allocations: none). */
static void step_with_refusal(scene_at *sc, twin t, long k, bool *refused)
{
    moved ka;
    tt_world *a = scene_make(sc, &ka);
    tt_stats before;
    tt_world_get_stats(a, &before);
    uint64_t h0 = tt_world_hash(a);
    tt_test_alloc_fail_from(k);
    tt_result r = tt_world_step(a, 1.0 / 60);
    *refused = tt_test_alloc_ok();
    char msg[256];
    snprintf(msg, sizeof msg, "%s", tt_last_error(a) ? tt_last_error(a) : "");
    tt_stats after;
    tt_world_get_stats(a, &after);
    if (r == TT_OK) { /* nothing refused, or a refusal the step does without at no cost */
        ENSURE(tt_world_hash(a) == t.step);
    } else {
        if (r != TT_ENOMEM || tt_world_hash(a) != h0)
            printf("    step %d, allocation %ld (asked for at %p) refused, step returned %d: %s\n", sc->at, k,
                   tt_test_alloc_refused_at(), (int)r, msg);
        ENSURE(*refused && r == TT_ENOMEM && after.steps == before.steps);
        ENSURE(strstr(msg, "the world is as it was") != NULL);
        ENSURE(tt_world_hash(a) == h0);
        if (strstr(msg, "before the step;")) { /* refused by a reserve: the step never began */
            tt_world_destroy(a);
            return;
        }
        ENSURE(tt_world_step(a, 1.0 / 60) == TT_OK); /* the same step again, with memory, and on */
        ENSURE(tt_world_hash(a) == t.step);
        for (int s = sc->at + 1; s < sc->at + 4; s++) ENSURE(step(a, ka, s) == TT_OK);
    }
    ENSURE(tt_world_hash(a) == (r == TT_OK ? t.step : t.on));
    tt_world_destroy(a);
}

/* Every allocation of the step refused in turn, for every integrator and
 * solver order: the first step (everything grows) and one after 30, with a
 * burst of contacts and a breaking link, sleepers waking (Verlet) and a pin
 * dragged at a limited rate; and step 30 as it comes. */
TEST(out_of_memory_inside_a_step_leaves_the_world_as_it_was)
{
    for (int in = 0; in < TT_INTEGRATOR_COUNT; in++)
        for (int order = 0; order < 2; order++)
            for (int at = 0; at <= 60; at += 30) {
                /* 60: step 30 again, without the burst (the end positions of step 29 are the next start) */
                scene_at sc = {(tt_integrator)in, order ? TT_JACOBI : TT_GAUSS_SEIDEL, at > 30 ? 30 : at, at <= 30, NULL, 0,
                               {{0, 0}, {0, 0}, {0, 0}}};
                const twin t = twin_of(&sc);
                ENSURE(t.step != 0);
                for (long k = 0; k < 1000; k++) {
                    bool refused = false;
                    step_with_refusal(&sc, t, k, &refused);
                    if (!refused) break;
                }
                free(sc.snap);
            }
}
