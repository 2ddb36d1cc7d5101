/* tether — substeps by speed (src/core/travel.c, tt_world_def.max_travel):
 * the count a step runs follows its fastest particle; a varying count keeps
 * free flight exact (time-corrected Verlet); a fast column lands without
 * sinking into itself where a fixed substep lets it; off, it leaves no
 * trace in the state; it is state when on (saved, loaded, refused when bad). */
#include "test.h"

#include <tether.h>

#include <math.h>
#include <stdlib.h>
#include <string.h>

static tt_world *world(tt_vec2 g, double travel, uint32_t most)
{
    tt_world_def wd = tt_world_def_default();
    wd.gravity = g;
    wd.sleep = false;
    wd.max_travel = travel;
    wd.max_substeps = most;
    tt_world *w = tt_world_create(&wd);
    tt_collision_settings cs = tt_collision_settings_default(); /* it acts where contacts can be found */
    if (w) tt_world_set_collision(w, &cs);
    return w;
}

static tt_particle ball(tt_world *w, tt_vec2 at, tt_vec2 v, double r)
{
    tt_particle_def pd = tt_particle_def_default();
    pd.position = at;
    pd.velocity = v;
    pd.radius = r;
    return tt_particle_create(w, &pd);
}

/* Something that stands still, far off: the speeds count against it. */
static void post(tt_world *w)
{
    tt_particle_def pd = tt_particle_def_default();
    pd.position = (tt_vec2){-1000, 0};
    pd.radius = 0.5;
    pd.pinned = true;
    tt_particle_create(w, &pd);
}

static uint32_t last_substeps(const tt_world *w)
{
    tt_stats st;
    tt_world_get_stats(w, &st);
    return st.substeps;
}

TEST(travel_count_follows_the_fastest_particle)
{
    /* 59 m/s for 1/60 s: 0.983 m, 1.97 radii of 0.5; at 0.5 radii a substep, 4 */
    tt_world *w = world((tt_vec2){0, 0}, 0.5, 8);
    ENSURE(w);
    ENSURE(last_substeps(w) == 0); /* no step yet */
    ball(w, (tt_vec2){0, 0}, (tt_vec2){1, 0}, 0.5);
    tt_particle fast = ball(w, (tt_vec2){10, 0}, (tt_vec2){0, 59}, 0.5);
    ENSURE_OK(tt_world_step(w, 1.0 / 60));
    ENSURE(last_substeps(w) == 4);
    ENSURE_OK(tt_world_set_travel(w, 0.5, 3)); /* capped */
    ENSURE_OK(tt_world_step(w, 1.0 / 60));
    ENSURE(last_substeps(w) == 3);
    ENSURE_OK(tt_world_set_travel(w, 0.5, 8));
    ENSURE_OK(tt_world_set_substeps(w, 6)); /* never fewer than the setting */
    ENSURE_OK(tt_world_step(w, 1.0 / 60));
    ENSURE(last_substeps(w) == 6);
    ENSURE_OK(tt_world_set_substeps(w, 1));
    ENSURE_OK(tt_particle_set_pinned(w, fast, true)); /* what cannot move asks for nothing */
    ENSURE_OK(tt_world_step(w, 1.0 / 60));
    ENSURE(last_substeps(w) == 1);
    ENSURE_OK(tt_particle_set_pinned(w, fast, false));
    ENSURE_OK(tt_particle_set_velocity(w, fast, (tt_vec2){0, 59}));
    ENSURE_OK(tt_particle_set_radius(w, fast, 0.0)); /* a point has no radius to measure by */
    ENSURE_OK(tt_world_step(w, 1.0 / 60));
    ENSURE(last_substeps(w) == 1);
    ENSURE_OK(tt_particle_set_radius(w, fast, 0.25)); /* 3.93 radii of 0.25 … */
    ENSURE_OK(tt_world_step(w, 1.0 / 60));
    ENSURE(last_substeps(w) == 8); /* … want 8 */
    ENSURE_OK(tt_world_set_travel(w, 0.0, 8)); /* off */
    ENSURE_OK(tt_world_step(w, 1.0 / 60));
    ENSURE(last_substeps(w) == 1);
    tt_world_destroy(w);
}

/* Time-corrected Verlet is exact for a constant acceleration whatever the
 * step, so a throw whose count goes 4 … 1 … 4 follows the parabola. */
TEST(travel_keeps_free_flight_on_its_parabola)
{
    const double g = -9.81, v0 = 100.0, dt = 1.0 / 60;
    tt_world *w = world((tt_vec2){0, g}, 0.5, 8);
    ENSURE(w);
    tt_particle p = ball(w, (tt_vec2){0, 0}, (tt_vec2){3, v0}, 0.5);
    post(w);
    uint32_t seen_lo = 100, seen_hi = 0;
    double worst = 0;
    for (int s = 1; s <= 1200; s++) {
        ENSURE_OK(tt_world_step(w, dt));
        const uint32_t n = last_substeps(w);
        seen_lo = n < seen_lo ? n : seen_lo;
        seen_hi = n > seen_hi ? n : seen_hi;
        tt_vec2 x;
        tt_particle_get_position(w, p, &x);
        const double t = s * dt;
        worst = fmax(worst, fmax(fabs(x.x - 3 * t), fabs(x.y - (v0 * t + 0.5 * g * t * t))));
    }
    ENSURE(seen_lo == 1 && seen_hi == 7); /* 100 m/s: 1.67 m a step, 3.3 radii; at the top, under 0.5 */
    ENSURE(worst < 1e-7); /* measured 3.6e-8 on a 510 m arc: the rounding of x − x_old (4 fixed substeps: 1.3e-7) */
    tt_world_destroy(w);
}

/* 40 circles in a column 1.1 m wide, falling together at 80 m/s (1.3 m a
 * step, 2.7 radii) onto the floor: at one substep the layers above run into
 * the stopped ones before the sweeps can hold them; with max_travel they land
 * in short substeps, paid for only while they are fast. */
static double column_landing(double travel, double *mean_substeps, uint32_t *at_rest_substeps)
{
    tt_world *w = world((tt_vec2){0, -9.81}, travel, 8);
    tt_world_set_iterations(w, 8);
    tt_collision_settings cs = tt_collision_settings_default();
    tt_world_set_collision(w, &cs);
    tt_shape_def sd = tt_shape_def_default();
    sd.type = TT_SHAPE_AABB;
    const tt_vec2 box[3][2] = {{{-5, -1}, {5, 0}}, {{-1.6, 0}, {-0.55, 200}}, {{0.55, 0}, {1.6, 200}}};
    for (int k = 0; k < 3; k++) {
        sd.a = box[k][0];
        sd.b = box[k][1];
        tt_shape_create(w, &sd);
    }
    enum { N = 40 };
    tt_particle ps[N];
    for (int i = 0; i < N; i++) ps[i] = ball(w, (tt_vec2){0, 5.5 + i}, (tt_vec2){0, -80}, 0.5);
    double worst = 0, subs = 0;
    for (int s = 0; s < 600; s++) {
        tt_world_step(w, 1.0 / 60);
        subs += last_substeps(w);
        tt_vec2 a, b;
        tt_particle_get_position(w, ps[0], &a);
        worst = fmax(worst, 0.5 - a.y);
        for (int i = 0; i + 1 < N; i++) {
            tt_particle_get_position(w, ps[i], &a);
            tt_particle_get_position(w, ps[i + 1], &b);
            worst = fmax(worst, 1.0 - hypot(b.x - a.x, b.y - a.y));
        }
    }
    *mean_substeps = subs / 600;
    *at_rest_substeps = last_substeps(w);
    tt_world_destroy(w);
    return worst / 0.5; /* of a radius */
}

TEST(travel_lands_a_fast_column_without_sinking_it)
{
    double mean1, mean2;
    uint32_t rest1, rest2;
    const double fixed = column_landing(0.0, &mean1, &rest1), by_speed = column_landing(0.5, &mean2, &rest2);
    ENSURE(fixed > 0.3);     /* measured 50 % of a radius */
    ENSURE(by_speed < 0.15); /* measured 7.3 % */
    ENSURE(mean1 == 1.0 && rest1 == 1);
    ENSURE(mean2 < 1.1 && rest2 == 1); /* measured 1.03: more substeps only in the landing */
}

TEST(travel_off_leaves_no_trace_in_the_state)
{
    tt_world *a = world((tt_vec2){0, -9.81}, 0.0, 8), *b = world((tt_vec2){0, -9.81}, 0.0, 8);
    ENSURE(a && b);
    double travel = -1;
    uint32_t most = 0;
    travel = tt_world_get_travel(a, &most);
    ENSURE(travel == 0.0 && most == 8);
    ball(a, (tt_vec2){0, 0}, (tt_vec2){0, 59}, 0.5);
    ball(b, (tt_vec2){0, 0}, (tt_vec2){0, 59}, 0.5);
    ENSURE_OK(tt_world_set_travel(b, 0.5, 5));
    ENSURE(tt_world_hash(a) != tt_world_hash(b)); /* on, it is state */
    ENSURE_OK(tt_world_set_travel(b, 0.0, 5)); /* off, but a cap of its own: a setting, kept */
    ENSURE(tt_world_hash(a) != tt_world_hash(b));
    ENSURE_OK(tt_world_set_travel(b, 0.0, 8));
    ENSURE(tt_world_hash(a) == tt_world_hash(b));
    tt_world_step(a, 1.0 / 60);
    tt_world_step(b, 1.0 / 60);
    ENSURE(tt_world_hash(a) == tt_world_hash(b));
    tt_world_destroy(a);
    tt_world_destroy(b);
}

static tt_world *reloaded(const tt_world *w)
{
    size_t size = 0;
    tt_world_save(w, NULL, 0, &size);
    void *buf = malloc(size);
    tt_world *copy = buf && tt_world_save(w, buf, size, &size) == TT_OK ? tt_world_load(buf, size) : NULL;
    free(buf);
    return copy;
}

/* The copy equals the world, in its settings, the last step's count and
 * hash, and steps on alike. */
static void same_after_reload(tt_world *w)
{
    tt_world *c = reloaded(w);
    ENSURE(c);
    uint32_t m1 = 0, m2 = 0;
    ENSURE(tt_world_get_travel(c, &m2) == tt_world_get_travel(w, &m1) && m1 == m2);
    ENSURE(last_substeps(c) == last_substeps(w));
    ENSURE(tt_world_hash(c) == tt_world_hash(w));
    for (int s = 0; s < 30; s++) {
        tt_world_step(w, 1.0 / 60);
        tt_world_step(c, 1.0 / 60);
    }
    ENSURE(tt_world_hash(c) == tt_world_hash(w));
    tt_world_destroy(c);
}

TEST(travel_is_saved_and_loaded_with_the_last_count)
{
    tt_world *w = world((tt_vec2){0, -9.81}, 0.5, 6);
    ENSURE(w);
    ball(w, (tt_vec2){0, 0}, (tt_vec2){0, 100}, 0.5);
    post(w);
    for (int s = 0; s < 3; s++) tt_world_step(w, 1.0 / 60);
    ENSURE(last_substeps(w) == 6);
    same_after_reload(w);
    /* off after a step that ran more than the setting: the count is kept */
    tt_world_step(w, 1.0 / 60);
    ENSURE_OK(tt_world_set_travel(w, 0.0, 6));
    ENSURE(last_substeps(w) == 6);
    same_after_reload(w);
    ENSURE(last_substeps(w) == 1);
    same_after_reload(w); /* off, the cap 6 kept */
    tt_world_destroy(w);
}

TEST(travel_refuses_bad_values_and_leaves_the_world_as_it_was)
{
    tt_world *w = world((tt_vec2){0, -9.81}, 0.25, 4);
    ENSURE(w);
    const uint64_t h = tt_world_hash(w);
    const double bad_travel[] = {-1.0, -1e-300, NAN, INFINITY, 2e12};
    for (size_t k = 0; k < sizeof bad_travel / sizeof *bad_travel; k++)
        ENSURE(tt_world_set_travel(w, bad_travel[k], 4) == TT_EINVAL);
    ENSURE(tt_world_set_travel(w, 0.5, 0) == TT_EINVAL);
    ENSURE(tt_world_set_travel(w, 0.5, TT_MAX_SUBSTEPS + 1) == TT_EINVAL);
    ENSURE(tt_world_set_travel(NULL, 0.5, 4) != TT_OK);
    ENSURE(tt_world_hash(w) == h);
    uint32_t most = 0;
    ENSURE(tt_world_get_travel(w, &most) == 0.25 && most == 4);
    ENSURE(tt_world_get_travel(NULL, NULL) == 0.0);
    tt_world_def wd = tt_world_def_default();
    wd.max_travel = NAN;
    ENSURE(!tt_world_create(&wd));
    wd.max_travel = 0.5;
    wd.max_substeps = TT_MAX_SUBSTEPS + 1;
    ENSURE(!tt_world_create(&wd));
    wd.max_substeps = 0; /* a def zeroed by hand: the default cap */
    tt_world *z = tt_world_create(&wd);
    ENSURE(z && tt_world_get_travel(z, &most) == 0.5 && most == 8);
    tt_world_destroy(z);
    /* a step backwards would start from other speeds, so another count: it acts only where contacts
     * can be found, which reverse refuses */
    ENSURE(tt_world_reverse(w) == TT_ESTATE);
    tt_world_destroy(w);
}

/* Substeps by speed is for contacts: where none can be found (no particle
 * contacts, shapes or terrain), a step runs the set substeps however fast
 * its particles, and such a world runs backwards. */
TEST(travel_leaves_a_world_without_contacts_at_its_substeps)
{
    tt_world_def wd = tt_world_def_default();
    wd.max_travel = 0.5;
    wd.integrator = TT_VERLET;
    tt_world *w = tt_world_create(&wd);
    ENSURE(w);
    ball(w, (tt_vec2){0, 0}, (tt_vec2){0, 59}, 0.5); /* 1.97 radii a step */
    post(w);
    ENSURE_OK(tt_world_step(w, 1.0 / 60));
    ENSURE(last_substeps(w) == 1);
    ENSURE_OK(tt_world_reverse(w));
    tt_collision_settings cs = tt_collision_settings_default();
    ENSURE_OK(tt_world_set_collision(w, &cs));
    ENSURE_OK(tt_world_step(w, 1.0 / 60));
    ENSURE(last_substeps(w) == 4); /* against the post */
    ENSURE(tt_world_reverse(w) == TT_ESTATE);
    cs.particles = false; /* shapes and terrain only */
    ENSURE_OK(tt_world_set_collision(w, &cs));
    ENSURE_OK(tt_world_step(w, 1.0 / 60));
    ENSURE(last_substeps(w) == 1);
    tt_world_destroy(w);
}

/* The speed that counts is relative to what a particle can meet: the other
 * particles (with particle contacts on), what stands still (pinned or
 * sleeping particles), and shapes and terrain within the step's reach. A
 * scene falling as one with nothing near pays nothing. */
TEST(travel_counts_motion_relative_to_what_can_be_met)
{
    tt_world *w = world((tt_vec2){0, -9.81}, 0.5, 8);
    ENSURE(w);
    tt_particle a = ball(w, (tt_vec2){0, 0}, (tt_vec2){0, 59}, 0.5), b = ball(w, (tt_vec2){5, 0}, (tt_vec2){0, 59}, 0.5);
    ENSURE_OK(tt_world_step(w, 1.0 / 60));
    ENSURE(last_substeps(w) == 1); /* flying as one */
    ENSURE_OK(tt_particle_set_velocity(w, a, (tt_vec2){0, 0}));
    ENSURE_OK(tt_world_step(w, 1.0 / 60));
    ENSURE(last_substeps(w) == 4); /* 59 m/s apart */
    ENSURE_OK(tt_particle_set_pinned(w, a, true)); /* what stands still counts, however far */
    ENSURE_OK(tt_particle_set_position(w, a, (tt_vec2){1e6, 0}, TT_MOVE_RESET_VELOCITY));
    ENSURE_OK(tt_world_step(w, 1.0 / 60));
    ENSURE(last_substeps(w) == 4);
    ENSURE_OK(tt_particle_set_radius(w, a, 0.0)); /* but not a point */
    ENSURE_OK(tt_world_step(w, 1.0 / 60));
    ENSURE(last_substeps(w) == 1);
    /* shapes: only within the step's reach (the ball's box grown by its radius and travel) */
    tt_shape_def sd = tt_shape_def_default();
    sd.a = (tt_vec2){1e6, -50};
    sd.b = (tt_vec2){1e6, 50};
    tt_shape far = tt_shape_create(w, &sd);
    ENSURE_OK(tt_world_step(w, 1.0 / 60));
    ENSURE(last_substeps(w) == 1);
    ENSURE_OK(tt_shape_destroy(w, far));
    sd.a = (tt_vec2){6, -1e3}; /* a wall 1 m beside the flying ball */
    sd.b = (tt_vec2){6, 1e3};
    tt_shape near = tt_shape_create(w, &sd);
    ENSURE_OK(tt_world_step(w, 1.0 / 60));
    ENSURE(last_substeps(w) >= 3);
    ENSURE_OK(tt_shape_destroy(w, near));
    ENSURE_OK(tt_world_step(w, 1.0 / 60));
    ENSURE(last_substeps(w) == 1);
    /* terrain likewise */
    tt_mask *m = tt_mask_create(8, 8, true);
    tt_terrain_def td = tt_terrain_def_default();
    td.solid = m;
    td.origin = (tt_vec2){1e5, 0};
    tt_terrain t = tt_terrain_create(w, &td);
    ENSURE_OK(tt_world_step(w, 1.0 / 60));
    ENSURE(last_substeps(w) == 1);
    ENSURE_OK(tt_terrain_destroy(w, t));
    tt_vec2 x;
    ENSURE_OK(tt_particle_get_position(w, b, &x));
    td.origin = (tt_vec2){5.8, x.y}; /* 0.3 m beside it */
    ENSURE(tt_terrain_create(w, &td).gen != 0);
    ENSURE_OK(tt_world_step(w, 1.0 / 60));
    ENSURE(last_substeps(w) >= 3);
    tt_mask_destroy(m);
    tt_world_destroy(w);
}

/* dt at both ends of its range, a speck of a radius, a tiny max_travel: the
 * count stays within [substeps, max_substeps] and nothing turns NaN. */
TEST(travel_at_the_extremes_stays_within_its_bounds)
{
    tt_world *w = world((tt_vec2){0, -9.81}, 0.5, 8);
    ENSURE(w);
    tt_particle p = ball(w, (tt_vec2){0, 0}, (tt_vec2){0, 0}, 0.5);
    ENSURE_OK(tt_world_step(w, TT_MAX_DT)); /* a fall of 490 m in a step: 981 radii */
    ENSURE(last_substeps(w) == 8);
    ENSURE_OK(tt_world_step(w, TT_MIN_DT));
    ENSURE(last_substeps(w) == 1); /* falling at 98 m/s, but 1e-7 m a step */
    ENSURE_OK(tt_particle_set_radius(w, p, 1e-9));
    ENSURE_OK(tt_world_set_travel(w, 1e-300, 1000)); /* the travel in radii overflows to +inf */
    ENSURE_OK(tt_world_step(w, 1.0 / 60));
    ENSURE(last_substeps(w) == 1000);
    tt_vec2 x, v;
    ENSURE_OK(tt_particle_get_position(w, p, &x));
    ENSURE_OK(tt_particle_get_velocity(w, p, &v));
    ENSURE(isfinite(x.x) && isfinite(x.y) && isfinite(v.x) && isfinite(v.y));
    tt_world_destroy(w);
}
