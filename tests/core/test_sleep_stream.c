/* Sleeping's snapshot section ('SLEP') in the layouts older builds wrote:
 * their streams still load (src/core/sleep_stream.c). */
#include "tether.h"
#include "core/stream.h" /* tt__hash_bytes: to reseal a stream rewritten in an older layout */
#include "../test.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Written by the build before 'SLEP' gained the time since the anchor and
 * the held flag (1faf175, sleeping opt-in, defaults 0.05 m/s and 0.5 s):
 * five circles r 0.25 asleep on a ground box (x -5..5, top at 0) after 32
 * steps at 1/60 s, g = -10, then a sixth made at (0, 50) and three steps
 * more. The stream is 28 bytes a particle in its 'SLEP' section. */
#define OLD_STREAM "tests/core/data/sleep_slep_v1.ttss"
#define OLD_LONE_Y 49.98749999999999

static unsigned char *read_file(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    unsigned char *b = malloc(1 << 16);
    *n = b ? fread(b, 1, 1 << 16, f) : 0;
    fclose(f);
    return b;
}

static uint32_t sleeping(const tt_world *w)
{
    tt_stats st;
    tt_world_get_stats(w, &st);
    return st.sleeping;
}

/* The particle made last (slot order) and its height. */
static double lone_y(const tt_world *w)
{
    tt_particle ids[8];
    const uint32_t n = tt_world_list_particles(w, ids, 8);
    tt_vec2 p = {0, 0};
    if (n) tt_particle_get_position(w, ids[n - 1], &p);
    return p.y;
}

TEST(sleep_stream_of_the_build_before_the_held_fields_loads)
{
    size_t n = 0;
    unsigned char *b = read_file(OLD_STREAM, &n);
    ENSURE(b && n > 32);
    tt_world *w = tt_world_load(b, n);
    ENSURE(w); /* refused before: "section 'SLEP': ... bytes left unread" or a bad held flag */
    double speed = 0, time = 0;
    ENSURE(tt_world_get_sleep(w, &speed, &time) && speed == 0.05 && time == 0.5);
    ENSURE(sleeping(w) == 5);
    ENSURE(lone_y(w) == OLD_LONE_Y);
    /* it goes on as a world does: the pile sleeps on while the lone one falls onto it and wakes it */
    for (int s = 0; s < 60; s++) tt_world_step(w, 1.0 / 60);
    ENSURE(sleeping(w) == 5 && lone_y(w) < OLD_LONE_Y - 4.0);
    int s = 0;
    while (sleeping(w) == 5 && s < 600) tt_world_step(w, 1.0 / 60), s++;
    ENSURE(s < 600 && lone_y(w) < 1.0); /* landed on the pile, which woke */
    while (sleeping(w) < 6 && s < 1200) tt_world_step(w, 1.0 / 60), s++;
    ENSURE(sleeping(w) == 6); /* and all of it falls asleep again */
    /* saved again, in today's layout: the same world */
    size_t m = 0;
    ENSURE(tt_world_save(w, NULL, 0, &m) == TT_ENOMEM);
    unsigned char *c = malloc(m);
    ENSURE_OK(tt_world_save(w, c, m, &m));
    tt_world *again = tt_world_load(c, m);
    ENSURE(again && tt_world_hash(again) == tt_world_hash(w));
    tt_world_destroy(again);
    free(c);
    tt_world_destroy(w);
    free(b);
}

/* Today's stream of a world whose particles all sleep (their held flags
 * are 0, their smoothed positions where they sleep) rewritten with each
 * particle's record cut to its first `keep` of 56 bytes: a layout between
 * (36: the time since the anchor, no held flag; 40: the held flag, no
 * smoothed position) loads as the same world. */
static void cut_records(size_t keep)
{
    size_t n = 0;
    unsigned char *b = read_file(OLD_STREAM, &n);
    ENSURE(b);
    tt_world *w = tt_world_load(b, n);
    ENSURE(w);
    for (int s = 0; s < 1200 && sleeping(w) < 6; s++) tt_world_step(w, 1.0 / 60);
    ENSURE(sleeping(w) == 6);
    tt_world_step(w, 1.0 / 60), tt_world_step(w, 1.0 / 60); /* nothing detected since: none held */
    size_t m = 0;
    ENSURE(tt_world_save(w, NULL, 0, &m) == TT_ENOMEM);
    unsigned char *c = malloc(m);
    ENSURE_OK(tt_world_save(w, c, m, &m));
    /* find 'SLEP', drop the last u32 of each of the 6 records, shorten the section and the body */
    size_t at = 32;
    while (at + 16 <= m && memcmp(c + at, "SLEP", 4) != 0) {
        uint64_t len;
        memcpy(&len, c + at + 8, 8);
        at += 16 + (size_t)len;
    }
    ENSURE(at + 16 <= m);
    uint64_t len;
    memcpy(&len, c + at + 8, 8);
    ENSURE(len == 20 + 6 * 56);
    unsigned char *rec = c + at + 16 + 20, *out = rec;
    for (int k = 0; k < 6; k++, rec += 56, out += keep) {
        uint32_t held;
        memcpy(&held, rec + 36, 4);
        ENSURE(held == 0);
        memmove(out, rec, keep);
    }
    memmove(out, rec, (size_t)(c + m - rec));
    m -= 6 * (56 - keep);
    len -= 6 * (56 - keep);
    memcpy(c + at + 8, &len, 8);
    uint64_t body = m - 32, sum = tt__hash_bytes(c + 32, m - 32);
    memcpy(c + 16, &body, 8);
    memcpy(c + 24, &sum, 8);
    tt_world *old = tt_world_load(c, m);
    ENSURE(old && sleeping(old) == 6 && tt_world_hash(old) == tt_world_hash(w));
    tt_world_destroy(old);
    free(c);
    tt_world_destroy(w);
    free(b);
}

TEST(sleep_stream_without_the_held_flag_loads) { cut_records(36); }
TEST(sleep_stream_without_the_smoothed_position_loads) { cut_records(40); }
