/* Sleeping: a pile at rest falls asleep and stays where it was; each thing
 * that can disturb it wakes it; the sleep state survives a snapshot. */
#include "tether.h"
#include "../test.h"

#include <stdlib.h>

#define R 0.1

/* Collisions on and a ground box from x = -half to half, its top at y = 0. */
static void floor_box(tt_world *w, double half)
{
    tt_collision_settings cs = tt_collision_settings_default();
    ENSURE_OK(tt_world_set_collision(w, &cs));
    tt_shape_def g = tt_shape_def_default();
    g.type = TT_SHAPE_AABB;
    g.a = (tt_vec2){-half, -1.0}, g.b = (tt_vec2){half, 0.0};
    ENSURE(tt_shape_is_valid(w, tt_shape_create(w, &g)));
}

/* A small pile: rows of touching particles (so one island, whatever gaps the
 * settling leaves) dropped into a box of three walls. */
static tt_world *pile(bool sleep, tt_particle *ids, uint32_t n)
{
    tt_world_def d = tt_world_def_default();
    d.sleep = sleep;
    tt_world *w = tt_world_create(&d);
    if (!w) return NULL;
    tt_collision_settings cs = tt_collision_settings_default();
    if (tt_world_set_collision(w, &cs) != TT_OK) return NULL;
    tt_shape_def g = tt_shape_def_default();
    g.type = TT_SHAPE_AABB;
    g.a = (tt_vec2){-2.0, -1.0}, g.b = (tt_vec2){2.0, 0.0};
    tt_shape_create(w, &g);
    g.a = (tt_vec2){-2.0, 0.0}, g.b = (tt_vec2){-1.0, 3.0};
    tt_shape_create(w, &g);
    g.a = (tt_vec2){1.0, 0.0}, g.b = (tt_vec2){2.0, 3.0};
    tt_shape_create(w, &g);
    for (uint32_t k = 0; k < n; k++) {
        tt_particle_def p = tt_particle_def_default();
        p.position = (tt_vec2){-0.85 + (k % 8) * 2.0 * R + (k / 8 % 2) * 0.05, R + 0.02 + (k / 8) * 2.2 * R};
        p.radius = R;
        ids[k] = tt_particle_create(w, &p);
    }
    return w;
}

static uint32_t sleeping(const tt_world *w)
{
    tt_stats st;
    tt_world_get_stats(w, &st);
    return st.sleeping;
}

static double top(const tt_world *w, const tt_particle *ids, uint32_t n)
{
    double y = -INFINITY;
    for (uint32_t k = 0; k < n; k++) {
        tt_vec2 p;
        tt_particle_get_position(w, ids[k], &p);
        y = fmax(y, p.y);
    }
    return y;
}

/* Steps until everything sleeps (at most max steps); the steps taken. */
static int settle(tt_world *w, uint32_t n, int max)
{
    for (int s = 0; s < max; s++) {
        if (sleeping(w) == n) return s;
        tt_world_step(w, 1.0 / 60.0);
    }
    return max;
}

enum { N = 48 };

TEST(sleep_pile_falls_asleep_where_the_awake_pile_rests)
{
    tt_particle a[N], b[N];
    tt_world *on = pile(true, a, N), *off = pile(false, b, N);
    ENSURE(on && off);
    ENSURE(settle(on, N, 1200) < 1200);
    for (int s = 0; s < 1200; s++) tt_world_step(off, 1.0 / 60.0);
    ENSURE(sleeping(off) == 0);
    /* the sleeping pile's height is the awake pile's, to a small part of a radius */
    ENSURE_NEAR(top(on, a, N), top(off, b, N), 0.5 * R);
    bool asleep;
    ENSURE_OK(tt_particle_get_asleep(on, a[0], &asleep));
    ENSURE(asleep);
    /* asleep, nothing moves: a step changes no position */
    tt_vec2 p0, p1;
    tt_particle_get_position(on, a[N - 1], &p0);
    for (int s = 0; s < 60; s++) tt_world_step(on, 1.0 / 60.0);
    tt_particle_get_position(on, a[N - 1], &p1);
    ENSURE(p0.x == p1.x && p0.y == p1.y);
    ENSURE(sleeping(on) == N);
    /* energy still counts sleepers: gravity's share is where they lie */
    tt_energy e;
    ENSURE_OK(tt_world_get_energy(on, &e));
    ENSURE(e.gravity > 0.0 && e.kinetic == 0.0);
    tt_world_destroy(on);
    tt_world_destroy(off);
}

TEST(sleep_on_by_default_and_turned_off_wakes_all)
{
    tt_world_def d = tt_world_def_default();
    ENSURE(d.sleep && d.sleep_speed == 0.01 && d.sleep_time == 1.0);
    tt_world *w0 = tt_world_create(&d);
    ENSURE(tt_world_get_sleep(w0, NULL, NULL));
    tt_world_destroy(w0);
    tt_particle a[N];
    tt_world *w = pile(false, a, N);
    ENSURE(w);
    double sp, tm;
    ENSURE(!tt_world_get_sleep(w, &sp, &tm));
    ENSURE_OK(tt_world_set_sleep(w, true, 0.05, 0.5));
    ENSURE(tt_world_get_sleep(w, &sp, &tm) && sp == 0.05 && tm == 0.5);
    ENSURE(settle(w, N, 1200) < 1200);
    ENSURE(tt_world_set_sleep(w, true, -1.0, 0.5) == TT_EINVAL);
    ENSURE(tt_world_set_sleep(w, true, 0.05, NAN) == TT_EINVAL);
    ENSURE(sleeping(w) == N); /* a refused call changed nothing */
    ENSURE_OK(tt_world_set_sleep(w, false, 0, 0));
    ENSURE(sleeping(w) == 0 && !tt_world_get_sleep(w, NULL, NULL));
    tt_world_destroy(w);
}

/* A ball dropped on the sleeping pile wakes it; the pile settles again to
 * its height (it was at rest: the ball adds a little on top). */
TEST(sleep_ball_wakes_what_it_hits)
{
    tt_particle a[N + 1];
    tt_world *w = pile(true, a, N);
    ENSURE(w);
    ENSURE(settle(w, N, 1200) < 1200);
    double h0 = top(w, a, N);
    tt_particle_def p = tt_particle_def_default();
    p.position = (tt_vec2){0.0, h0 + 1.0};
    p.radius = R;
    a[N] = tt_particle_create(w, &p);
    int s = 0;
    while (sleeping(w) == N && s < 120) tt_world_step(w, 1.0 / 60.0), s++;
    ENSURE(s < 120 && s > 10); /* woken when the ball arrived, not before */
    ENSURE(settle(w, N + 1, 2400) < 2400);
    ENSURE_NEAR(top(w, a, N), h0, 0.5 * R);
    tt_world_destroy(w);
}

/* Each script call on a sleeper wakes its island. */
TEST(sleep_script_calls_wake)
{
    tt_particle a[N];
    for (int trigger = 0; trigger < 9; trigger++) {
        tt_world *w = pile(true, a, N);
        ENSURE(w);
        ENSURE(settle(w, N, 1200) < 1200);
        tt_particle q = a[N / 2];
        switch (trigger) {
        case 0: ENSURE_OK(tt_particle_set_velocity(w, q, (tt_vec2){0, 1})); break;
        case 1: ENSURE_OK(tt_particle_apply_impulse(w, q, (tt_vec2){0, 0.1})); break;
        case 2: ENSURE_OK(tt_particle_apply_force(w, q, (tt_vec2){0, 10})); break;
        case 3: ENSURE_OK(tt_particle_set_position(w, q, (tt_vec2){0, 2.5}, TT_MOVE_RESET_VELOCITY)); break;
        case 4: ENSURE_OK(tt_particle_destroy(w, q)); break;
        case 5: ENSURE_OK(tt_particle_set_radius(w, q, 0.5 * R)); break;
        case 6: ENSURE_OK(tt_world_explode(w, (tt_vec2){0, 0.3}, 0.5, 0.1)); break;
        case 7: ENSURE_OK(tt_particle_set_mass(w, q, 2.0)); break;
        case 8: ENSURE_OK(tt_particle_set_pinned(w, a[0], true)); break;
        }
        ENSURE(sleeping(w) == 0);
        /* and a refused call wakes nothing: the world is as it was */
        tt_world_destroy(w);
    }
    tt_world *w = pile(true, a, N);
    ENSURE(settle(w, N, 1200) < 1200);
    uint64_t h = tt_world_hash(w);
    ENSURE(tt_particle_set_velocity(w, a[3], (tt_vec2){NAN, 0}) == TT_EINVAL);
    ENSURE(tt_particle_set_mass(w, a[3], -1.0) == TT_EINVAL);
    ENSURE(sleeping(w) == N && tt_world_hash(w) == h);
    tt_world_destroy(w);
}

/* Woken by velocity, the pile moves at once, and it starts from rest where it slept: no jump. */
TEST(sleep_wake_starts_from_rest)
{
    tt_particle a[N];
    tt_world *w = pile(true, a, N);
    ENSURE(settle(w, N, 1200) < 1200);
    tt_vec2 p0[N];
    for (int k = 0; k < N; k++) tt_particle_get_position(w, a[k], &p0[k]);
    ENSURE_OK(tt_particle_set_velocity(w, a[N - 1], (tt_vec2){0, 0}));
    tt_world_step(w, 1.0 / 60.0);
    for (int k = 0; k < N; k++) {
        tt_vec2 p;
        tt_particle_get_position(w, a[k], &p);
        ENSURE(hypot(p.x - p0[k].x, p.y - p0[k].y) < 0.05 * R);
    }
    tt_world_destroy(w);
}

/* A shape the script moves into the pile wakes it before it arrives; a box
 * woken by tt__sleep_wake_aabb's public road (an explosion of impulse 0)
 * wakes what is inside only. */
TEST(sleep_moved_shape_wakes)
{
    tt_particle a[N];
    tt_world *w = pile(true, a, N);
    ENSURE(settle(w, N, 1200) < 1200);
    tt_shape_def g = tt_shape_def_default();
    g.type = TT_SHAPE_CIRCLE;
    g.radius = 0.2;
    g.position = (tt_vec2){0.0, 3.0};
    tt_shape s = tt_shape_create(w, &g);
    tt_world_step(w, 1.0 / 60.0);
    ENSURE(sleeping(w) == N); /* far away: nothing woke */
    for (int k = 0; k < 60 && sleeping(w) == N; k++) {
        ENSURE_OK(tt_shape_set_transform(w, s, (tt_vec2){0.0, 3.0 - 0.05 * (k + 1)}, 0.0));
        tt_world_step(w, 1.0 / 60.0);
    }
    ENSURE(sleeping(w) == 0);
    tt_world_destroy(w);
}

/* Two piles apart are two islands: a touch wakes one, the other sleeps on. */
TEST(sleep_islands_wake_apart)
{
    tt_world_def d = tt_world_def_default();
    d.sleep = true;
    tt_world *w = tt_world_create(&d);
    floor_box(w, 5.0);
    tt_particle l[3], r[3];
    for (int k = 0; k < 3; k++) {
        tt_particle_def p = tt_particle_def_default();
        p.radius = R;
        p.position = (tt_vec2){-2.0, R + 2 * R * k};
        l[k] = tt_particle_create(w, &p);
        p.position = (tt_vec2){2.0, R + 2 * R * k};
        r[k] = tt_particle_create(w, &p);
    }
    ENSURE(settle(w, 6, 600) < 600);
    ENSURE_OK(tt_particle_apply_impulse(w, l[2], (tt_vec2){0.0, 0.0}));
    bool s0, s1;
    tt_particle_get_asleep(w, l[0], &s0);
    tt_particle_get_asleep(w, r[0], &s1);
    ENSURE(!s0 && s1);
    ENSURE(sleeping(w) == 3);
    tt_world_destroy(w);
}

/* The sleep state is world state: saved, restored and hashed; a restored
 * world goes on exactly as the original (it wakes alike). */
TEST(sleep_snapshot_round_trip)
{
    tt_particle a[N];
    tt_world *w = pile(true, a, N);
    ENSURE(w);
    for (int s = 0; s < 40; s++) tt_world_step(w, 1.0 / 60.0); /* some at rest, none asleep yet */
    size_t size;
    ENSURE(tt_world_save(w, NULL, 0, &size) == TT_ENOMEM);
    void *buf = malloc(size);
    ENSURE_OK(tt_world_save(w, buf, size, &size));
    tt_world *c = tt_world_load(buf, size);
    ENSURE(c && tt_world_hash(c) == tt_world_hash(w));
    ENSURE(tt_world_get_sleep(c, NULL, NULL));
    int sw = settle(w, N, 1200), sc = settle(c, N, 1200);
    ENSURE(sw == sc && sw < 1200);
    ENSURE(tt_world_hash(c) == tt_world_hash(w));
    /* asleep, saved and loaded: still asleep, and woken alike */
    free(buf);
    ENSURE(tt_world_save(w, NULL, 0, &size) == TT_ENOMEM);
    buf = malloc(size);
    ENSURE_OK(tt_world_save(w, buf, size, &size));
    tt_world_destroy(c);
    c = tt_world_load(buf, size);
    ENSURE(c && sleeping(c) == N && tt_world_hash(c) == tt_world_hash(w));
    tt_particle_apply_impulse(w, a[5], (tt_vec2){0.01, 0});
    tt_particle_apply_impulse(c, a[5], (tt_vec2){0.01, 0});
    for (int s = 0; s < 30; s++) tt_world_step(w, 1.0 / 60.0), tt_world_step(c, 1.0 / 60.0);
    ENSURE(tt_world_hash(c) == tt_world_hash(w));
    /* sleeping makes a different state from not sleeping: the hash tells them apart */
    tt_world *off = pile(false, a, N);
    tt_world *on = pile(true, a, N);
    ENSURE(tt_world_hash(off) != tt_world_hash(on));
    tt_world_destroy(off);
    tt_world_destroy(on);
    free(buf);
    tt_world_destroy(c);
    tt_world_destroy(w);
}

/* Slow motions never sleep mid-motion at the default rest test (a 1 cm
 * window, 1 s; sleep.c rest_one): each runs with sleeping on and must
 * still be moving at the end (no test that cannot fail: the swings keep
 * their amplitude, so an island that slept would be caught by the count). */
static tt_world *sleepy(double g)
{
    tt_world_def d = tt_world_def_default();
    d.sleep = true;
    d.gravity = (tt_vec2){0.0, -g};
    return tt_world_create(&d);
}

/* A pendulum 1 m long swinging `amp` rad (period 2 s): it dwells near a
 * turning point, but leaves the 1 cm window there within 0.5 s (2 cm
 * swing: 0.72 s, the closest; the old 2.5 cm window, 0.5 s, slept a 5 cm
 * swing there). Returns the least x it reached in
 * the last period (the swing still there), NAN if anything ever slept. */
static double pendulum(double amp, int seconds)
{
    tt_world *w = sleepy(9.81);
    tt_particle_def pd = tt_particle_def_default();
    pd.pinned = true;
    tt_particle top = tt_particle_create(w, &pd);
    pd.pinned = false;
    pd.position = (tt_vec2){sin(amp), -cos(amp)};
    tt_particle bob = tt_particle_create(w, &pd);
    tt_distance_def dd = tt_distance_def_default();
    dd.a = top, dd.b = bob;
    dd.length = 1.0;
    tt_distance_create(w, &dd);
    double least = INFINITY;
    bool slept = false;
    for (int s = 0; s < seconds * 60; s++) {
        tt_world_step(w, 1.0 / 60.0);
        slept |= sleeping(w) != 0;
        tt_vec2 p;
        tt_particle_get_position(w, bob, &p);
        if (s >= (seconds - 2) * 60) least = fmin(least, p.x);
    }
    tt_world_destroy(w);
    return slept ? NAN : least;
}

TEST(sleep_a_slow_pendulum_swings_on)
{
    /* the world's default damping takes 8 % of the swing a second: 5 cm
     * swings 2.0 cm after 12 s, 2 cm 1.3 cm after 6 s (and once the whole
     * arc fits in the window, about 1 cm, it is at rest and sleeps) */
    ENSURE(pendulum(0.05, 12) < -0.018); /* swung on, to the other side */
    ENSURE(pendulum(0.02, 6) < -0.012);
}

/* A rope of 8 links hanging from a pin, its lower end pulled 20 cm aside
 * and let go: it swings slowly (its bottom moves about 0.3 m/s at most,
 * the joints near the pin a few cm/s) for 10 s. */
TEST(sleep_a_slowly_swinging_rope_swings_on)
{
    tt_world *w = sleepy(9.81);
    tt_particle p[9];
    for (int k = 0; k < 9; k++) {
        tt_particle_def pd = tt_particle_def_default();
        pd.pinned = k == 0;
        pd.position = (tt_vec2){0.2 * (k / 8.0) * (k / 8.0), -0.25 * k};
        p[k] = tt_particle_create(w, &pd);
        if (k) {
            tt_distance_def dd = tt_distance_def_default();
            dd.a = p[k - 1], dd.b = p[k];
            ENSURE(tt_constraint_is_valid(w, tt_distance_create(w, &dd)));
        }
    }
    double least = INFINITY;
    for (int s = 0; s < 600; s++) {
        tt_world_step(w, 1.0 / 60.0);
        ENSURE(sleeping(w) == 0);
        tt_vec2 q;
        tt_particle_get_position(w, p[8], &q);
        if (s >= 480) least = fmin(least, q.x);
    }
    ENSURE(least < -0.05); /* still swinging to the other side */
    tt_world_destroy(w);
}

/* A ball let go at rest on a frictionless slope of 1° (it gathers speed at
 * 0.17 m/s², leaving the 1 cm window in 0.34 s): it rolls, never sleeping,
 * down the whole slope. */
TEST(sleep_a_ball_rolling_slowly_down_a_gentle_slope_rolls_on)
{
    tt_world *w = sleepy(9.81);
    tt_collision_settings cs = tt_collision_settings_default();
    cs.friction_static = cs.friction_kinetic = 0.0;
    ENSURE_OK(tt_world_set_collision(w, &cs));
    const double th = 1.0 * M_PI / 180.0;
    tt_shape_def g = tt_shape_def_default();
    g.type = TT_SHAPE_SEGMENT;
    g.a = (tt_vec2){0.0, 0.0}, g.b = (tt_vec2){10.0 * cos(th), -10.0 * sin(th)};
    g.friction_static = g.friction_kinetic = 0.0;
    tt_shape_create(w, &g);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.1;
    pd.position = (tt_vec2){0.5 - 0.1 * sin(th), -0.5 * tan(th) + 0.1 / cos(th)};
    tt_particle ball = tt_particle_create(w, &pd);
    for (int s = 0; s < 240; s++) {
        tt_world_step(w, 1.0 / 60.0);
        ENSURE(sleeping(w) == 0);
    }
    tt_vec2 q;
    tt_particle_get_position(w, ball, &q);
    /* x = x0 + g sinθ t²/2 cosθ over 4 s: 1.37 m */
    ENSURE_NEAR(q.x - 0.5, 0.5 * 9.81 * sin(th) * cos(th) * 16.0, 0.05);
    tt_world_destroy(w);
}

/* A particle thrown up at 1 m/s under g = 1 m/s² (over a floor, so contacts
 * can hold: the rest test runs) is at the top of its arc at 1 s and 0.5 m,
 * dwelling within 1 cm of it for 0.28 s: it must not sleep up there. */
TEST(sleep_a_particle_at_the_top_of_its_throw_falls_back)
{
    tt_world *w = sleepy(1.0);
    floor_box(w, 5.0);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.1;
    pd.position = (tt_vec2){0.0, 0.1};
    pd.velocity = (tt_vec2){0.0, 1.0};
    tt_particle p = tt_particle_create(w, &pd);
    double top = 0.0;
    for (int s = 0; s < 110; s++) {
        tt_world_step(w, 1.0 / 60.0);
        ENSURE(sleeping(w) == 0);
        tt_vec2 q;
        tt_particle_get_position(w, p, &q);
        top = fmax(top, q.y);
    }
    ENSURE_NEAR(top, 0.6, 0.02);
    /* landed, it rests and sleeps */
    ENSURE(settle(w, 1, 300) < 300);
    tt_world_destroy(w);
}

/* A particle on a floor that the script moves each step: side to side by
 * `jitter` m (one way, then back), or along the floor at `speed` m/s from
 * rest. Returns the first step after which it sleeps, or -1 within `steps`
 * (-2: a call failed). */
static int scripted(double jitter, double speed, int steps)
{
    tt_world *w = sleepy(9.81);
    tt_collision_settings cs = tt_collision_settings_default();
    tt_shape_def g = tt_shape_def_default();
    g.type = TT_SHAPE_AABB;
    g.a = (tt_vec2){-50.0, -1.0}, g.b = (tt_vec2){50.0, 0.0};
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.5;
    pd.position = (tt_vec2){0.0, 0.5};
    tt_particle p = tt_particle_create(w, &pd);
    int slept = tt_world_set_collision(w, &cs) == TT_OK && tt_shape_is_valid(w, tt_shape_create(w, &g)) ? -1 : -2;
    for (int s = 0; s < steps && slept == -1; s++) {
        tt_vec2 q;
        if (tt_particle_get_position(w, p, &q) != TT_OK) slept = -2;
        q.x = jitter > 0.0 ? (s % 2 ? jitter : 0.0) : speed * (s + 1) / 60.0;
        if (tt_particle_set_position(w, p, q, TT_MOVE_RESET_VELOCITY) != TT_OK || tt_world_step(w, 1.0 / 60.0) != TT_OK) slept = -2;
        else if (sleeping(w)) slept = s;
    }
    tt_world_destroy(w);
    return slept; /* -2: a call failed */
}

/* A jammed particle of a settled pile that the sweeps push one way and
 * back the next step, for ever (the reference pour: 7-31 of 10 000, up to
 * 2 cm a step, since the speed cap) is at rest: a rest window set where
 * a stretch began was left every step, and the pile never slept. A steady
 * slide from rest at 1.5 times sleep_speed is not at rest: an anchor that
 * only followed the particle smoothed over sleep_time trailed it by less
 * than the window for 1.1 s, and it slept. */
TEST(sleep_a_jitter_rests_and_a_slow_slide_does_not)
{
    const int jitter = scripted(0.018, 0.0, 300);
    ENSURE(jitter >= 60 && jitter < 120); /* rested a second, from its first steps */
    ENSURE(scripted(0.0, 0.015, 600) == -1);
    ENSURE(scripted(0.0, 0.011, 600) == -1);
    ENSURE(scripted(0.0, 0.009, 600) >= 0); /* under sleep_speed: a creep, at rest */
}

/* Particles made after the last step lie past the sleep arrays: waking a
 * box, or turning sleeping off, before the next step must not read there
 * (found reading the code; ASan in the SANITIZE=1 build is the check). */
TEST(sleep_wake_with_particles_made_since_the_step)
{
    tt_particle a[N];
    tt_world *w = pile(true, a, N);
    ENSURE(settle(w, N, 1200) < 1200);
    for (int k = 0; k < 40; k++) {
        tt_particle_def p = tt_particle_def_default();
        p.position = (tt_vec2){10.0 + k, 10.0};
        tt_particle_create(w, &p);
    }
    ENSURE_OK(tt_world_explode(w, (tt_vec2){0.0, 0.3}, 0.5, 0.0));
    ENSURE(sleeping(w) == 0);
    tt_world_step(w, 1.0 / 60.0);
    ENSURE(settle(w, N, 1200) < 1200 || sleeping(w) >= N);
    for (int k = 0; k < 40; k++) {
        tt_particle_def p = tt_particle_def_default();
        p.position = (tt_vec2){-10.0 - k, 10.0};
        tt_particle_create(w, &p);
    }
    ENSURE_OK(tt_world_set_sleep(w, false, 0, 0));
    ENSURE(sleeping(w) == 0);
    tt_world_destroy(w);
}

/* What springs and constraints hold is listed once and listed again only
 * when one is made or removed (sleep_rest.c): a holder made later must be
 * counted, and a particle that lost its holder (its slot then reused by a
 * free one) must not be. No gravity: a held particle at rest sleeps, a free
 * one never does. */
static tt_particle at_rest(tt_world *w, double x, bool pinned)
{
    tt_particle_def pd = tt_particle_def_default();
    pd.position = (tt_vec2){x, 0.0};
    pd.pinned = pinned;
    return tt_particle_create(w, &pd);
}

static void hold(tt_world *w, tt_particle a, tt_particle b)
{
    tt_distance_def dd = tt_distance_def_default();
    dd.a = a, dd.b = b;
    ENSURE(tt_constraint_is_valid(w, tt_distance_create(w, &dd)));
}

static void steps(tt_world *w, int n)
{
    for (int s = 0; s < n; s++) tt_world_step(w, 1.0 / 60.0);
}

TEST(sleep_a_holder_made_later_counts)
{
    tt_world *w = sleepy(0.0);
    tt_particle pin = at_rest(w, 0.0, true), x = at_rest(w, 1.0, false);
    tt_particle y = at_rest(w, 3.0, false), z = at_rest(w, 5.0, false);
    hold(w, pin, x);
    steps(w, 120);
    ENSURE(sleeping(w) == 1u); /* x: held and at rest; y and z free */
    hold(w, pin, y);
    tt_spring_def sd = tt_spring_def_default();
    sd.a = pin, sd.b = z;
    ENSURE(tt_spring_is_valid(w, tt_spring_create(w, &sd)));
    steps(w, 120);
    ENSURE(sleeping(w) == 3u);
    tt_world_destroy(w);
}

TEST(sleep_a_particle_whose_holder_went_is_free_again)
{
    tt_world *w = sleepy(0.0);
    tt_particle pin = at_rest(w, 0.0, true), x = at_rest(w, 1.0, false);
    hold(w, pin, x);
    steps(w, 10); /* x listed as held, not asleep yet */
    ENSURE(sleeping(w) == 0u);
    ENSURE_OK(tt_particle_destroy(w, x)); /* its constraint goes with it */
    tt_particle y = at_rest(w, 1.0, false); /* free, in x's slot */
    ENSURE(y.index == x.index);
    steps(w, 180);
    ENSURE(sleeping(w) == 0u);
    tt_world_destroy(w);
}

/* Waking a box wakes exactly the islands with a sleeper touching it, wherever
 * the box and whatever the radii (sleep_grid.c finds the candidates): 60
 * lone sleepers of radii 0.05 to 0.8 (each its own island), explosions of
 * force 0 over a lattice of centres and radii, each on a fresh copy, against
 * the box test done here for every particle. */
TEST(sleep_wake_box_wakes_exactly_what_it_touches)
{
    tt_world_def d = tt_world_def_default();
    tt_world *w = tt_world_create(&d);
    floor_box(w, 100.0);
    enum { M = 60 };
    tt_particle p[M];
    double x = -60.0;
    for (int k = 0; k < M; k++) {
        tt_particle_def pd = tt_particle_def_default();
        pd.radius = k % 7 == 3 ? 0.8 : 0.05 + 0.05 * (k % 5);
        x += pd.radius + 0.3 + 0.4 * (k % 3);
        pd.position = (tt_vec2){x, pd.radius};
        x += pd.radius;
        p[k] = tt_particle_create(w, &pd);
    }
    ENSURE(settle(w, M, 600) < 600);
    size_t n = 0;
    ENSURE(tt_world_save(w, NULL, 0, &n) == TT_ENOMEM);
    unsigned char *b = malloc(n);
    ENSURE_OK(tt_world_save(w, b, n, &n));
    int woken = 0;
    for (double cx = -62.0; cx <= x + 2.0; cx += 0.7)
        for (double r = 0.05; r < 3.0; r *= 2.3) {
            tt_world *c = tt_world_load(b, n);
            ENSURE(c);
            ENSURE_OK(tt_world_explode(c, (tt_vec2){cx, 0.3}, r, 0.0));
            for (int k = 0; k < M; k++) {
                tt_vec2 q;
                double rad;
                bool asleep;
                tt_particle_get_position(c, p[k], &q);
                tt_particle_get_radius(c, p[k], &rad);
                tt_particle_get_asleep(c, p[k], &asleep);
                const bool touches = q.x + rad >= cx - r && q.x - rad <= cx + r && q.y + rad >= 0.3 - r && q.y - rad <= 0.3 + r;
                ENSURE(asleep == !touches);
                woken += touches;
            }
            tt_world_destroy(c);
        }
    ENSURE(woken > 100);
    free(b);
    tt_world_destroy(w);
}
