/* Waking by islands (sleep.c keeps each island's members as a ring): a
 * wake reaches exactly the island it touches, whatever its size, in a
 * world fresh from falling asleep and in one loaded from a snapshot. */
#include "tether.h"
#include "../test.h"

#include <stdlib.h>

#define R 0.1
enum { GROUPS = 8, TOTAL = GROUPS * (GROUPS + 1) / 2 };

static uint32_t sleeping(const tt_world *w)
{
    tt_stats st;
    tt_world_get_stats(w, &st);
    return st.sleeping;
}

/* Group g: a row of g + 1 touching circles on a floor (one island), the
 * groups 1 m apart, all asleep, in *out; first[g] its first particle's
 * index in p. */
static void rows(tt_world **out, tt_particle *p, int *first)
{
    tt_world *w = *out = tt_world_create(NULL);
    tt_collision_settings cs = tt_collision_settings_default();
    ENSURE_OK(tt_world_set_collision(w, &cs));
    tt_shape_def g = tt_shape_def_default();
    g.type = TT_SHAPE_AABB;
    g.a = (tt_vec2){-1.0, -1.0}, g.b = (tt_vec2){40.0, 0.0};
    ENSURE(tt_shape_is_valid(w, tt_shape_create(w, &g)));
    int k = 0;
    double x = 0.0;
    for (int grp = 0; grp < GROUPS; grp++, x += 1.0) {
        first[grp] = k;
        for (int m = 0; m <= grp; m++, k++, x += 2.0 * R) {
            tt_particle_def d = tt_particle_def_default();
            d.radius = R;
            d.position = (tt_vec2){x, R};
            p[k] = tt_particle_create(w, &d);
        }
    }
    for (int s = 0; s < 600 && sleeping(w) < TOTAL; s++) tt_world_step(w, 1.0 / 60.0);
    ENSURE(sleeping(w) == TOTAL);
}

/* After waking group grp: its members awake, every other particle asleep. */
static void only_group_awake(const tt_world *w, const tt_particle *p, const int *first, int grp)
{
    for (int k = 0; k < TOTAL; k++) {
        bool asleep;
        ENSURE_OK(tt_particle_get_asleep(w, p[k], &asleep));
        ENSURE(asleep == !(k >= first[grp] && k <= first[grp] + grp));
    }
    ENSURE(sleeping(w) == (uint32_t)(TOTAL - grp - 1));
}

TEST(sleep_wake_reaches_exactly_the_island_touched)
{
    tt_particle p[TOTAL], q[TOTAL]; /* q: the saved world's handles (a loaded world takes its tag) */
    int first[GROUPS];
    tt_world *w;
    rows(&w, q, first);
    size_t n = 0;
    ENSURE(tt_world_save(w, NULL, 0, &n) == TT_ENOMEM);
    unsigned char *b = malloc(n);
    ENSURE_OK(tt_world_save(w, b, n, &n));
    tt_world_destroy(w);
    for (int grp = 0; grp < GROUPS; grp++)
        for (int m = 0; m <= grp; m++) {
            rows(&w, p, first); /* the rings as the islands fell asleep */
            ENSURE_OK(tt_particle_apply_impulse(w, p[first[grp] + m], (tt_vec2){0.0, 0.0}));
            only_group_awake(w, p, first, grp);
            tt_world_destroy(w);
            w = tt_world_load(b, n); /* the rings made again from the islands */
            ENSURE(w);
            ENSURE_OK(tt_particle_set_velocity(w, q[first[grp] + m], (tt_vec2){0.0, 0.0}));
            only_group_awake(w, q, first, grp);
            /* a second wake of another island, the first one awake */
            const int other = (grp + 3) % GROUPS;
            ENSURE_OK(tt_particle_apply_impulse(w, q[first[other]], (tt_vec2){0.0, 0.0}));
            ENSURE(sleeping(w) == (uint32_t)(TOTAL - grp - 1 - other - 1));
            tt_world_destroy(w);
        }
    free(b);
}

/* A woken island that falls asleep again forms a new ring: waking it once
 * more wakes all of it and nothing else. */
TEST(sleep_an_island_asleep_again_wakes_whole)
{
    tt_particle p[TOTAL];
    int first[GROUPS];
    tt_world *w;
    rows(&w, p, first);
    const int grp = GROUPS - 1;
    ENSURE_OK(tt_particle_apply_impulse(w, p[first[grp] + 2], (tt_vec2){0.0, 0.0}));
    for (int s = 0; s < 600 && sleeping(w) < TOTAL; s++) tt_world_step(w, 1.0 / 60.0);
    ENSURE(sleeping(w) == TOTAL);
    ENSURE_OK(tt_particle_apply_impulse(w, p[first[grp] + grp], (tt_vec2){0.0, 0.0}));
    only_group_awake(w, p, first, grp);
    tt_world_destroy(w);
}
