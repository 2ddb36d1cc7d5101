/* tether — replay journals (src/core/journal*.c): a recorded session,
 * replayed into a new world or the same one, from memory or from a file,
 * gives the recorded hash at every step; a desync is reported at its step;
 * files cut short, corrupted or foreign are refused with nothing changed;
 * memory stays within max_bytes; journaling changes nothing of the world. */
#include "test.h"
#include "alloc_fail.h"
#include "core/scenes.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

enum { STEPS = 90 };

static const char *tmp_path(const char *name)
{
    static char p[2][256];
    static int k;
    k ^= 1;
    snprintf(p[k], sizeof p[k], "/tmp/tether_test_%ld_%s", (long)getpid(), name);
    return p[k];
}

/* Records STEPS steps of scene k (its driver's calls between the steps are
 * what the journal must catch): the journal and the hash after each step. */
static tt_journal *record(scene_kind k, uint64_t *h, scene *out)
{
    scene sc;
    if (!scene_build(&sc, k)) return NULL;
    tt_journal *j = tt_journal_start(sc.w, &(tt_journal_def){.max_bytes = (size_t)64 << 20});
    for (int s = 0; j && s < STEPS; s++) {
        scene_step(&sc);
        h[s] = tt_world_hash(sc.w);
    }
    if (out) *out = sc;
    else tt_world_destroy(sc.w);
    return j;
}

/* Plays j into w from its start: true when every step had the recorded hash h[]. */
static bool replays(tt_journal *j, tt_world *w, const uint64_t *h)
{
    if (tt_journal_replay_begin(j, w) != TT_OK) return false;
    for (int s = 0; s < STEPS; s++) {
        tt_replay r;
        if (tt_journal_replay_step(j, w, &r) != TT_OK || r != TT_REPLAY_SYNC || tt_world_hash(w) != h[s]) {
            printf("    step %d: %s\n", s + 1, tt_last_error(w));
            return false;
        }
    }
    tt_replay r = TT_REPLAY_SYNC;
    return tt_journal_replay_step(j, w, &r) == TT_OK && r == TT_REPLAY_END;
}

TEST(journal_replays_each_reference_scene_into_a_new_world_and_the_same_one_hash_for_hash)
{
    for (int k = 0; k < SCENE_COUNT; k++) {
        uint64_t h[STEPS];
        scene sc;
        tt_journal *j = record((scene_kind)k, h, &sc);
        ENSURE(j);
        tt_journal_info info;
        ENSURE_OK(tt_journal_get_info(j, &info));
        ENSURE(info.recording && !info.full && info.steps == STEPS);
        ENSURE(k == SCENE_INTEGRATORS || k == SCENE_SETTLE || info.changed > 0); /* the drivers call between steps (settle's first at step 240) */
        ENSURE_OK(tt_journal_stop(j));
        ENSURE(tt_journal_replay_begin(j, sc.w) == TT_OK); /* no longer recording: replays */
        tt_world *fresh = tt_world_create(NULL);
        ENSURE(replays(j, fresh, h));
        ENSURE(replays(j, sc.w, h));
        ENSURE_OK(tt_journal_get_info(j, &info));
        ENSURE(!info.recording && info.replayed == STEPS && info.desync == 0);
        tt_world_destroy(fresh);
        tt_world_destroy(sc.w);
        tt_journal_destroy(j);
    }
}

TEST(journal_saved_to_a_file_replays_in_a_new_world_and_a_snapshot_file_is_not_one)
{
    uint64_t h[STEPS];
    tt_journal *j = record(SCENE_ZOO, h, NULL); /* the world goes: the journal stops with it */
    ENSURE(j);
    tt_journal_info info;
    ENSURE_OK(tt_journal_get_info(j, &info));
    ENSURE(!info.recording && info.steps == STEPS);
    const char *path = tmp_path("zoo.ttj"), *snap = tmp_path("zoo.tts");
    ENSURE_OK(tt_journal_save_file(j, path));
    tt_journal_destroy(j);
    tt_journal *back = tt_journal_load_file(path);
    ENSURE(back);
    tt_world *w = tt_world_create(NULL);
    ENSURE(replays(back, w, h));
    /* all at once, from the start again */
    ENSURE_OK(tt_journal_replay_begin(back, w));
    tt_replay r;
    ENSURE_OK(tt_journal_replay_all(back, w, &r));
    ENSURE(r == TT_REPLAY_END && tt_world_hash(w) == h[STEPS - 1]);
    /* a journal file is not a snapshot, nor a snapshot a journal: both refused, naming it */
    const uint64_t before = tt_world_hash(w);
    ENSURE(tt_world_restore_file(w, path) == TT_EINVAL);
    ENSURE(strstr(tt_last_error(w), "replay journal") != NULL);
    ENSURE(tt_world_hash(w) == before);
    ENSURE_OK(tt_world_save_file(w, snap));
    ENSURE(tt_journal_load_file(snap) == NULL);
    ENSURE(strstr(tt_last_error(NULL), "not a replay journal") != NULL);
    remove(path);
    remove(snap);
    tt_journal_destroy(back);
    tt_world_destroy(w);
}

static unsigned char *bytes_of(const tt_journal *j, size_t *n)
{
    tt_journal_save(j, NULL, 0, n);
    unsigned char *b = malloc(*n);
    if (b && tt_journal_save(j, b, *n, n) != TT_OK) {
        free(b);
        b = NULL;
    }
    return b;
}

TEST(journal_cut_short_corrupted_or_foreign_is_refused_and_the_world_is_unchanged)
{
    uint64_t h[STEPS];
    tt_journal *j = record(SCENE_POUR, h, NULL);
    ENSURE(j);
    size_t n;
    unsigned char *b = bytes_of(j, &n);
    ENSURE(b);
    const char *path = tmp_path("cut.ttj");
    ENSURE_OK(tt_journal_save_file(j, path));
    /* the file cut at a spread of lengths, and bytes flipped across it: the checksum catches each */
    FILE *f = fopen(path, "rb");
    ENSURE(f);
    unsigned char *file = malloc(n + 48);
    size_t fn = fread(file, 1, n + 48, f);
    fclose(f);
    ENSURE(fn == n + 48);
    tt_world *w = tt_world_create(NULL);
    ENSURE_OK(tt_journal_replay_begin(j, w));
    ENSURE_OK(tt_journal_replay_step(j, w, NULL));
    const uint64_t hw = tt_world_hash(w);
    for (size_t cut = 0; cut < fn; cut += 1 + fn / 97) {
        f = fopen(path, "wb");
        ENSURE(f && fwrite(file, 1, cut, f) == cut);
        fclose(f);
        ENSURE(tt_journal_load_file(path) == NULL);
    }
    for (size_t at = 0; at < fn; at += 1 + fn / 89) {
        file[at] ^= 0x10;
        f = fopen(path, "wb");
        ENSURE(f && fwrite(file, 1, fn, f) == fn);
        fclose(f);
        file[at] ^= 0x10;
        ENSURE(tt_journal_load_file(path) == NULL);
        ENSURE(strstr(tt_last_error(NULL), path) != NULL);
    }
    /* the bytes themselves (no file checksum): cut, and fields broken in place */
    for (size_t cut = 0; cut < n; cut += 1 + n / 61) ENSURE(tt_journal_load(b, cut) == NULL);
    static const size_t fields[] = {0, 4, 8, 12, 16, 24, 32, 40, 48};
    for (unsigned k = 0; k < sizeof fields / sizeof fields[0]; k++) {
        b[fields[k]] ^= 0x41;
        ENSURE(tt_journal_load(b, n) == NULL);
        b[fields[k]] ^= 0x41;
    }
    b[n - 1] ^= 0xFF; /* the last step's delta or hash: a hash loads, a delta must not break the reader */
    tt_journal *odd = tt_journal_load(b, n);
    tt_journal_destroy(odd);
    b[n - 1] ^= 0xFF;
    tt_journal *same = tt_journal_load(b, n);
    ENSURE(same);
    tt_journal_destroy(same);
    ENSURE(tt_journal_load_file(tmp_path("does-not-exist.ttj")) == NULL);
    ENSURE(strstr(tt_last_error(NULL), "cannot open") != NULL);
    ENSURE(tt_world_hash(w) == hw);
    /* the replay goes on where it was */
    for (int s = 1; s < STEPS; s++) ENSURE_OK(tt_journal_replay_step(j, w, NULL));
    ENSURE(tt_world_hash(w) == h[STEPS - 1]);
    remove(path);
    free(file);
    free(b);
    tt_world_destroy(w);
    tt_journal_destroy(j);
}

TEST(journal_desync_is_reported_at_its_step_and_a_change_that_no_longer_applies_is_refused)
{
    scene sc;
    ENSURE(scene_build(&sc, SCENE_POUR));
    tt_journal *j = tt_journal_start(sc.w, &(tt_journal_def){.max_bytes = (size_t)16 << 20});
    ENSURE(j);
    for (int s = 0; s < 40; s++) {
        if (s == 30) tt_particle_apply_impulse(sc.w, sc.p[4], (tt_vec2){1, 0});
        scene_step(&sc);
    }
    ENSURE_OK(tt_journal_stop(j));
    tt_world *w = tt_world_create(NULL);
    ENSURE_OK(tt_journal_replay_begin(j, w));
    tt_replay r;
    for (int s = 0; s < 10; s++) ENSURE(tt_journal_replay_step(j, w, &r) == TT_OK && r == TT_REPLAY_SYNC);
    /* the game meddles with the replay world: the next step no longer matches */
    tt_world_set_gravity(w, (tt_vec2){0, -9});
    ENSURE_OK(tt_journal_replay_all(j, w, &r));
    ENSURE(r == TT_REPLAY_DESYNC);
    tt_journal_info info;
    ENSURE_OK(tt_journal_get_info(j, &info));
    ENSURE(info.desync == 11 && info.replayed == 11 && info.desync_got != info.desync_expected);
    ENSURE(info.desync_got == tt_world_hash(w));
    ENSURE(strstr(tt_last_error(w), "desync at step 11") != NULL);
    /* playing on: the change recorded before step 31 was coded against a world this one is not */
    uint64_t hw = 0;
    tt_result res = TT_OK;
    for (int s = 11; s < 40 && res == TT_OK; s++) {
        hw = tt_world_hash(w);
        res = tt_journal_replay_step(j, w, &r);
    }
    ENSURE(res == TT_EINVAL && strstr(tt_last_error(w), "does not apply") != NULL);
    ENSURE_OK(tt_journal_get_info(j, &info));
    ENSURE(info.replayed == 30 && info.desync == 11 && tt_world_hash(w) == hw);
    /* replays refuse a journal that records, and nothing begun */
    tt_journal *k = tt_journal_start(w, &(tt_journal_def){.max_bytes = 1 << 24});
    ENSURE(k);
    ENSURE(tt_journal_start(w, &(tt_journal_def){.max_bytes = 1 << 24}) == NULL);
    ENSURE(tt_journal_replay_begin(k, sc.w) == TT_ESTATE);
    tt_journal_destroy(k);
    tt_journal *l = tt_journal_load(NULL, 0);
    ENSURE(!l);
    tt_journal_destroy(j);
    tt_world_destroy(w);
    tt_world_destroy(sc.w);
}

TEST(journal_changes_nothing_of_the_world_and_records_a_restore_as_a_change)
{
    scene a, b;
    ENSURE(scene_build(&a, SCENE_CLOTH) && scene_build(&b, SCENE_CLOTH));
    tt_journal *j = tt_journal_start(b.w, &(tt_journal_def){.max_bytes = (size_t)64 << 20});
    ENSURE(j);
    size_t n = 0, na = 0;
    tt_world_save(b.w, NULL, 0, &n);
    unsigned char *s = malloc(n), *sa = malloc(n);
    ENSURE(s && sa);
    for (int t = 0; t < 80; t++) {
        if (t == 20) ENSURE(tt_world_save(b.w, s, n, &n) == TT_OK && tt_world_save(a.w, sa, n, &na) == TT_OK);
        if (t == 50) { /* a game loads its save: the world jumps back 30 steps */
            ENSURE_OK(tt_world_restore(b.w, s, n));
            ENSURE_OK(tt_world_restore(a.w, sa, na));
        }
        scene_step(&a);
        scene_step(&b);
        ENSURE(tt_world_hash(a.w) == tt_world_hash(b.w)); /* the journaled twin stays the unjournaled one */
    }
    tt_journal_info info;
    ENSURE_OK(tt_journal_get_info(j, &info));
    ENSURE(info.steps == 80 && info.changed >= 1);
    /* the restore replays: a new world ends where b is */
    ENSURE_OK(tt_journal_stop(j));
    tt_world *c = tt_world_create(NULL);
    tt_replay r;
    ENSURE(tt_journal_replay_begin(j, c) == TT_OK && tt_journal_replay_all(j, c, &r) == TT_OK && r == TT_REPLAY_END);
    ENSURE(tt_world_hash(c) == tt_world_hash(b.w));
    tt_world_destroy(c);
    tt_journal_destroy(j); /* stops recording first */
    ENSURE(tt_world_step(b.w, 1.0 / 60) == TT_OK);
    free(s);
    free(sa);
    tt_world_destroy(a.w);
    tt_world_destroy(b.w);
}

TEST(journal_memory_stays_within_max_bytes_recording_stops_and_what_it_holds_replays)
{
    scene sc;
    ENSURE(scene_build(&sc, SCENE_POUR));
    size_t n = 0;
    tt_world_save(sc.w, NULL, 0, &n);
    const size_t max = 3 * n + 7000; /* room for a few steps past the work space (6000 before the sleep section's smoothed positions: then full at step 0) */
    ENSURE(tt_journal_start(sc.w, &(tt_journal_def){.max_bytes = 3 * n - 1}) == NULL); /* not even its work space */
    ENSURE(strstr(tt_last_error(sc.w), "max_bytes") != NULL);
    ENSURE(tt_journal_start(sc.w, &(tt_journal_def){.max_bytes = 10}) == NULL);
    ENSURE(tt_journal_start(sc.w, NULL) == NULL);
    ENSURE(tt_journal_start(NULL, &(tt_journal_def){.max_bytes = 1 << 20}) == NULL);
    tt_journal *j = tt_journal_start(sc.w, &(tt_journal_def){.max_bytes = max});
    ENSURE(j);
    uint64_t h[STEPS];
    tt_journal_info info = {0};
    int s = 0;
    for (; s < STEPS; s++) {
        scene_step(&sc);
        h[s] = tt_world_hash(sc.w);
        ENSURE_OK(tt_journal_get_info(j, &info));
        ENSURE(info.bytes <= max);
    }
    ENSURE(info.full && !info.recording && info.steps > 0 && info.steps < STEPS);
    /* what it holds loads back (the step it could not take leaves no trace: found by the C fuzzer) */
    size_t bn;
    unsigned char *b = bytes_of(j, &bn);
    tt_journal *back = b ? tt_journal_load(b, bn) : NULL;
    ENSURE(back);
    tt_journal_destroy(back);
    free(b);
    tt_world *w = tt_world_create(NULL);
    ENSURE_OK(tt_journal_replay_begin(j, w));
    tt_replay r;
    ENSURE_OK(tt_journal_replay_all(j, w, &r));
    ENSURE(r == TT_REPLAY_END && tt_world_hash(w) == h[info.steps - 1]);
    tt_journal_destroy(j);
    tt_world_destroy(w);
    tt_world_destroy(sc.w);
}

TEST(journal_out_of_memory_while_recording_or_replaying_leaves_the_world_as_it_was)
{
    scene sc, twin;
    ENSURE(scene_build(&sc, SCENE_ZOO) && scene_build(&twin, SCENE_ZOO));
    tt_journal *j = tt_journal_start(sc.w, &(tt_journal_def){.max_bytes = (size_t)64 << 20});
    ENSURE(j);
    for (int s = 0; s < 12; s++) {
        scene_step(&sc);
        scene_step(&twin);
    }
    /* a change the journal must code when memory has run out: recording stops, the step goes on */
    ENSURE_OK(tt_particle_apply_impulse(sc.w, sc.p[0], (tt_vec2){0.5, 0}));
    ENSURE_OK(tt_particle_apply_impulse(twin.w, twin.p[0], (tt_vec2){0.5, 0}));
    tt_test_alloc_fail_from(0);
    const tt_result stepped = tt_world_step(sc.w, 1.0 / 60);
    ENSURE(tt_test_alloc_ok());
    ENSURE_OK(tt_world_step(twin.w, 1.0 / 60));
    ENSURE(stepped != TT_OK || tt_world_hash(sc.w) == tt_world_hash(twin.w));
    tt_journal_info info;
    ENSURE_OK(tt_journal_get_info(j, &info));
    ENSURE(!info.recording && info.full && info.steps == 12);
    /* replay steps that run out of memory at each allocation in turn, inside the step too: each is
     * refused with the world as it was, and the same step replayed again plays as recorded */
    tt_world *w = tt_world_create(NULL);
    ENSURE_OK(tt_journal_replay_begin(j, w));
    int inside = 0;
    for (uint64_t s = 0; s < info.steps; s++) {
        for (long k = 0;; k++) {
            const uint64_t before = tt_world_hash(w);
            tt_test_alloc_fail_from(k);
            tt_result res = tt_journal_replay_step(j, w, NULL);
            const bool refused = tt_test_alloc_ok();
            if (res == TT_OK) break;
            tt_journal_info now;
            tt_journal_get_info(j, &now);
            inside += strstr(tt_last_error(w), "inside the step") != NULL;
            ENSURE(refused && res == TT_ENOMEM);
            ENSURE(now.replayed == s && tt_world_hash(w) == before);
        }
    }
    ENSURE_OK(tt_journal_get_info(j, &info));
    ENSURE(info.replayed == 12 && info.desync == 0 && inside > 0);
    tt_journal_destroy(j);
    tt_world_destroy(w);
    tt_world_destroy(sc.w);
    tt_world_destroy(twin.w);
}

/* A world of a velocity integrator whose one shape went after a step that
 * collided with it: the collision state stays (the shape's slot is saved)
 * with nothing left to detect, and the arrays that step made stay too. A
 * world loaded from its stream has the same state without those arrays.
 * The C fuzzer's journal desync (seed 1796210282, call 43839, step 1) was
 * such a world: the recorded one kept its last substep's end positions
 * (they were in its stream and its hash), the replay did not. */
static tt_world *shape_gone(tt_integrator integrator, tt_particle *p)
{
    tt_world_def wd = tt_world_def_default();
    wd.integrator = integrator;
    tt_world *w = tt_world_create(&wd);
    tt_particle_def pd = tt_particle_def_default();
    pd.position = (tt_vec2){0.5, 0.55};
    pd.radius = 0.05;
    *p = tt_particle_create(w, &pd);
    tt_shape_def sd = tt_shape_def_default(); /* a segment (0, 0) - (1, 0) */
    sd.type = TT_SHAPE_CAPSULE;
    sd.radius = 0.5;
    tt_shape s = tt_shape_create(w, &sd);
    /* a particle made since: the end positions no longer hold, and a stream holds none */
    pd.position = (tt_vec2){3, 0};
    if (tt_world_step(w, 1.0 / 60) != TT_OK || tt_shape_destroy(w, s) != TT_OK ||
        !tt_particle_is_valid(w, tt_particle_create(w, &pd))) {
        tt_world_destroy(w);
        return NULL;
    }
    return w;
}

TEST(journal_replays_a_velocity_integrator_world_whose_shapes_are_gone)
{
    const tt_integrator kinds[] = {TT_EULER, TT_SYMPLECTIC_EULER, TT_LEAPFROG, TT_RK4};
    for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; k++) {
        tt_particle p;
        tt_world *w = shape_gone(kinds[k], &p);
        ENSURE(w);
        tt_journal *j = tt_journal_start(w, &(tt_journal_def){.max_bytes = 1 << 20});
        ENSURE(j);
        uint64_t h[6];
        for (int s = 0; s < 6; s++) {
            ENSURE_OK(tt_world_step(w, 1.0 / 60));
            h[s] = tt_world_hash(w);
        }
        ENSURE_OK(tt_journal_stop(j));
        tt_world *fresh = tt_world_create(NULL);
        ENSURE_OK(tt_journal_replay_begin(j, fresh));
        for (int s = 0; s < 6; s++) {
            tt_replay r;
            ENSURE_OK(tt_journal_replay_step(j, fresh, &r));
            ENSURE(r == TT_REPLAY_SYNC && tt_world_hash(fresh) == h[s]);
        }
        tt_journal_destroy(j);
        tt_world_destroy(fresh);
        tt_world_destroy(w);
    }
}

/* The same world against a copy restored from its snapshot: they step alike
 * while nothing collides, and when a shape comes back under the falling
 * particle, the substep each starts from (kept end positions, or x − v·h)
 * is the same, so the bounce is too. */
TEST(journal_world_whose_shapes_are_gone_and_its_snapshot_step_alike)
{
    const tt_integrator kinds[] = {TT_EULER, TT_SYMPLECTIC_EULER, TT_LEAPFROG, TT_RK4};
    for (size_t k = 0; k < sizeof kinds / sizeof kinds[0]; k++) {
        tt_particle p, q;
        tt_world *w = shape_gone(kinds[k], &p);
        tt_world *copy = shape_gone(TT_VERLET, &q);
        ENSURE(w && copy);
        size_t n = 0;
        ENSURE(tt_world_save(w, NULL, 0, &n) == TT_ENOMEM);
        unsigned char *b = malloc(n);
        ENSURE(b);
        ENSURE_OK(tt_world_save(w, b, n, &n));
        ENSURE_OK(tt_world_restore(copy, b, n));
        free(b);
        for (int s = 0; s < 40; s++) {
            if (s == 3) { /* a floor under it again, in both */
                tt_shape_def sd = tt_shape_def_default();
                sd.type = TT_SHAPE_AABB;
                sd.a = (tt_vec2){-5, -2};
                sd.b = (tt_vec2){5, -1};
                ENSURE(tt_shape_is_valid(w, tt_shape_create(w, &sd)) && tt_shape_is_valid(copy, tt_shape_create(copy, &sd)));
            }
            ENSURE_OK(tt_world_step(w, 1.0 / 60));
            ENSURE_OK(tt_world_step(copy, 1.0 / 60));
            ENSURE(tt_world_hash(w) == tt_world_hash(copy));
        }
        tt_vec2 a, c;
        ENSURE_OK(tt_particle_get_position(w, p, &a));
        ENSURE_OK(tt_particle_get_position(copy, p, &c));
        ENSURE(a.x == c.x && a.y == c.y && a.y > -1.0); /* on the floor, not through it */
        tt_world_destroy(copy);
        tt_world_destroy(w);
    }
}
