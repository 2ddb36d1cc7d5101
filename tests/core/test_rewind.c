/* tether — the rewind ring (src/core/rewind.c, delta.c): scrubbing back
 * and playing forward again gives the first pass's hash at every step; a
 * seek lands on the newest keyframe at or before the step; history and
 * memory stay within their bounds; the delta codec round-trips any bytes. */
#include "test.h"
#include "core/delta.h"
#include "core/scenes.h"

#include <stdlib.h>
#include <string.h>

enum { STEPS = 300 };

/* Steps the scene from its current step to `to` (the scene's inputs are a function of the step counter). */
static void play_to(scene *sc, uint64_t to)
{
    tt_stats st;
    while (tt_world_get_stats(sc->w, &st) == TT_OK && st.steps < to) scene_step(sc);
}

TEST(rewind_scrub_back_2_s_and_forward_again_gives_the_first_pass_hashes)
{
    for (int kind = 0; kind < SCENE_COUNT; kind++) {
        scene sc;
        ENSURE(scene_build(&sc, (scene_kind)kind));
        tt_rewind_def def = tt_rewind_def_default();
        def.every = 7;
        tt_rewind *r = tt_rewind_create(&def);
        ENSURE(r);
        uint64_t h[STEPS + 1];
        ENSURE_OK(tt_rewind_record(r, sc.w));
        h[0] = tt_world_hash(sc.w);
        for (int s = 1; s <= STEPS; s++) {
            scene_step(&sc);
            ENSURE_OK(tt_rewind_record(r, sc.w));
            h[s] = tt_world_hash(sc.w);
        }
        /* back 2 s at 60 Hz, one step at a time (a scrub backwards), each rebuilt exactly */
        for (int s = STEPS; s >= STEPS - 120; s--) {
            uint64_t at = 0;
            ENSURE_OK(tt_rewind_seek(r, sc.w, (uint64_t)s, &at));
            ENSURE(at <= (uint64_t)s && at + def.every > (uint64_t)s && at % def.every == 0);
            play_to(&sc, (uint64_t)s);
            ENSURE(tt_world_hash(sc.w) == h[s]);
        }
        /* and forward again from there, recording: the same hashes as the first pass */
        for (int s = STEPS - 119; s <= STEPS; s++) {
            scene_step(&sc);
            ENSURE_OK(tt_rewind_record(r, sc.w));
            ENSURE(tt_world_hash(sc.w) == h[s]);
        }
        /* every step in the ring rebuilds, in any order */
        for (int s = 0; s <= STEPS; s += 13) {
            ENSURE_OK(tt_rewind_seek(r, sc.w, (uint64_t)s, NULL));
            play_to(&sc, (uint64_t)s);
            ENSURE(tt_world_hash(sc.w) == h[s]);
        }
        tt_rewind_destroy(r);
        tt_world_destroy(sc.w);
    }
}

TEST(rewind_a_new_timeline_drops_the_old_future)
{
    scene sc;
    ENSURE(scene_build(&sc, SCENE_POUR));
    tt_rewind *r = tt_rewind_create(&(tt_rewind_def){.every = 10, .keep_steps = 1000, .max_bytes = 1 << 28});
    ENSURE(r);
    for (int s = 0; s <= 100; s++) {
        if (s) scene_step(&sc);
        ENSURE_OK(tt_rewind_record(r, sc.w));
    }
    ENSURE(tt_rewind_get_count(r) == 11);
    ENSURE_OK(tt_rewind_seek(r, sc.w, 55, NULL));
    play_to(&sc, 55);
    tt_particle_def pd = tt_particle_def_default(); /* another input: another future */
    pd.position = (tt_vec2){0, 3};
    ENSURE(tt_particle_is_valid(sc.w, tt_particle_create(sc.w, &pd)));
    ENSURE_OK(tt_rewind_record(r, sc.w));
    uint64_t first, last;
    ENSURE_OK(tt_rewind_get_range(r, &first, &last));
    ENSURE(first == 0 && last == 55 && tt_rewind_get_count(r) == 6);
    ENSURE(tt_rewind_seek(r, sc.w, 80, NULL) == TT_EINVAL);
    ENSURE(strstr(tt_last_error(sc.w), "not in the ring (0 … 55)"));
    /* the kept keyframes still rebuild: step 50 is what the first pass had */
    scene sc2;
    ENSURE(scene_build(&sc2, SCENE_POUR));
    play_to(&sc2, 50);
    ENSURE_OK(tt_rewind_seek(r, sc.w, 50, NULL));
    ENSURE(tt_world_hash(sc.w) == tt_world_hash(sc2.w));
    tt_world_destroy(sc2.w);
    tt_rewind_destroy(r);
    tt_world_destroy(sc.w);
}

TEST(rewind_history_and_memory_stay_within_their_bounds)
{
    scene sc;
    ENSURE(scene_build(&sc, SCENE_CLOTH));
    tt_rewind *r = tt_rewind_create(&(tt_rewind_def){.every = 5, .keep_steps = 60, .max_bytes = 1 << 28});
    tt_rewind *small = tt_rewind_create(&(tt_rewind_def){.every = 5, .keep_steps = 1000, .max_bytes = 100000});
    ENSURE(r && small);
    size_t one = 0;
    tt_world_save(sc.w, NULL, 0, &one);
    for (int s = 0; s <= 400; s++) {
        if (s) scene_step(&sc);
        ENSURE_OK(tt_rewind_record(r, sc.w));
        ENSURE_OK(tt_rewind_record(small, sc.w));
        uint64_t first, last;
        ENSURE_OK(tt_rewind_get_range(r, &first, &last));
        /* the window is covered: its oldest step rebuilds, and no keyframe older than needed is kept */
        ENSURE(last == (uint64_t)s);
        if (last >= 60) ENSURE(first <= last - 60 && first + 60 + 5 > last);
        /* over the bound by at most the newest keyframe and the decoding buffers */
        ENSURE(tt_rewind_get_memory(small) <= 100000 + 4 * one + 4096);
    }
    ENSURE(tt_rewind_get_count(small) >= 1 && tt_rewind_get_count(small) < 81);
    tt_rewind_destroy(r);
    tt_rewind_destroy(small);
    tt_world_destroy(sc.w);
}

TEST(rewind_refuses_bad_definitions_and_arguments)
{
    tt_rewind_def d = tt_rewind_def_default();
    d.every = 0;
    ENSURE(!tt_rewind_create(&d) && strstr(tt_last_error(NULL), "every must be in"));
    d = tt_rewind_def_default();
    d.keep_steps = 3;
    ENSURE(!tt_rewind_create(&d) && strstr(tt_last_error(NULL), "keep_steps"));
    d = tt_rewind_def_default();
    d.max_bytes = 10;
    ENSURE(!tt_rewind_create(&d));
    ENSURE(!tt_rewind_create(NULL));
    tt_rewind *r = tt_rewind_create(&(tt_rewind_def){.every = 1, .keep_steps = 10, .max_bytes = 1 << 20});
    tt_world_def wd = tt_world_def_default();
    tt_world *w = tt_world_create(&wd);
    ENSURE(r && w);
    uint64_t a, b;
    ENSURE(tt_rewind_get_range(r, &a, &b) == TT_ESTATE);
    ENSURE(tt_rewind_seek(r, w, 0, NULL) == TT_EINVAL && strstr(tt_last_error(w), "empty"));
    ENSURE(tt_rewind_record(NULL, w) == TT_EINVAL);
    ENSURE(tt_rewind_record(r, NULL) == TT_EINVAL);
    ENSURE(tt_rewind_seek(r, NULL, 0, NULL) == TT_EINVAL);
    tt_rewind_destroy(r);
    tt_rewind_destroy(NULL);
    tt_world_destroy(w);
}

TEST(delta_codec_round_trips_any_bytes_against_any_reference)
{
    uint64_t x = 88172645463325252ull;
    for (int round = 0; round < 300; round++) {
        size_t tn = (size_t)(x % 3000), rn = (size_t)((x >> 20) % 3000);
        unsigned char *t = malloc(tn + 1), *r = malloc(rn + 1), *back = malloc(tn + 1);
        ENSURE(t && r && back);
        for (size_t i = 0; i < rn; i++) { x ^= x << 13; x ^= x >> 7; x ^= x << 17; r[i] = (unsigned char)(x % 7 == 0 ? x >> 8 : 0); }
        for (size_t i = 0; i < tn; i++) { x ^= x << 13; x ^= x >> 7; x ^= x << 17; t[i] = (unsigned char)(i < rn && x % 5 ? r[i] : x >> 16); }
        unsigned char *d;
        size_t dn;
        ENSURE(tt__delta_encode(t, tn, r, rn, &d, &dn));
        ENSURE(tt__delta_length(d, dn) == tn || (tn == 0 && tt__delta_length(d, dn) == 0));
        ENSURE(tt__delta_decode(d, dn, r, rn, back, tn));
        ENSURE(memcmp(t, back, tn) == 0);
        if (dn > 6) { /* a damaged coding decodes to something or is refused, never past its buffers (ASan) */
            d[5 + x % (dn - 5)] ^= 0x40;
            (void)tt__delta_decode(d, dn, r, rn, back, tn);
            (void)tt__delta_decode(d, dn - 1, r, rn, back, tn);
        }
        free(d);
        free(t);
        free(r);
        free(back);
    }
}
