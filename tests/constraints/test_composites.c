/* Composites: what each builder makes, the lattice body's centre of mass and
 * orientation against the exact rigid motion, removal, and all-or-nothing
 * creation: a creating call that fails, on bad input or out of memory half
 * way, leaves the world exactly as it was (shapes, constraints and springs
 * are checked here too, with the same twin worlds). */
#include "test.h"
#include "alloc_fail.h"
#include "core/internal.h"
#include "tether.h"

#include <stdlib.h>
#include <string.h>

static const double PI = 3.14159265358979323846;

static tt_vec2 pos(const tt_world *w, tt_particle p)
{
    tt_vec2 x = {NAN, NAN};
    tt_particle_get_position(w, p, &x);
    return x;
}

TEST(lattice_spins_as_a_rigid_body_centre_and_angle_exact)
{
    tt_world_def wd = tt_world_def_default();
    wd.gravity = (tt_vec2){0, 0};
    wd.iterations = 50;
    tt_world *w = tt_world_create(&wd);
    tt_lattice_def ld = tt_lattice_def_default();
    ld.center = (tt_vec2){1, 2};
    ld.width = 2;
    ld.height = 1;
    ld.columns = 4;
    ld.rows = 3;
    ld.angle = 0.3;
    tt_composite c = tt_lattice_create(w, &ld);
    ENSURE(c.gen != 0);
    tt_vec2 cm;
    double a;
    ENSURE_OK(tt_composite_get_center(w, c, &cm));
    ENSURE_NEAR(cm.x, 1, 1e-12);
    ENSURE_NEAR(cm.y, 2, 1e-12);
    ENSURE_OK(tt_composite_get_angle(w, c, &a));
    ENSURE_NEAR(a, 0, 1e-12); /* measured from the shape as made */
    tt_particle ps[12];
    uint32_t n;
    ENSURE_OK(tt_composite_get_particles(w, c, ps, 12, &n));
    ENSURE(n == 12);
    /* spin at ω = 2 rad/s and drift at (0.5, 0): v = v0 + ω × r */
    const double om = 2.0;
    for (uint32_t i = 0; i < n; i++) {
        tt_vec2 x = pos(w, ps[i]);
        tt_particle_set_velocity(w, ps[i], (tt_vec2){0.5 - om * (x.y - 2), om * (x.x - 1)});
    }
    double rest[12];
    for (uint32_t i = 0; i < n; i++) rest[i] = hypot(pos(w, ps[i]).x - 1, pos(w, ps[i]).y - 2);
    const int steps = 60;
    for (int s = 0; s < steps; s++) tt_world_step(w, 1.0 / 240);
    double t = steps / 240.0;
    ENSURE_OK(tt_composite_get_center(w, c, &cm));
    ENSURE_NEAR(cm.x, 1 + 0.5 * t, 1e-9); /* momentum is conserved: the centre drifts exactly */
    ENSURE_NEAR(cm.y, 2, 1e-9);
    ENSURE_OK(tt_composite_get_angle(w, c, &a));
    ENSURE_NEAR(a, om * t, 0.01 * om * t); /* projection trims a little rotation energy */
    for (uint32_t i = 0; i < n; i++) /* it stays rigid: every particle keeps its distance to the centre */
        ENSURE_NEAR(hypot(pos(w, ps[i]).x - cm.x, pos(w, ps[i]).y - cm.y), rest[i], 1e-3);
    tt_world_destroy(w);
}

TEST(lattice_polygon_dropped_on_the_floor_keeps_its_shape)
{
    tt_world_def wd = tt_world_def_default();
    wd.iterations = 30;
    tt_world *w = tt_world_create(&wd);
    tt_vec2 tri[3] = {{0, 2}, {1, 2}, {0.5, 3}};
    tt_lattice_def ld = tt_lattice_def_default();
    ld.points = tri;
    ld.point_count = 3;
    tt_composite c = tt_lattice_create(w, &ld);
    ENSURE(c.gen != 0);
    ENSURE(tt_world_constraint_count(w) == 3);
    tt_bounds_def bd = tt_bounds_def_default();
    bd.min = (tt_vec2){-10, 0};
    bd.friction = 1;
    tt_bounds_create(w, &bd);
    for (int s = 0; s < 240; s++) tt_world_step(w, 1.0 / 60);
    tt_particle ps[3];
    uint32_t n;
    tt_composite_get_particles(w, c, ps, 3, &n);
    ENSURE_NEAR(pos(w, ps[0]).y, 0, 1e-4); /* landed flat on its base (within what 30 sweeps leave) */
    ENSURE_NEAR(pos(w, ps[1]).y, 0, 1e-4);
    ENSURE_NEAR(hypot(pos(w, ps[0]).x - pos(w, ps[1]).x, 0), 1, 1e-6);
    ENSURE_NEAR(pos(w, ps[2]).y, 1, 1e-4);
    double a;
    tt_composite_get_angle(w, c, &a);
    ENSURE_NEAR(a, 0, 1e-4);
    tt_world_destroy(w);
}

TEST(each_builder_makes_what_it_documents)
{
    tt_world *w = tt_world_create(NULL);
    tt_rope_def rd = tt_rope_def_default();
    rd.segments = 7;
    rd.pin_finish = true;
    tt_composite rope = tt_rope_create(w, &rd);
    uint32_t np, nc;
    tt_composite_get_particles(w, rope, NULL, 0, &np);
    tt_composite_get_constraints(w, rope, NULL, 0, &nc);
    ENSURE(np == 8 && nc == 7);
    tt_particle rp[8];
    tt_composite_get_particles(w, rope, rp, 8, &np);
    bool pinned;
    tt_particle_get_pinned(w, rp[0], &pinned);
    ENSURE(pinned);
    tt_particle_get_pinned(w, rp[7], &pinned);
    ENSURE(pinned);
    ENSURE_NEAR(pos(w, rp[7]).x, 1, 1e-15);

    tt_ragdoll_def gd = tt_ragdoll_def_default();
    tt_composite doll = tt_ragdoll_create(w, &gd);
    tt_composite_get_particles(w, doll, NULL, 0, &np);
    tt_composite_get_constraints(w, doll, NULL, 0, &nc);
    ENSURE(np == 11 && nc == 13 + 6);
    tt_particle dp[11];
    tt_composite_get_particles(w, doll, dp, 11, &np);
    ENSURE(pos(w, dp[0]).y > pos(w, dp[1]).y && pos(w, dp[1]).y > pos(w, dp[2]).y); /* head, neck, pelvis */
    ENSURE(pos(w, dp[8]).y < pos(w, dp[7]).y);                                       /* foot below knee */
    ENSURE_NEAR(pos(w, dp[0]).y - pos(w, dp[8]).y, 1.8, 1e-12);
    tt_constraint dc[19];
    tt_composite_get_constraints(w, doll, dc, 19, &nc);
    for (uint32_t i = 0; i < nc; i++) { /* made satisfied */
        double e;
        tt_constraint_get_error(w, dc[i], &e);
        ENSURE(e < 1e-12);
    }

    tt_soft_body_def sd = tt_soft_body_def_default();
    sd.segments = 12;
    tt_composite soft = tt_soft_body_create(w, &sd);
    tt_composite_get_constraints(w, soft, NULL, 0, &nc);
    ENSURE(nc == 13); /* 12 edges + the area */

    tt_cloth_def cd = tt_cloth_def_default();
    cd.columns = 5;
    cd.rows = 4;
    cd.bend_stiffness = 0;
    tt_composite cloth = tt_cloth_create(w, &cd);
    tt_composite_get_constraints(w, cloth, NULL, 0, &nc);
    ENSURE(nc == 4 * 4 + 5 * 3 + 2 * 4 * 3);
    ENSURE(tt_world_composite_count(w) == 4);

    tt_lattice_def ld = tt_lattice_def_default();
    ld.columns = 1;
    ENSURE(tt_lattice_create(w, &ld).gen == 0 && strstr(tt_last_error(w), "columns"));
    rd.common.mass = 0;
    ENSURE(tt_rope_create(w, &rd).gen == 0 && strstr(tt_last_error(w), "mass"));
    cd.width = NAN;
    ENSURE(tt_cloth_create(w, &cd).gen == 0);
    tt_world_destroy(w);
}

TEST(removing_a_composite_removes_everything_it_made_and_nothing_else)
{
    tt_world *w = tt_world_create(NULL);
    tt_particle_def pd = tt_particle_def_default();
    tt_particle keep = tt_particle_create(w, &pd);
    tt_cloth_def cd = tt_cloth_def_default();
    cd.break_strain = 0.1;
    tt_composite c = tt_cloth_create(w, &cd);
    tt_constraint first;
    uint32_t n;
    tt_composite_get_constraints(w, c, &first, 1, &n);
    tt_constraint_destroy(w, first); /* already gone: destroy skips it */
    ENSURE_OK(tt_composite_destroy(w, c));
    ENSURE(tt_world_particle_count(w) == 1 && tt_particle_is_valid(w, keep));
    ENSURE(tt_world_constraint_count(w) == 0 && tt_world_composite_count(w) == 0);
    ENSURE(!tt_composite_is_valid(w, c));
    ENSURE(tt_composite_destroy(w, c) == TT_ESTALE);
    tt_vec2 cm;
    ENSURE(tt_composite_get_center(w, c, &cm) == TT_ESTALE);
    tt_world_destroy(w);
}

TEST(a_composite_that_does_not_fit_leaves_nothing_behind)
{
    tt_world_def wd = tt_world_def_default();
    wd.max_particles = 5;
    tt_world *w = tt_world_create(&wd);
    tt_rope_def rd = tt_rope_def_default();
    rd.segments = 9;
    ENSURE(tt_rope_create(w, &rd).gen == 0);
    ENSURE(strstr(tt_last_error(w), "full") != NULL);
    ENSURE(tt_world_particle_count(w) == 0);
    ENSURE(tt_world_constraint_count(w) == 0 && tt_world_composite_count(w) == 0);
    rd.segments = 4;
    ENSURE(tt_rope_create(w, &rd).gen != 0); /* the slots were given back */
    tt_world_destroy(w);
}

TEST(ragdoll_limits_hold_while_it_falls_and_lands)
{
    tt_world_def wd = tt_world_def_default();
    wd.iterations = 20;
    tt_world *w = tt_world_create(&wd);
    tt_ragdoll_def gd = tt_ragdoll_def_default();
    gd.position = (tt_vec2){0, 3};
    tt_composite doll = tt_ragdoll_create(w, &gd);
    tt_particle dp[11];
    uint32_t n;
    tt_composite_get_particles(w, doll, dp, 11, &n);
    tt_particle_set_velocity(w, dp[0], (tt_vec2){4, 0}); /* a shove at the head */
    tt_bounds_def bd = tt_bounds_def_default();
    bd.min = (tt_vec2){-10, 0};
    bd.friction = 0.5;
    tt_bounds_create(w, &bd);
    tt_constraint dc[19];
    tt_composite_get_constraints(w, doll, dc, 19, &n);
    double worst = 0;
    for (int s = 0; s < 300; s++) {
        tt_world_step(w, 1.0 / 60);
        for (uint32_t i = 0; i < n; i++) {
            double e;
            tt_constraint_get_error(w, dc[i], &e);
            worst = fmax(worst, e);
        }
    }
    ENSURE(worst < 0.05); /* bones within 5 cm, limits within 0.05 rad, every step */
    tt_vec2 cm;
    tt_composite_get_center(w, doll, &cm);
    ENSURE(cm.y < 0.6); /* it fell over */
    for (uint32_t i = 0; i < 11; i++) ENSURE(pos(w, dp[i]).y >= -1e-9);
    (void)PI;
    tt_world_destroy(w);
}

/* ---- a call that fails leaves the world exactly as it was -------------------- */

/* A world with a past: particles made and removed (free slots to hand out
 * again) and, with `constraints`, collisions on and constraints made and
 * removed; without, neither group is registered yet. */
static tt_world *lived_in(bool constraints, uint32_t max_particles)
{
    tt_world_def wd = tt_world_def_default();
    wd.max_particles = max_particles;
    tt_world *w = tt_world_create(&wd);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.1;
    tt_particle p[6];
    for (int i = 0; i < 6; i++) {
        pd.position = (tt_vec2){0.3 * i, 1.0 + 0.2 * i};
        p[i] = tt_particle_create(w, &pd);
    }
    if (constraints) {
        tt_collision_settings cs = tt_collision_settings_default();
        tt_world_set_collision(w, &cs);
        tt_distance_def dd = tt_distance_def_default();
        dd.a = p[0];
        dd.b = p[2];
        tt_constraint gone = tt_distance_create(w, &dd);
        dd.a = p[2];
        dd.b = p[3];
        tt_distance_create(w, &dd);
        tt_constraint_destroy(w, gone);
    }
    tt_particle_destroy(w, p[4]);
    tt_particle_destroy(w, p[1]);
    return w;
}

/* A handle without its world's tag (the generation's bits above TT_HANDLE_GEN_BITS): twins hand out the same. */
static uint64_t untagged(uint32_t index, uint32_t gen) { return (uint64_t)(gen & ((1u << TT_HANDLE_GEN_BITS) - 1)) << 32 | index; }

static bool same_pairs_excluded(const tt_world *a, const tt_world *b)
{
    uint32_t n = a->ppool.count > b->ppool.count ? a->ppool.count : b->ppool.count;
    for (uint32_t i = 0; i < n; i++)
        for (uint32_t j = i + 1; j < n; j++)
            if (tt__constraint_pair_excluded(a, i, j) != tt__constraint_pair_excluded(b, i, j)) return false;
    return true;
}

/* The handles of one shape, two particles, a constraint, a rope and a spring
 * made now (the shape first: a group left registered by a failed call would
 * then come first in the sweeps of one twin only). */
static void make_the_same(tt_world *w, uint64_t out[6])
{
    tt_shape_def sd = tt_shape_def_default();
    sd.type = TT_SHAPE_CIRCLE;
    sd.position = (tt_vec2){0, -2};
    tt_shape s = tt_shape_create(w, &sd);
    tt_particle_def pd = tt_particle_def_default();
    pd.position = (tt_vec2){0.5, 2};
    tt_particle p = tt_particle_create(w, &pd);
    pd.position = (tt_vec2){1, 2.5};
    tt_particle q = tt_particle_create(w, &pd);
    tt_distance_def dd = tt_distance_def_default();
    dd.a = p;
    dd.b = q;
    tt_constraint c = tt_distance_create(w, &dd);
    tt_rope_def rd = tt_rope_def_default();
    rd.start = (tt_vec2){-1, 3};
    rd.finish = (tt_vec2){1, 3};
    rd.segments = 4;
    tt_composite r = tt_rope_create(w, &rd);
    tt_spring_def kd = tt_spring_def_default();
    kd.a = p;
    kd.b = q;
    tt_spring k = tt_spring_create(w, &kd);
    out[0] = untagged(s.index, s.gen);
    out[1] = untagged(p.index, p.gen);
    out[2] = untagged(q.index, q.gen);
    out[3] = untagged(c.index, c.gen);
    out[4] = untagged(r.index, r.gen);
    out[5] = untagged(k.index, k.gen);
}

/* Where twins a and b part, or NULL: the hash and counts now, the pairs kept
 * from colliding, the handles the same calls hand out next, the hash 10
 * steps later. */
static const char *parting(tt_world *a, tt_world *b)
{
    if (tt_world_hash(a) != tt_world_hash(b)) return "the twins differ in the hash right after the call";
    if (tt_world_particle_count(a) != tt_world_particle_count(b) || tt_world_constraint_count(a) != tt_world_constraint_count(b) ||
        tt_world_composite_count(a) != tt_world_composite_count(b) || tt_world_shape_count(a) != tt_world_shape_count(b) ||
        tt_world_spring_count(a) != tt_world_spring_count(b))
        return "the twins differ in the counts";
    if (!same_pairs_excluded(a, b)) return "the twins differ in the pairs kept from colliding";
    uint64_t na[6], nb[6];
    make_the_same(a, na);
    make_the_same(b, nb);
    for (int i = 0; i < 6; i++)
        if (na[i] != nb[i] || na[i] == 0) return "the twins differ in the next handles";
    for (int s = 0; s < 10; s++) {
        tt_world_step(a, 1.0 / 60);
        tt_world_step(b, 1.0 / 60);
    }
    return tt_world_hash(a) != tt_world_hash(b) ? "the twins differ in the hash 10 steps later" : NULL;
}

/* One creating call on w; true when it failed. */
typedef bool (*call_fn)(tt_world *w);

/* call fails on one of two twin worlds, which must stay twins. */
static const char *fails_cleanly(call_fn call, bool constraints, uint32_t max_particles)
{
    tt_world *a = lived_in(constraints, max_particles), *b = lived_in(constraints, max_particles);
    const char *why = call(a) ? parting(a, b) : "the call did not fail";
    tt_world_destroy(a);
    tt_world_destroy(b);
    return why;
}

/* call runs out of memory at its first allocation, then its second, … on one
 * of two twins each time, until it gets to the end: each time it fails, the
 * twins must still agree. */
static const char *fails_cleanly_out_of_memory(call_fn call, bool constraints)
{
    static char msg[160];
    for (long k = 0; k < 100000; k++) {
        tt_world *a = lived_in(constraints, 1u << 24), *b = lived_in(constraints, 1u << 24);
        tt_test_alloc_fail_from(k);
        bool failed = call(a);
        bool refused = tt_test_alloc_ok();
        const char *why = !failed ? NULL : refused ? parting(a, b) : "it failed with memory to spare";
        tt_world_destroy(a);
        tt_world_destroy(b);
        if (why) {
            snprintf(msg, sizeof msg, "allocation %ld refused: %s", k, why);
            return msg;
        }
        if (!refused) return NULL; /* it ran to the end */
    }
    return "it never ran to the end";
}

typedef struct named_call {
    const char *name;
    call_fn fn;
} named_call;
#define CALL(f) {#f, f}

/* why: NULL, or where the twins parted after the call named `name`. */
#define ENSURE_CLEAN(name, why)                                                              \
    do {                                                                                     \
        const char *why_ = (why);                                                            \
        if (why_) {                                                                          \
            tt_test_fail(__FILE__, __LINE__, "%s: %s", (name), why_);                          \
            return;                                                                          \
        }                                                                                    \
    } while (0)

/* Calls that fail on bad input found half way: a particle past TT_MAX_VALUE. */
static bool cloth_past_the_edge(tt_world *w)
{
    tt_cloth_def d = tt_cloth_def_default();
    d.origin = (tt_vec2){TT_MAX_VALUE - 0.5, 0}; /* the far edge, 0.5 m past */
    d.columns = d.rows = 4;
    return tt_cloth_create(w, &d).gen == 0;
}

static bool ragdoll_past_the_edge(tt_world *w)
{
    tt_ragdoll_def d = tt_ragdoll_def_default();
    d.position = (tt_vec2){TT_MAX_VALUE, 0}; /* head, neck, pelvis fit; the right elbow does not */
    return tt_ragdoll_create(w, &d).gen == 0;
}

static bool soft_body_past_the_edge(tt_world *w)
{
    tt_soft_body_def d = tt_soft_body_def_default();
    d.center = (tt_vec2){0, TT_MAX_VALUE - 0.5}; /* the ring's top, a quarter of the way round */
    d.segments = 8;
    return tt_soft_body_create(w, &d).gen == 0;
}

static bool lattice_past_the_edge(tt_world *w)
{
    tt_lattice_def d = tt_lattice_def_default();
    d.center = (tt_vec2){TT_MAX_VALUE - 0.5, 0};
    d.width = 2;
    d.columns = 3;
    return tt_lattice_create(w, &d).gen == 0;
}

static bool rope_past_the_edge(tt_world *w)
{
    tt_rope_def d = tt_rope_def_default();
    d.start = (tt_vec2){-152580229995.33337, 0};
    d.finish = (tt_vec2){TT_MAX_VALUE, 0};
    d.segments = 9; /* start + (end − start)·1 rounds to 1e12 + 1.2e-4: the last particle */
    return tt_rope_create(w, &d).gen == 0;
}

TEST(a_composite_past_the_largest_coordinate_leaves_the_world_as_it_was)
{
    const named_call calls[] = {CALL(cloth_past_the_edge), CALL(ragdoll_past_the_edge), CALL(soft_body_past_the_edge),
                                CALL(lattice_past_the_edge), CALL(rope_past_the_edge)};
    for (int k = 0; k < 2; k++)
        for (size_t i = 0; i < sizeof calls / sizeof calls[0]; i++)
            ENSURE_CLEAN(calls[i].name, fails_cleanly(calls[i].fn, k, 1u << 24));
    tt_world *w = tt_world_create(NULL);
    cloth_past_the_edge(w);
    ENSURE(strstr(tt_last_error(w), "tt_cloth_create: ") == tt_last_error(w));
    ENSURE(strstr(tt_last_error(w), "1e+12") != NULL);
    tt_world_destroy(w);
}

/* Lattice polygons a polygon shape would refuse too. */
static bool lattice_of(tt_world *w, const tt_vec2 *pts, uint32_t n)
{
    tt_lattice_def d = tt_lattice_def_default();
    d.points = pts;
    d.point_count = n;
    return tt_lattice_create(w, &d).gen == 0;
}

static bool lattice_on_a_line(tt_world *w)
{
    const tt_vec2 pts[3] = {{0, 0}, {1, 0}, {2, 0}};
    return lattice_of(w, pts, 3);
}

static bool lattice_with_a_point_twice(tt_world *w)
{
    const tt_vec2 pts[4] = {{0, 0}, {1, 0}, {1, 0}, {0, 1}};
    return lattice_of(w, pts, 4);
}

static bool lattice_meeting_itself(tt_world *w)
{
    const tt_vec2 pts[6] = {{0, 0}, {2, -1}, {2, 1}, {0, 0}, {-2, 1}, {-2, -1}}; /* two triangles touching at a tip */
    return lattice_of(w, pts, 6);
}

TEST(a_lattice_refuses_collinear_or_repeated_points_as_a_polygon_shape_does)
{
    const named_call calls[] = {CALL(lattice_on_a_line), CALL(lattice_with_a_point_twice), CALL(lattice_meeting_itself)};
    for (int k = 0; k < 2; k++)
        for (size_t i = 0; i < sizeof calls / sizeof calls[0]; i++)
            ENSURE_CLEAN(calls[i].name, fails_cleanly(calls[i].fn, k, 1u << 24));
    tt_world *w = tt_world_create(NULL);
    ENSURE(lattice_on_a_line(w));
    ENSURE(strcmp(tt_last_error(w), "tt_lattice_create: points must make a polygon with no repeated or collinear points (at point 1)") == 0);
    ENSURE(lattice_meeting_itself(w));
    ENSURE(strstr(tt_last_error(w), "(at point 3)") != NULL);
    const tt_vec2 line[3] = {{0, 0}, {1, 0}, {2, 0}};
    tt_shape_def sd = tt_shape_def_default();
    sd.type = TT_SHAPE_POLYGON;
    sd.points = line;
    sd.count = 3;
    ENSURE(tt_shape_create(w, &sd).gen == 0);
    ENSURE(strstr(tt_last_error(w), "no repeated or collinear points (at point 1)") != NULL);
    const tt_vec2 notch[5] = {{0, 0}, {2, 0}, {2, 2}, {1, 1}, {0, 2}}; /* concave: every pair is braced, so it stays rigid */
    ENSURE(!lattice_of(w, notch, 5));
    ENSURE(tt_world_composite_count(w) == 1 && tt_world_constraint_count(w) == 10);
    tt_world_destroy(w);
}

/* Valid calls, for a world full half way and for memory running out. */
static bool make_cloth(tt_world *w)
{
    tt_cloth_def d = tt_cloth_def_default(); /* 16 × 16: the particle arrays grow half way */
    d.origin = (tt_vec2){-1, 4};
    d.break_strain = 0.5;
    return tt_cloth_create(w, &d).gen == 0;
}

static bool make_ragdoll(tt_world *w)
{
    tt_ragdoll_def d = tt_ragdoll_def_default();
    d.position = (tt_vec2){2, 3};
    return tt_ragdoll_create(w, &d).gen == 0;
}

static bool make_soft_body(tt_world *w)
{
    tt_soft_body_def d = tt_soft_body_def_default();
    d.center = (tt_vec2){-2, 3};
    d.ring_radius = 0.5;
    return tt_soft_body_create(w, &d).gen == 0;
}

static bool make_lattice(tt_world *w)
{
    tt_lattice_def d = tt_lattice_def_default();
    d.center = (tt_vec2){0, 5};
    d.columns = d.rows = 4;
    return tt_lattice_create(w, &d).gen == 0;
}

static bool make_lattice_polygon(tt_world *w)
{
    tt_vec2 pts[4] = {{0, 6}, {1, 6}, {1.2, 7}, {0.3, 6.8}};
    tt_lattice_def d = tt_lattice_def_default();
    d.points = pts;
    d.point_count = 4;
    return tt_lattice_create(w, &d).gen == 0;
}

static bool make_rope(tt_world *w)
{
    tt_rope_def d = tt_rope_def_default();
    d.start = (tt_vec2){-3, 4};
    d.finish = (tt_vec2){-1, 4};
    return tt_rope_create(w, &d).gen == 0;
}

TEST(a_composite_that_fills_the_world_half_way_leaves_it_as_it_was)
{
    /* 4 live particles, 2 free slots: 8 more fit in 12, fewer than each makes */
    const named_call calls[] = {CALL(make_cloth), CALL(make_ragdoll), CALL(make_soft_body), CALL(make_lattice), CALL(make_rope)};
    for (int k = 0; k < 2; k++)
        for (size_t i = 0; i < sizeof calls / sizeof calls[0]; i++)
            ENSURE_CLEAN(calls[i].name, fails_cleanly(calls[i].fn, k, 12));
    tt_world_def wd = tt_world_def_default();
    wd.max_particles = 12;
    tt_world *w = tt_world_create(&wd);
    ENSURE(make_cloth(w));
    ENSURE(strstr(tt_last_error(w), "full") != NULL);
    tt_world_destroy(w);
}

TEST(a_composite_out_of_memory_half_way_leaves_the_world_as_it_was)
{
    const named_call calls[] = {CALL(make_cloth), CALL(make_ragdoll), CALL(make_soft_body), CALL(make_lattice),
                                CALL(make_lattice_polygon), CALL(make_rope)};
    for (int k = 0; k < 2; k++)
        for (size_t i = 0; i < sizeof calls / sizeof calls[0]; i++)
            ENSURE_CLEAN(calls[i].name, fails_cleanly_out_of_memory(calls[i].fn, k));
}

/* The other creating calls, out of memory: each makes one thing, on the
 * lived-in world's live particles 0, 2, 3 and 5. */
static tt_particle live(tt_world *w, uint32_t i)
{
    tt_particle ps[4];
    tt_world_list_particles(w, ps, 4);
    return ps[i];
}

static bool make_polygon(tt_world *w)
{
    tt_vec2 pts[5] = {{0, 0}, {1, 0}, {1.5, 0.5}, {1, 1}, {0, 1}};
    tt_shape_def d = tt_shape_def_default();
    d.type = TT_SHAPE_POLYGON;
    d.points = pts;
    d.count = 5;
    return tt_shape_create(w, &d).gen == 0;
}

static bool make_chain(tt_world *w)
{
    tt_vec2 pts[3] = {{-3, 0}, {0, -1}, {3, 0}};
    tt_shape_def d = tt_shape_def_default();
    d.type = TT_SHAPE_CHAIN;
    d.points = pts;
    d.count = 3;
    return tt_shape_create(w, &d).gen == 0;
}

static bool make_area(tt_world *w)
{
    tt_particle ps[3] = {live(w, 0), live(w, 1), live(w, 3)};
    tt_area_def d = tt_area_def_default();
    d.particles = ps;
    d.count = 3;
    return tt_area_create(w, &d).gen == 0;
}

static bool make_bounds(tt_world *w)
{
    tt_particle ps[2] = {live(w, 1), live(w, 2)};
    tt_bounds_def d = tt_bounds_def_default();
    d.particles = ps;
    d.count = 2;
    return tt_bounds_create(w, &d).gen == 0;
}

static bool make_distance(tt_world *w)
{
    tt_distance_def d = tt_distance_def_default();
    d.a = live(w, 0);
    d.b = live(w, 3);
    return tt_distance_create(w, &d).gen == 0;
}

static bool make_angle(tt_world *w)
{
    tt_angle_def d = tt_angle_def_default();
    d.a = live(w, 0);
    d.b = live(w, 1);
    d.c = live(w, 2);
    return tt_angle_create(w, &d).gen == 0;
}

static bool make_spring(tt_world *w)
{
    tt_spring_def d = tt_spring_def_default();
    d.a = live(w, 1);
    d.b = live(w, 3);
    return tt_spring_create(w, &d).gen == 0;
}

static bool make_particle(tt_world *w)
{
    tt_particle_def d = tt_particle_def_default();
    d.position = (tt_vec2){3, 3};
    return tt_particle_create(w, &d).gen == 0;
}

TEST(shapes_constraints_and_springs_out_of_memory_leave_the_world_as_it_was)
{
    const named_call calls[] = {CALL(make_polygon), CALL(make_chain), CALL(make_area), CALL(make_bounds),
                                CALL(make_distance), CALL(make_angle), CALL(make_spring), CALL(make_particle)};
    for (int k = 0; k < 2; k++)
        for (size_t i = 0; i < sizeof calls / sizeof calls[0]; i++)
            ENSURE_CLEAN(calls[i].name, fails_cleanly_out_of_memory(calls[i].fn, k));
}

/* Found by the C fuzzer (seed 23, call 333): a composite whose last part is
 * refused (here the soft body's area compliance, a denormal) was undone,
 * yet the world's epoch stayed bumped by the particles it made and removed,
 * so a velocity integrator's end-of-substep positions, world state since
 * the stream, were no longer current: the hash changed. */
TEST(a_refused_composite_leaves_the_epoch_and_so_the_hash_as_it_was)
{
    tt_world_def wd = tt_world_def_default();
    wd.integrator = TT_LEAPFROG;
    tt_world *w = tt_world_create(&wd);
    tt_collision_settings cs = tt_collision_settings_default();
    tt_world_set_collision(w, &cs);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.1;
    for (int i = 0; i < 10; i++) {
        pd.position = (tt_vec2){i * 0.3, 1};
        tt_particle_create(w, &pd);
    }
    tt_world_step(w, 1.0 / 60);
    uint64_t h0 = tt_world_hash(w);
    tt_soft_body_def sd = tt_soft_body_def_default();
    sd.center = (tt_vec2){5, 5};
    sd.segments = 10;
    sd.area_compliance = 1e-320;
    ENSURE(tt_soft_body_create(w, &sd).gen == 0);
    ENSURE(tt_world_hash(w) == h0);
    tt_world_destroy(w);
}
