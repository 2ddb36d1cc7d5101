/* Targets the script moves between steps (a rope's length, a pin's anchor,
 * a kinematic shape's transform) must move across the substeps of the next
 * step, not jump in the first: a particle reeled in, dragged or carried at
 * 1 m/s moves at 1 m/s in every substep, at 1, 4 and 8 substeps. The per-substep motion is read by a test group
 * whose end hook the solver calls after every substep, so what is measured
 * is what the engine did inside the step, not what a reading after it implies. */
#include "test.h"
#include "alloc_fail.h"
#include "constraints/constraint_internal.h"

#include <math.h>

static const double DT = 1.0 / 60.0;

/* ---- a per-substep observer ---------------------------------------------- */

typedef struct watch {
    uint32_t i;          /* the particle's slot */
    double x, y;         /* where it was at the end of the last substep */
    double fastest;      /* the largest displacement ÷ substep dt seen, m/s */
} watch;

static double watch_relax(tt_world *w, void *self, const tt__block *b)
{
    (void)w;
    (void)self;
    (void)b;
    return 0.0;
}

static void watch_end(tt_world *w, void *self, double h)
{
    watch *o = self;
    double v = hypot(w->px[o->i] - o->x, w->py[o->i] - o->y) / h;
    if (v > o->fastest) o->fastest = v;
    o->x = w->px[o->i];
    o->y = w->py[o->i];
}

static const tt__group_ops watch_ops = {.name = "watch", .rank = TT__RANK_TEST, .relax = watch_relax, .end = watch_end};

static void watch_start(tt_world *w, watch *o, tt_particle p)
{
    o->i = p.index;
    o->x = w->px[p.index];
    o->y = w->py[p.index];
    o->fastest = 0.0;
    tt__group_add(w, &watch_ops, o);
}

/* ---- scenes ----------------------------------------------------------------- */

static tt_world *world_with(uint32_t substeps)
{
    tt_world_def d = tt_world_def_default();
    d.substeps = substeps;
    return tt_world_create(&d);
}

static tt_particle add(tt_world *w, double x, double y, bool pinned)
{
    tt_particle_def pd = tt_particle_def_default();
    pd.position = (tt_vec2){x, y};
    pd.pinned = pinned;
    return tt_particle_create(w, &pd);
}

static tt_constraint rope(tt_world *w, tt_particle a, tt_particle b, double len)
{
    tt_distance_def d = tt_distance_def_default();
    d.a = a;
    d.b = b;
    d.length = len;
    d.mode = TT_DISTANCE_MAX;
    return tt_distance_create(w, &d);
}

static double speed(const tt_world *w, tt_particle p)
{
    tt_vec2 v = {NAN, NAN};
    tt_particle_get_velocity(w, p, &v);
    return hypot(v.x, v.y);
}

/* The slowest and fastest speed read after any step. */
typedef struct range {
    double lo, hi;
} range;

static void widen(range *r, double v)
{
    if (v < r->lo) r->lo = v;
    if (v > r->hi) r->hi = v;
}

/* A particle hanging 5 m under a fixed point on a rope reeled in at 1 m/s
 * for 1 s: gravity keeps the rope taut, so the particle rises with the rope. */
static void reel_in(uint32_t substeps, range *after_step, double *fastest)
{
    tt_world *w = world_with(substeps);
    tt_particle top = add(w, 0, 0, true), bob = add(w, 0, -5, false);
    tt_constraint c = rope(w, top, bob, 5.0);
    watch o;
    watch_start(w, &o, bob);
    *after_step = (range){INFINITY, -INFINITY};
    double len = 5.0;
    for (int s = 0; s < 60; s++) {
        len -= DT * 1.0;
        tt_distance_set_length(w, c, len);
        tt_world_step(w, DT);
        widen(after_step, speed(w, bob));
    }
    *fastest = o.fastest;
    tt_world_destroy(w);
}

/* A particle held by a pin whose anchor the script drags at 1 m/s for 1 s. */
static void drag(uint32_t substeps, range *after_step, double *fastest)
{
    tt_world *w = world_with(substeps);
    tt_particle p = add(w, 0, 0, false);
    tt_pin_def pd = tt_pin_def_default();
    pd.particle = p;
    tt_constraint c = tt_pin_create(w, &pd);
    watch o;
    watch_start(w, &o, p);
    *after_step = (range){INFINITY, -INFINITY};
    for (int s = 0; s < 60; s++) {
        tt_pin_set_anchor(w, c, (tt_vec2){DT * (s + 1), 0.0});
        tt_world_step(w, DT);
        widen(after_step, speed(w, p));
    }
    *fastest = o.fastest;
    tt_world_destroy(w);
}

static const uint32_t SUBSTEPS[] = {1, 4, 8};

TEST(targets_reel_in_moves_at_the_reel_speed_in_every_substep)
{
    range r[3];
    double fastest[3];
    for (int k = 0; k < 3; k++) { /* all three first, so a failure shows every count */
        reel_in(SUBSTEPS[k], &r[k], &fastest[k]);
        printf("    reel-in, %u substeps: w:velocity %.4f…%.4f m/s, fastest substep %.4f m/s\n", SUBSTEPS[k], r[k].lo,
               r[k].hi, fastest[k]);
    }
    for (int k = 0; k < 3; k++) {
        ENSURE_NEAR(r[k].lo, 1.0, 0.02);
        ENSURE_NEAR(r[k].hi, 1.0, 0.02);
        ENSURE_NEAR(fastest[k], 1.0, 0.02);
    }
}

TEST(targets_dragged_pin_moves_at_the_drag_speed_in_every_substep)
{
    range r[3];
    double fastest[3];
    for (int k = 0; k < 3; k++) { /* all three first, so a failure shows every count */
        drag(SUBSTEPS[k], &r[k], &fastest[k]);
        printf("    drag, %u substeps: w:velocity %.4f…%.4f m/s, fastest substep %.4f m/s\n", SUBSTEPS[k], r[k].lo,
               r[k].hi, fastest[k]);
    }
    for (int k = 0; k < 3; k++) {
        ENSURE_NEAR(r[k].lo, 1.0, 0.02);
        ENSURE_NEAR(r[k].hi, 1.0, 0.02);
        ENSURE_NEAR(fastest[k], 1.0, 0.02);
    }
}

/* A particle resting on a box (friction 1) that the script moves at 1 m/s,
 * sideways (friction carries it) or up (the contact lifts it). The box
 * starts at once, so the particle first catches up (0.1 s at μ = 1); from
 * then on it must move with the box in every substep. */
static void carry(uint32_t substeps, bool up, range *after_step, double *fastest)
{
    tt_world *w = world_with(substeps);
    tt_collision_settings cs = tt_collision_settings_default();
    cs.friction_static = cs.friction_kinetic = 1.0;
    tt_world_set_collision(w, &cs);
    tt_shape_def sd = tt_shape_def_default();
    sd.type = TT_SHAPE_BOX;
    sd.half_extents = (tt_vec2){50.0, 0.5};
    sd.friction_static = sd.friction_kinetic = 1.0;
    tt_shape box = tt_shape_create(w, &sd);
    tt_particle_def pd = tt_particle_def_default();
    pd.position = (tt_vec2){0.0, 0.6};
    pd.radius = 0.1;
    tt_particle p = tt_particle_create(w, &pd);
    for (int s = 0; s < 30; s++) tt_world_step(w, DT); /* at rest on the box */
    watch o;
    *after_step = (range){INFINITY, -INFINITY};
    for (int s = 1; s <= 120; s++) {
        if (s == 31) watch_start(w, &o, p); /* caught up: from here on every substep counts */
        double d = DT * s;
        tt_shape_set_transform(w, box, up ? (tt_vec2){0.0, d} : (tt_vec2){d, 0.0}, 0.0);
        tt_world_step(w, DT);
        if (s > 30) widen(after_step, speed(w, p));
    }
    *fastest = o.fastest;
    tt_world_destroy(w);
}

TEST(targets_a_kinematic_box_carries_a_resting_particle_at_its_speed_in_every_substep)
{
    range r[2][3];
    double fastest[2][3];
    for (int up = 0; up < 2; up++)
        for (int k = 0; k < 3; k++) {
            carry(SUBSTEPS[k], up, &r[up][k], &fastest[up][k]);
            printf("    box moving %s, %u substeps: w:velocity %.4f…%.4f m/s, fastest substep %.4f m/s\n",
                   up ? "up" : "sideways", SUBSTEPS[k], r[up][k].lo, r[up][k].hi, fastest[up][k]);
        }
    for (int up = 0; up < 2; up++)
        for (int k = 0; k < 3; k++) {
            ENSURE_NEAR(r[up][k].lo, 1.0, 0.02);
            ENSURE_NEAR(r[up][k].hi, 1.0, 0.02);
            ENSURE_NEAR(fastest[up][k], 1.0, 0.02);
        }
}

/* A winch: a max rope made 2 m shorter at once, limited to 1 m/s, takes 2 s
 * (120 steps of 1/60 s, ± 1) and never moves its load faster than 1 m/s;
 * without the limit the whole 2 m would go in one step. */
static void winch(uint32_t substeps, int *steps, range *after_step, double *fastest, double *got)
{
    tt_world *w = world_with(substeps);
    tt_particle top = add(w, 0, 0, true), bob = add(w, 0, -5, false);
    tt_constraint c = rope(w, top, bob, 5.0);
    tt_constraint_set_max_rate(w, c, 1.0);
    watch o;
    watch_start(w, &o, bob);
    tt_distance_set_length(w, c, 3.0);
    tt_distance_get_length(w, c, got); /* what the script set, at once */
    *after_step = (range){INFINITY, -INFINITY};
    *steps = -1;
    for (int s = 1; s <= 180; s++) {
        tt_world_step(w, DT);
        widen(after_step, speed(w, bob));
        tt_vec2 p = {NAN, NAN};
        tt_particle_get_position(w, bob, &p);
        if (*steps < 0 && hypot(p.x, p.y) <= 3.0 + 1e-9) *steps = s;
    }
    *fastest = o.fastest;
    tt_world_destroy(w);
}

TEST(targets_winch_reels_at_max_rate_over_as_many_steps_as_it_takes)
{
    int steps[3];
    range r[3];
    double fastest[3], got[3];
    for (int k = 0; k < 3; k++) {
        winch(SUBSTEPS[k], &steps[k], &r[k], &fastest[k], &got[k]);
        printf("    winch, %u substeps: there after %d steps, w:velocity up to %.4f m/s, fastest substep %.4f m/s\n",
               SUBSTEPS[k], steps[k], r[k].hi, fastest[k]);
    }
    for (int k = 0; k < 3; k++) {
        ENSURE(got[k] == 3.0);
        ENSURE(steps[k] >= 119 && steps[k] <= 121);
        ENSURE(r[k].hi <= 1.02);
        ENSURE(fastest[k] <= 1.02);
    }
}

TEST(targets_getters_return_what_the_script_set)
{
    tt_world *w = world_with(4);
    tt_particle top = add(w, 0, 0, true), bob = add(w, 0, -5, false);
    tt_constraint c = rope(w, top, bob, 5.0);
    tt_pin_def pd = tt_pin_def_default();
    pd.particle = bob;
    pd.max_rate = 0.5;
    tt_constraint pin = tt_pin_create(w, &pd);
    double rate = -1, len = -1;
    ENSURE_OK(tt_constraint_get_max_rate(w, pin, &rate));
    ENSURE(rate == 0.5);
    ENSURE_OK(tt_constraint_get_max_rate(w, c, &rate));
    ENSURE(rate == 0.0);
    ENSURE_OK(tt_pin_set_anchor(w, pin, (tt_vec2){3, -5}));
    tt_vec2 a = {0, 0};
    ENSURE_OK(tt_pin_get_anchor(w, pin, &a));
    ENSURE(a.x == 3 && a.y == -5);
    ENSURE_OK(tt_world_step(w, DT)); /* under way: still the anchor set */
    ENSURE_OK(tt_pin_get_anchor(w, pin, &a));
    ENSURE(a.x == 3 && a.y == -5);
    ENSURE_OK(tt_distance_set_length(w, c, 4.25));
    ENSURE_OK(tt_distance_get_length(w, c, &len));
    ENSURE(len == 4.25);
    ENSURE(tt_constraint_set_max_rate(w, c, -1.0) == TT_EINVAL);
    ENSURE(tt_constraint_set_max_rate(w, c, NAN) == TT_EINVAL);
    tt_bounds_def bd = tt_bounds_def_default();
    tt_constraint box = tt_bounds_create(w, &bd);
    ENSURE(tt_constraint_set_max_rate(w, box, 1.0) == TT_EINVAL);
    tt_world_destroy(w);
}

/* The exact new value in the last substep, not the sum of the fractions:
 * a rod set to 1/3 m is 1/3 m (to rounding of the projection) after one step
 * at 7 substeps, and its target is no longer moving (stepping on changes nothing). */
TEST(targets_arrive_exactly_and_stop_moving)
{
    tt_world *w = world_with(7);
    tt_world_set_gravity(w, (tt_vec2){0, 0});
    tt_particle a = add(w, 0, 0, true), b = add(w, 1, 0, false);
    tt_distance_def d = tt_distance_def_default();
    d.a = a;
    d.b = b;
    tt_constraint c = tt_distance_create(w, &d);
    ENSURE_OK(tt_distance_set_length(w, c, 1.0 / 3.0));
    ENSURE_OK(tt_world_step(w, DT));
    const tt__cgroup *g = tt__cgroup_peek(w);
    ENSURE(g->nmoving == 0);
    ENSURE(g->dist[0].lo == 1.0 / 3.0 && g->dist[0].hi == 1.0 / 3.0);
    tt_vec2 p = {0, 0};
    tt_particle_get_position(w, b, &p);
    ENSURE_NEAR(p.x, 1.0 / 3.0, 1e-12);
    tt_world_destroy(w);
}

/* A constraint removed, or broken, while its target moves leaves no trace
 * in the moving list (ASan would see a stale entry written). */
TEST(targets_removed_while_moving)
{
    tt_world *w = world_with(4);
    tt_particle top = add(w, 0, 0, true), b1 = add(w, 0, -5, false), b2 = add(w, 1, -5, false);
    tt_constraint r1 = rope(w, top, b1, 5.0), r2 = rope(w, top, b2, hypot(1, 5));
    tt_pin_def pd = tt_pin_def_default();
    pd.particle = b2;
    pd.max_rate = 1.0;
    tt_constraint pin = tt_pin_create(w, &pd);
    ENSURE_OK(tt_constraint_set_max_rate(w, r1, 1.0));
    ENSURE_OK(tt_distance_set_length(w, r1, 1.0));
    ENSURE_OK(tt_distance_set_length(w, r2, 2.0));
    ENSURE_OK(tt_pin_set_anchor(w, pin, (tt_vec2){5, -5}));
    ENSURE_OK(tt_world_step(w, DT));
    ENSURE(tt__cgroup_peek(w)->nmoving == 2); /* r2 arrived; r1 and the pin are on their way */
    ENSURE_OK(tt_constraint_destroy(w, r1));
    ENSURE(tt__cgroup_peek(w)->nmoving == 1);
    ENSURE_OK(tt_particle_destroy(w, b2));
    ENSURE(tt__cgroup_peek(w)->nmoving == 0);
    ENSURE_OK(tt_world_step(w, DT));
    tt_world_destroy(w);
}

/* Moving a target needs room in the moving list: without memory the setter
 * says so and nothing changes, neither the target set nor the one the solver uses. */
TEST(targets_move_without_memory_changes_nothing)
{
    tt_world *w = world_with(4);
    tt_particle top = add(w, 0, 0, true), bob = add(w, 0, -5, false);
    tt_constraint c = rope(w, top, bob, 5.0);
    tt_pin_def pd = tt_pin_def_default();
    pd.particle = bob;
    tt_constraint pin = tt_pin_create(w, &pd);
    tt_test_alloc_fail_from(0);
    tt_result r1 = tt_distance_set_length(w, c, 4.0);
    tt_result r2 = tt_pin_set_anchor(w, pin, (tt_vec2){1, -5});
    ENSURE(tt_test_alloc_ok());
    ENSURE(r1 == TT_ENOMEM && r2 == TT_ENOMEM);
    double len = 0;
    tt_vec2 a = {1, 1};
    ENSURE_OK(tt_distance_get_length(w, c, &len));
    ENSURE_OK(tt_pin_get_anchor(w, pin, &a));
    ENSURE(len == 5.0 && a.x == 0.0 && a.y == -5.0);
    ENSURE(tt__cgroup_peek(w)->nmoving == 0);
    tt_world_destroy(w);
}
