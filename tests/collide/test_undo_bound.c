/* Out of memory inside a step and what it costs (tt_world_step's doc): a
 * world whose step can need more memory than it has keeps a copy of what
 * the step changes; one whose contacts have all their room before it (no
 * pair possible, few static primitives, no events, bullets or terrain)
 * keeps none. Either way a refused allocation fails the step with the world
 * as it was: each allocation of the step refused in turn, where the world
 * changes from one kind to the other and where contacts first appear, the
 * hash after a failed step is the one before it, and the step retried goes
 * on as a twin that never ran out. */
#include "test.h"
#include "alloc_fail.h"
#include "tether.h"

#include <string.h>

enum { SIDE = 12, N = SIDE * SIDE };

typedef enum kind {
    POINTS,        /* pairs on, every radius 0, nothing else */
    SHAPE,         /* pairs off, one static circle under the lattice */
    POINTS_SHAPE,  /* pairs on, every radius 0, the circle */
    CLUSTER,       /* pairs on, radius 0.2, a lattice converging (the pair skip, then pairs) */
} kind;

/* A lattice 1 m apart above a circle of radius 3 (its top at y = 0): the
 * lowest row reaches it after about a quarter of a second. */
static tt_world *make(kind k, double radius, tt_particle *made)
{
    tt_world_def d = tt_world_def_default();
    d.substeps = 2;
    tt_world *w = tt_world_create(&d);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = radius;
    for (int i = 0; i < N; i++) {
        const double x = i % SIDE - 5.5, y = i / SIDE + 0.3;
        pd.position = (tt_vec2){x, y};
        pd.velocity = k == CLUSTER ? (tt_vec2){-x * 0.6, -(y - 6.0) * 0.6} : (tt_vec2){0.0, 0.0};
        made[i] = tt_particle_create(w, &pd);
    }
    if (k != SHAPE) {
        tt_collision_settings cs = tt_collision_settings_default();
        tt_world_set_collision(w, &cs);
    }
    if (k == SHAPE || k == POINTS_SHAPE) {
        tt_shape_def sd = tt_shape_def_default();
        sd.type = TT_SHAPE_CIRCLE;
        sd.radius = 3.0;
        sd.position = (tt_vec2){0.0, -3.0};
        tt_shape_create(w, &sd);
    }
    if (k == CLUSTER) tt_world_set_gravity(w, (tt_vec2){0.0, 0.0});
    return w;
}

/* What the script does before step `at` (the same to both twins; p: the
 * world's lattice). */
typedef void (*inputs)(tt_world *w, const tt_particle *p, int at);

static void nothing(tt_world *w, const tt_particle *p, int at) { (void)w, (void)p, (void)at; }

/* Before step 5 every radius becomes 0.3 and 48 particles are put 0.1 m
 * apart: that step finds more pairs than any room made before. */
static void radii_grow(tt_world *w, const tt_particle *made, int at)
{
    if (at != 5) return;
    for (int i = 0; i < N; i++) tt_particle_set_radius(w, made[i], 0.3);
    for (int i = 0; i < 48; i++)
        tt_particle_set_position(w, made[i], (tt_vec2){-5.0 + 0.1 * (i % 8), 3.0 + 0.1 * (i / 8)}, TT_MOVE_KEEP_VELOCITY);
}

/* Before step events_at, events on. */
static int events_at;

static void events_on(tt_world *w, const tt_particle *p, int at)
{
    (void)p;
    if (at != events_at) return;
    tt_collision_settings cs;
    tt_world_get_collision(w, &cs);
    cs.events = TT_EVENT_BEGIN | TT_EVENT_PERSIST | TT_EVENT_END;
    tt_world_set_collision(w, &cs);
}

/* Step `at` with every allocation from the k-th on refused, k = 0, 1, ...
 * until the step makes no more. Returns how many allocations the step made
 * (with everything granted), or −1 on a failed check. */
static long refuse_each(kind kd, double radius, inputs in, int at)
{
    for (long k = 0;; k++) {
        tt_particle pa[N], pb[N];
        tt_world *a = make(kd, radius, pa), *b = make(kd, radius, pb);
        bool ok = true;
        for (int s = 0; s < at; s++) {
            in(a, pa, s), in(b, pb, s);
            ok &= tt_world_step(a, 1.0 / 60) == TT_OK && tt_world_step(b, 1.0 / 60) == TT_OK;
        }
        in(a, pa, at), in(b, pb, at);
        const uint64_t h0 = tt_world_hash(a);
        tt_test_alloc_fail_from(k);
        const tt_result r = tt_world_step(a, 1.0 / 60);
        const bool refused = tt_test_alloc_ok();
        if (r != TT_OK) {
            ok &= refused && r == TT_ENOMEM && tt_world_hash(a) == h0;
            if (!ok) printf("    kind %d, step %d, allocation %ld refused: %s\n", (int)kd, at, k, tt_last_error(a));
            ok &= tt_world_step(a, 1.0 / 60) == TT_OK; /* the same step again, with memory */
        }
        ok &= tt_world_step(b, 1.0 / 60) == TT_OK;
        for (int s = at + 1; s < at + 4; s++) {
            in(a, pa, s), in(b, pb, s);
            ok &= tt_world_step(a, 1.0 / 60) == TT_OK && tt_world_step(b, 1.0 / 60) == TT_OK;
        }
        ok &= tt_world_hash(a) == tt_world_hash(b);
        tt_world_destroy(a);
        tt_world_destroy(b);
        if (!ok) return -1;
        if (!refused) return k;
    }
}

/* The first step after which the world has a contact of the kind asked. */
static int first_contact(kind kd, double radius, bool pairs)
{
    tt_particle p[N];
    tt_world *w = make(kd, radius, p);
    int at = -1;
    for (int s = 0; s < 200 && at < 0; s++) {
        tt_world_step(w, 1.0 / 60);
        tt_collision_stats st;
        tt_world_get_collision_stats(w, &st);
        if (pairs ? st.pair_contacts > 0 : st.shape_contacts > 0) at = s;
    }
    tt_world_destroy(w);
    return at;
}

static size_t memory_after_a_step(kind kd, double radius)
{
    tt_particle p[N];
    tt_world *w = make(kd, radius, p);
    tt_world_step(w, 1.0 / 60);
    tt_memory m;
    tt_world_get_memory(w, &m);
    tt_world_destroy(w);
    return m.total;
}

/* Pairs on with every radius 0 can find no pair: the world keeps no copy
 * for the undo, at least 32 bytes a particle less than the same lattice
 * with radii (nothing touching, but pairs possible). */
TEST(a_world_whose_step_cannot_run_out_keeps_no_copy_of_it)
{
    const size_t points = memory_after_a_step(POINTS, 0.0), round = memory_after_a_step(POINTS, 0.2);
    ENSURE(round >= points + 32 * (size_t)N);
}

/* The lattice lands on the circle (pairs off): the shape contacts, a
 * particle at most once each, had their room before; the step where they
 * first appear allocates nothing. */
TEST(shape_contacts_of_a_lone_primitive_need_nothing_inside_the_step)
{
    const int at = first_contact(SHAPE, 0.2, false);
    ENSURE(at > 0);
    ENSURE(refuse_each(SHAPE, 0.2, nothing, at) == 0);
    ENSURE(refuse_each(SHAPE, 0.2, nothing, at + 1) == 0);
}

/* Points on the circle with pairs on: the first step with shape contacts
 * grows the bottom-up pass (a copy is kept for it), the next has room. */
TEST(points_on_a_shape_with_pairs_on_fail_a_step_whole)
{
    const int at = first_contact(POINTS_SHAPE, 0.0, false);
    ENSURE(at > 0);
    for (int s = at - 1; s <= at + 1; s++) ENSURE(refuse_each(POINTS_SHAPE, 0.0, nothing, s) >= 0);
}

/* A world that kept no copy gets radii (pairs possible from that step on)
 * or events (records grow with the contacts): that very step keeps one. */
TEST(a_world_that_starts_to_need_the_copy_has_it_that_step)
{
    ENSURE(refuse_each(POINTS, 0.0, radii_grow, 5) > 0);
    ENSURE(refuse_each(POINTS_SHAPE, 0.0, radii_grow, 5) > 0);
    const int at = first_contact(SHAPE, 0.2, false);
    ENSURE(at > 5);
    events_at = 5;
    ENSURE(refuse_each(SHAPE, 0.2, events_on, 5) >= 0);
    events_at = at + 10; /* the lattice on the circle: more records than the room made before */
    ENSURE(refuse_each(SHAPE, 0.2, events_on, at + 10) > 0);
}

/* Pairs on, none near (the grid unbuilt while the skip's bound holds), then
 * the step in which the first pairs appear: refused there, it fails whole. */
TEST(out_of_memory_where_pairs_first_appear_after_skipping_leaves_the_world_as_it_was)
{
    const int at = first_contact(CLUSTER, 0.2, true);
    ENSURE(at > 5);
    ENSURE(refuse_each(CLUSTER, 0.2, nothing, at) > 0);
}
