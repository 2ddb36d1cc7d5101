/* tether — snapshots (src/core/snapshot.c and the features' sections): a
 * restored world continues bit for bit as the original, in place and as a
 * new world; a bad stream is refused with the world unchanged; the hash
 * covers what the stream holds. */
#include "test.h"
#include "alloc_fail.h"
#include "core/scenes.h"
#include "core/stream.h" /* tt__hash_bytes: to forge valid checksums */

#include <math.h>
#include <stdlib.h>
#include <string.h>

static bool same_stream(const tt_world *w, const unsigned char *b, size_t n)
{
    size_t m;
    unsigned char *c = scene_save(w, &m);
    bool same = c && m == n && memcmp(b, c, n) == 0;
    free(c);
    return same;
}

static void run(scene *sc, int steps)
{
    for (int s = 0; s < steps; s++) scene_step(sc);
}

/* Counts what the run went through, so the test shows it exercised tearing and events. */
static void run_counting(scene *sc, int steps, uint32_t *breaks, uint32_t *events)
{
    for (int s = 0; s < steps; s++) {
        scene_step(sc);
        uint32_t n = 0;
        const tt_break_event *be;
        if (tt_world_get_break_events(sc->w, &be, &n) == TT_OK) *breaks += n;
        tt_world_get_contact_events(sc->w, &n);
        *events += n;
    }
}

TEST(snapshot_restore_in_place_repeats_the_same_1000_steps)
{
    uint32_t breaks = 0, events = 0;
    for (int k = 0; k < SCENE_COUNT; k++) {
        scene sc;
        ENSURE(scene_build(&sc, (scene_kind)k));
        run(&sc, 40);
        size_t n;
        unsigned char *b = scene_save(sc.w, &n);
        ENSURE(b);
        uint64_t h0 = tt_world_hash(sc.w);
        run_counting(&sc, 1000, &breaks, &events);
        uint64_t h1 = tt_world_hash(sc.w), p1 = scene_positions_digest(sc.w);
        ENSURE(h1 != h0);
        ENSURE_OK(tt_world_restore(sc.w, b, n));
        ENSURE(tt_world_hash(sc.w) == h0);
        ENSURE(same_stream(sc.w, b, n));
        run(&sc, 1000);
        ENSURE(tt_world_hash(sc.w) == h1);
        ENSURE(scene_positions_digest(sc.w) == p1);
        free(b);
        tt_world_destroy(sc.w);
    }
    ENSURE(breaks > 0);  /* the cloth tore */
    ENSURE(events > 0);  /* contacts were reported */
}

TEST(snapshot_into_a_new_world_continues_as_the_original)
{
    for (int k = 0; k < SCENE_COUNT; k++) {
        scene sc;
        ENSURE(scene_build(&sc, (scene_kind)k));
        run(&sc, 77);
        size_t n;
        unsigned char *b = scene_save(sc.w, &n);
        ENSURE(b);
        scene copy = sc;
        copy.w = tt_world_load(b, n);
        ENSURE(copy.w);
        ENSURE(same_stream(copy.w, b, n));
        ENSURE(tt_world_hash(copy.w) == tt_world_hash(sc.w));
        run(&sc, 1000);
        run(&copy, 1000); /* the driver uses the handles of the original: valid in the loaded world */
        ENSURE(tt_world_hash(copy.w) == tt_world_hash(sc.w));
        ENSURE(scene_positions_digest(copy.w) == scene_positions_digest(sc.w));
        free(b);
        tt_world_destroy(sc.w);
        tt_world_destroy(copy.w);
    }
}

TEST(snapshot_saved_handles_work_in_the_loaded_world)
{
    tt_world *a = tt_world_create(NULL);
    tt_particle_def pd = tt_particle_def_default();
    tt_particle p = tt_particle_create(a, &pd);
    tt_particle gone = tt_particle_create(a, &pd);
    ENSURE_OK(tt_particle_destroy(a, gone));
    size_t n;
    unsigned char *b = scene_save(a, &n);
    ENSURE(b);
    tt_world_destroy(a);
    tt_world *other = tt_world_create(NULL); /* takes the next tag */
    tt_particle mine = tt_particle_create(other, &pd);
    ENSURE(mine.index == p.index && mine.gen != p.gen); /* same slot, another world's tag */
    tt_world *c = tt_world_load(b, n);
    ENSURE(c);
    ENSURE(tt_particle_is_valid(c, p));
    ENSURE(!tt_particle_is_valid(c, gone));
    ENSURE(!tt_particle_is_valid(other, p));
    ENSURE(!tt_particle_is_valid(c, mine));
    /* restored in place, another world becomes the saved one, tag included */
    ENSURE_OK(tt_world_restore(other, b, n));
    ENSURE(tt_particle_is_valid(other, p));
    ENSURE(!tt_particle_is_valid(other, mine)); /* its own handles of before are stale now */
    /* the free list came back: the next particle takes the removed one's slot, with a new generation */
    tt_particle q = tt_particle_create(c, &pd);
    ENSURE(q.index == gone.index && q.gen != gone.gen);
    free(b);
    tt_world_destroy(c);
    tt_world_destroy(other);
}

TEST(snapshot_save_asks_for_room_and_writes_nothing_short)
{
    scene sc;
    ENSURE(scene_build(&sc, SCENE_ZOO));
    size_t n = 0, m = 0;
    ENSURE(tt_world_save(sc.w, NULL, 0, &n) == TT_ENOMEM && n > 32);
    unsigned char *b = malloc(n + 8);
    ENSURE(b);
    memset(b, 0xAB, n + 8);
    ENSURE(tt_world_save(sc.w, b, n - 1, &m) == TT_ENOMEM && m == n);
    ENSURE(tt_world_save(sc.w, b, n + 8, &m) == TT_OK && m == n);
    ENSURE(b[n] == 0xAB);
    ENSURE(tt_world_save(NULL, b, n, &m) == TT_EINVAL);
    ENSURE(tt_world_save(sc.w, NULL, 5, &m) == TT_EINVAL);
    free(b);
    tt_world_destroy(sc.w);
}

TEST(snapshot_truncated_corrupted_or_foreign_streams_are_refused_with_the_world_unchanged)
{
    tt_world *src = scene_small_world(), *w = scene_small_world();
    ENSURE(src && w);
    tt_world_step(w, 0.01); /* w differs from src */
    size_t n, wn;
    unsigned char *b = scene_save(src, &n), *before = scene_save(w, &wn);
    ENSURE(b && before);
    for (size_t len = 0; len < n; len++) {
        if (tt_world_restore(w, b, len) != TT_EINVAL) { tt_test_fail(__FILE__, __LINE__, "truncated to %zu accepted", len); break; }
    }
    for (size_t i = 0; i < n; i++) {
        b[i] ^= 0x5A;
        bool refused = tt_world_restore(w, b, n) == TT_EINVAL && tt_world_load(b, n) == NULL;
        b[i] ^= 0x5A;
        if (!refused) { tt_test_fail(__FILE__, __LINE__, "byte %zu flipped: accepted", i); break; }
    }
    ENSURE(strstr(tt_last_error(w), "unchanged"));
    ENSURE(tt_world_restore(w, "TTSS but not really a snapshot", 31) == TT_EINVAL);
    unsigned char *foreign = malloc(n);
    memcpy(foreign, b, n);
    foreign[0] = 'X'; /* another format */
    ENSURE(tt_world_restore(w, foreign, n) == TT_EINVAL && strstr(tt_last_error(w), "not a tether snapshot"));
    memcpy(foreign, b, n);
    foreign[4] = 2; /* another version */
    ENSURE(tt_world_restore(w, foreign, n) == TT_EINVAL && strstr(tt_last_error(w), "version 2"));
    memcpy(foreign, b, n);
    uint32_t swapped = 0x04030201u; /* written on a machine of the other byte order */
    memcpy(foreign + 8, &swapped, 4);
    ENSURE(tt_world_restore(w, foreign, n) == TT_EINVAL && strstr(tt_last_error(w), "byte order"));
    ENSURE(tt_world_restore(w, NULL, n) == TT_EINVAL);
    ENSURE(tt_world_restore(NULL, b, n) == TT_EINVAL);
    ENSURE(same_stream(w, before, wn));
    ENSURE_OK(tt_world_restore(w, b, n)); /* and the real one still works */
    ENSURE(tt_world_hash(w) == tt_world_hash(src));
    free(foreign);
    free(b);
    free(before);
    tt_world_destroy(src);
    tt_world_destroy(w);
}

/* Hostile bytes behind a valid checksum: every byte of the body changed in
 * turn, the checksum made to match. Each stream is refused with the world
 * unchanged, or is a valid world that steps without harm (ASan, UBSan). */
static void reseal(unsigned char *b, size_t n)
{
    uint64_t sum = tt__hash_bytes(b + 32, n - 32);
    memcpy(b + 24, &sum, 8);
}

TEST(snapshot_reader_survives_every_byte_changed_behind_a_valid_checksum)
{
    tt_world *w = scene_small_world();
    ENSURE(w);
    size_t n, wn;
    unsigned char *b = scene_save(w, &n), *before = scene_save(w, &wn);
    ENSURE(b && before);
    uint32_t accepted = 0;
    for (size_t i = 32; i < n; i++) {
        static const unsigned char flips[] = {0x01, 0x80, 0xFF};
        for (int f = 0; f < 3; f++) {
            b[i] ^= flips[f];
            reseal(b, n);
            if (tt_world_restore(w, b, n) == TT_OK) {
                accepted++;
                for (int s = 0; s < 3; s++) tt_world_step(w, 1.0 / 60);
                size_t m;
                unsigned char *again = scene_save(w, &m);
                ENSURE(again);
                free(again);
                ENSURE_OK(tt_world_restore(w, before, wn));
            } else if (!same_stream(w, before, wn)) {
                tt_test_fail(__FILE__, __LINE__, "byte %zu ^ 0x%02x: refused, but the world changed", i, flips[f]);
                return;
            }
            b[i] ^= flips[f];
        }
    }
    ENSURE(accepted > 0 && accepted < 3 * (n - 32)); /* some changes are valid states (a position's low bit), most not */
    free(b);
    free(before);
    tt_world_destroy(w);
}

TEST(snapshot_refuses_a_spring_joining_a_removed_particle)
{
    tt_world *w = tt_world_create(NULL);
    tt_particle_def pd = tt_particle_def_default();
    tt_particle a = tt_particle_create(w, &pd), b = tt_particle_create(w, &pd), c = tt_particle_create(w, &pd);
    tt_spring_def sd = tt_spring_def_default();
    sd.a = a;
    sd.b = b;
    ENSURE(tt_spring_create(w, &sd).gen);
    ENSURE_OK(tt_particle_destroy(w, c));
    size_t n;
    unsigned char *s = scene_save(w, &n);
    ENSURE(s);
    /* the spring record is the last 33 bytes of the world section's springs: b is at offset 5 */
    unsigned char *rec = NULL;
    for (size_t i = 32; i + 33 <= n; i++) {
        uint32_t ia, ib;
        memcpy(&ia, s + i + 1, 4);
        memcpy(&ib, s + i + 5, 4);
        if (s[i] == 1 && ia == a.index && ib == b.index) rec = s + i;
    }
    ENSURE(rec);
    memcpy(rec + 5, &c.index, 4);
    reseal(s, n);
    ENSURE(tt_world_restore(w, s, n) == TT_EINVAL);
    ENSURE(strstr(tt_last_error(w), "spring 0 joins particles 0 and 2"));
    free(s);
    tt_world_destroy(w);
}

/* Removing a particle in a loaded or restored world removes its springs, as
 * in the world that was saved (the removal reaches the springs through a
 * hook the world sets when it is made, by tt_world_create or the loader). */
TEST(snapshot_loaded_world_removes_a_particles_springs_with_it)
{
    tt_world *w = tt_world_create(NULL);
    tt_particle_def pd = tt_particle_def_default();
    tt_particle a = tt_particle_create(w, &pd), b = tt_particle_create(w, &pd);
    tt_spring_def sd = tt_spring_def_default();
    sd.a = a;
    sd.b = b;
    ENSURE(tt_spring_create(w, &sd).gen);
    size_t n;
    unsigned char *s = scene_save(w, &n);
    ENSURE(s);
    tt_world *l = tt_world_load(s, n);
    ENSURE(l);
    ENSURE_OK(tt_particle_destroy(l, a));
    ENSURE(tt_world_spring_count(l) == 0);
    ENSURE_OK(tt_world_restore(w, s, n));
    ENSURE_OK(tt_particle_destroy(w, b));
    ENSURE(tt_world_spring_count(w) == 0);
    for (int i = 0; i < 3; i++) ENSURE_OK(tt_world_step(l, 1.0 / 60));
    free(s);
    tt_world_destroy(l);
    tt_world_destroy(w);
}

/* Found by the stream reader's fuzzer (make fuzz, seed 1796181652): a
 * distance's moving target (a reeled length) was read as any number in
 * ±TT_MAX_VALUE, so a negative one was accepted, stepped into a negative
 * link length, and the world's own stream was then refused. */
TEST(snapshot_refuses_a_negative_moving_length)
{
    tt_world *w = tt_world_create(NULL);
    tt_particle_def pd = tt_particle_def_default();
    tt_particle a = tt_particle_create(w, &pd);
    pd.position.x = 1.0;
    tt_particle b = tt_particle_create(w, &pd);
    tt_distance_def dd = tt_distance_def_default();
    dd.a = a;
    dd.b = b;
    tt_constraint c = tt_distance_create(w, &dd);
    ENSURE(c.gen);
    ENSURE_OK(tt_distance_set_length(w, c, 3.25)); /* a target that moves over the next step */
    size_t n;
    unsigned char *s = scene_save(w, &n);
    ENSURE(s);
    const double want = 3.25, bad = -3.25;
    unsigned char *to = NULL; /* the mover's target follows the link's rest length: the last 3.25 */
    for (size_t i = 32; i + 8 <= n; i++)
        if (memcmp(s + i, &want, 8) == 0) to = s + i;
    ENSURE(to);
    memcpy(to, &bad, 8);
    reseal(s, n);
    const uint64_t h = tt_world_hash(w);
    if (tt_world_restore(w, s, n) == TT_OK) { /* accepted: then it must step into a world that saves and loads */
        ENSURE_OK(tt_world_step(w, 1.0 / 60));
        size_t m;
        unsigned char *again = scene_save(w, &m);
        tt_world *back = again ? tt_world_load(again, m) : NULL;
        ENSURE(back != NULL);
        tt_world_destroy(back);
        free(again);
    } else {
        ENSURE(tt_world_hash(w) == h);
    }
    free(s);
    tt_world_destroy(w);
}

/* The loader held x_old to 1e3·TT_DIVERGED, not the velocity it stands
 * for, so a crafted stream could put |v| far past TT_DIVERGED (the guard's
 * bound, which no step ever leaves) into a world. One particle, its x_old
 * (Verlet: v = (x − x_old)/dt_prev) or its velocity (the other
 * integrators) rewritten to |v| ≥ 1e17 yet |x_old| ≤ 1e3·TT_DIVERGED: the
 * stream is refused and the world is unchanged. */
TEST(snapshot_refuses_a_velocity_past_the_divergence_guard)
{
    static const tt_integrator kinds[] = {TT_VERLET, TT_SYMPLECTIC_EULER};
    for (int k = 0; k < 2; k++) {
        tt_world *w = tt_world_create(NULL);
        ENSURE(w);
        ENSURE_OK(tt_world_set_integrator(w, kinds[k]));
        tt_particle_def pd = tt_particle_def_default();
        pd.position = (tt_vec2){0.3671875, 0.6171875}; /* bit patterns found once in the stream */
        pd.velocity = (tt_vec2){0.1875, 0};
        tt_particle p = tt_particle_create(w, &pd);
        ENSURE(p.gen);
        size_t n;
        unsigned char *s = scene_save(w, &n);
        ENSURE(s);
        unsigned char *px = NULL; /* one particle: px, py, then qx */
        for (size_t i = 32; i + 24 <= n && !px; i++)
            if (memcmp(s + i, &pd.position.x, 8) == 0 && memcmp(s + i + 8, &pd.position.y, 8) == 0) px = s + i;
        ENSURE(px);
        const double q = kinds[k] == TT_VERLET ? -1e16 : 1e17; /* Verlet: v = (0.37 + 1e16)·60 */
        memcpy(px + 16, &q, 8);
        reseal(s, n);
        const uint64_t h = tt_world_hash(w);
        ENSURE(tt_world_restore(w, s, n) == TT_EINVAL);
        ENSURE(tt_world_hash(w) == h);
        ENSURE(tt_world_load(s, n) == NULL);
        tt_vec2 v;
        ENSURE_OK(tt_particle_get_velocity(w, p, &v));
        ENSURE(fabs(v.x - 0.1875) < 1e-9);
        free(s);
        tt_world_destroy(w);
    }
}

/* Found by the stream reader's fuzzer once it read every restored particle
 * back through its listed handle (seed 7, stream 257): the pools' slot
 * generations were taken as they came, so a stream could give a live slot
 * generation 0 (its listed handle is the null handle, refused as stale),
 * another world's tag, or a reuse count of 0, none of which a pool hands
 * out. Each is refused, the world unchanged. */
TEST(snapshot_refuses_a_slot_generation_no_pool_hands_out)
{
    tt_world *w = tt_world_create(NULL);
    ENSURE(w);
    tt_particle_def pd = tt_particle_def_default();
    tt_particle a = tt_particle_create(w, &pd), b = tt_particle_create(w, &pd);
    ENSURE(a.gen && b.gen);
    const uint32_t tag = b.gen >> TT_HANDLE_GEN_BITS;
    const uint32_t bad[] = {0, ((tag % 1000) + 1) << TT_HANDLE_GEN_BITS | 1u, tag << TT_HANDLE_GEN_BITS};
    size_t n;
    unsigned char *s = scene_save(w, &n);
    ENSURE(s);
    const uint32_t pool[5] = {2, a.gen, b.gen, 0, tag}; /* count, generations, free count, tag */
    unsigned char *at = NULL;
    for (size_t i = 32; i + sizeof pool <= n && !at; i++)
        if (memcmp(s + i, pool, sizeof pool) == 0) at = s + i;
    ENSURE(at);
    const uint64_t h = tt_world_hash(w);
    for (int k = 0; k < 3; k++) {
        memcpy(at + 8, &bad[k], 4);
        reseal(s, n);
        if (tt_world_restore(w, s, n) != TT_EINVAL || tt_world_load(s, n) != NULL) {
            tt_test_fail(__FILE__, __LINE__, "generation 0x%x accepted", bad[k]);
            break;
        }
        ENSURE(tt_world_hash(w) == h);
    }
    ENSURE(tt_particle_get_mass(w, b, &(double){0}) == TT_OK);
    free(s);
    tt_world_destroy(w);
}

TEST(hash_covers_collision_filters_shape_points_and_free_lists)
{
    /* before the hash was the stream's, each of these pairs hashed alike */
    tt_world *w1 = tt_world_create(NULL), *w2 = tt_world_create(NULL);
    tt_particle_def pd = tt_particle_def_default();
    tt_particle p1 = tt_particle_create(w1, &pd), p2 = tt_particle_create(w2, &pd);
    ENSURE(tt_world_hash(w1) == tt_world_hash(w2)); /* worlds differ in tag only */
    tt_particle_set_filter(w2, p2, 1, 0xFFFE);
    ENSURE(tt_world_hash(w1) != tt_world_hash(w2));
    tt_particle_set_filter(w2, p2, 1, 0xFFFF);
    ENSURE(tt_world_hash(w1) == tt_world_hash(w2));
    /* free lists: the same live particles, slots freed in another order */
    tt_particle q1 = tt_particle_create(w1, &pd), q2 = tt_particle_create(w2, &pd);
    tt_particle_destroy(w1, p1);
    tt_particle_destroy(w1, q1);
    tt_particle_destroy(w2, q2);
    tt_particle_destroy(w2, p2);
    ENSURE(tt_world_hash(w1) != tt_world_hash(w2));
    tt_world_destroy(w1);
    tt_world_destroy(w2);
    static const tt_vec2 c1[] = {{0, 0}, {1, 0}, {2, 1}}, c2[] = {{0, 0}, {1, 0}, {2, 2}};
    tt_world *a = tt_world_create(NULL), *b = tt_world_create(NULL);
    tt_shape_def sd = tt_shape_def_default();
    sd.type = TT_SHAPE_CHAIN;
    sd.count = 3;
    sd.points = c1;
    ENSURE(tt_shape_create(a, &sd).gen);
    sd.points = c2;
    ENSURE(tt_shape_create(b, &sd).gen);
    ENSURE(tt_world_hash(a) != tt_world_hash(b));
    tt_world_destroy(a);
    tt_world_destroy(b);
}

TEST(snapshot_restore_is_exact_for_every_integrator_with_contacts)
{
    /* the velocity integrators carry the last substep's end positions into the next step */
    for (int i = 0; i < TT_INTEGRATOR_COUNT; i++) {
        scene sc;
        ENSURE(scene_build(&sc, SCENE_POUR));
        ENSURE_OK(tt_world_set_integrator(sc.w, (tt_integrator)i));
        ENSURE_OK(tt_world_set_substeps(sc.w, 2));
        run(&sc, 30);
        size_t n;
        unsigned char *b = scene_save(sc.w, &n);
        ENSURE(b);
        run(&sc, 200);
        uint64_t h1 = tt_world_hash(sc.w);
        ENSURE_OK(tt_world_restore(sc.w, b, n));
        run(&sc, 200);
        ENSURE(tt_world_hash(sc.w) == h1);
        free(b);
        tt_world_destroy(sc.w);
    }
}

TEST(snapshot_between_a_shape_move_and_the_step_keeps_the_shapes_path)
{
    /* a kinematic box moved by the script travels from where the last step
     * left it across the next step's substeps, carrying what rests on it:
     * that start is state */
    tt_world *w = tt_world_create(NULL);
    tt_world_set_substeps(w, 4);
    tt_shape_def sd = tt_shape_def_default();
    sd.type = TT_SHAPE_BOX;
    sd.half_extents = (tt_vec2){2, 0.5};
    sd.friction_static = sd.friction_kinetic = 1.0;
    tt_shape box = tt_shape_create(w, &sd);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.25;
    pd.position = (tt_vec2){0, 0.75};
    tt_particle p = tt_particle_create(w, &pd);
    for (int s = 0; s < 30; s++) tt_world_step(w, 1.0 / 60);
    ENSURE_OK(tt_shape_set_transform(w, box, (tt_vec2){0.05, 0}, 0));
    size_t n;
    unsigned char *b = scene_save(w, &n);
    ENSURE(b);
    tt_world_step(w, 1.0 / 60);
    tt_vec2 v1, v2;
    ENSURE_OK(tt_particle_get_velocity(w, p, &v1));
    uint64_t h1 = tt_world_hash(w);
    ENSURE(v1.x > 0.05); /* friction drags it along with the box */
    ENSURE_OK(tt_world_restore(w, b, n));
    tt_world_step(w, 1.0 / 60);
    ENSURE_OK(tt_particle_get_velocity(w, p, &v2));
    ENSURE(v2.x == v1.x);
    ENSURE(tt_world_hash(w) == h1);
    free(b);
    tt_world_destroy(w);
}

/* A world steps as a copy loaded from its own snapshot does (found by the
 * replay journal's random session): a removed particle's slot kept its
 * position, velocity and radius in the live world, while the stream holds
 * zeros for a dead slot; with symplectic Euler at 2 substeps the two
 * differed from the first step after the removal. */
TEST(a_world_with_a_removed_particle_steps_as_its_loaded_copy)
{
    tt_world_def wd = tt_world_def_default();
    wd.integrator = TT_SYMPLECTIC_EULER;
    wd.substeps = 2;
    wd.iterations = 5;
    tt_world *w = tt_world_create(&wd);
    tt_collision_settings cs = tt_collision_settings_default();
    cs.friction_static = cs.friction_kinetic = 0.3;
    tt_world_set_collision(w, &cs);
    tt_shape_def sd = tt_shape_def_default();
    sd.type = TT_SHAPE_SEGMENT;
    sd.a = (tt_vec2){-10, 0};
    sd.b = (tt_vec2){10, 0};
    tt_shape_create(w, &sd);
    tt_particle ps[10];
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.3;
    for (int i = 0; i < 10; i++) {
        pd.position = (tt_vec2){-5 + i, 3 + i % 3};
        ps[i] = tt_particle_create(w, &pd);
    }
    for (int s = 0; s < 5; s++) tt_world_step(w, 1.0 / 60);
    ENSURE(tt_particle_destroy(w, ps[2]) == TT_OK);
    tt_world *copy = scene_reload(w);
    ENSURE(copy != NULL);
    for (int s = 0; s < 30; s++) {
        tt_world_step(w, 1.0 / 60);
        tt_world_step(copy, 1.0 / 60);
        ENSURE(tt_world_hash(w) == tt_world_hash(copy));
    }
    tt_world_destroy(copy);
    tt_world_destroy(w);
}

/* A load that runs out of memory at any allocation is refused cleanly:
 * no crash, no leak, and a restore leaves the world as it was. Found by
 * the replay journal's test: a world with shapes whose shape array could
 * not be allocated was freed through a NULL array (tt__shapes_free). */
TEST(snapshot_load_and_restore_out_of_memory_at_each_allocation_are_refused_cleanly)
{
    for (int kind = 0; kind < SCENE_COUNT; kind++) {
        scene sc;
        ENSURE(scene_build(&sc, (scene_kind)kind));
        for (int s = 0; s < 5; s++) scene_step(&sc);
        size_t n = 0;
        unsigned char *b = scene_save(sc.w, &n);
        ENSURE(b);
        const uint64_t h = tt_world_hash(sc.w);
        for (long k = 0;; k++) {
            tt_test_alloc_fail_from(k);
            tt_world *w = tt_world_load(b, n);
            const bool refused = tt_test_alloc_ok();
            if (w) {
                ENSURE(tt_world_hash(w) == h);
                tt_world_destroy(w);
                break;
            }
            ENSURE(refused);
        }
        for (long k = 0;; k++) {
            tt_test_alloc_fail_from(k);
            tt_result r = tt_world_restore(sc.w, b, n);
            tt_test_alloc_ok();
            ENSURE(tt_world_hash(sc.w) == h);
            if (r == TT_OK) break;
        }
        free(b);
        tt_world_destroy(sc.w);
    }
}

/* Found by the C fuzzer (seed 1796198215, call 2459: a journal saved to a
 * file did not load): a particle may drift past the largest coordinate the
 * API takes (up to the divergence guard), and a pin made where it is keeps
 * that anchor; the loader refused every value past 1e12, so such a world
 * saved but did not load. A spring made between such particles keeps their
 * distance as its rest length: the loader refused it past 3e12 (the C
 * fuzzer again, seed 20261209, call 681221). */
TEST(a_world_with_a_pin_anchored_past_the_largest_coordinate_saves_and_loads)
{
    tt_world_def wd = tt_world_def_default();
    wd.gravity = (tt_vec2){0, 0};
    tt_world *w = tt_world_create(&wd);
    tt_particle_def pd = tt_particle_def_default();
    pd.velocity = (tt_vec2){1e12, 0};
    tt_particle p = tt_particle_create(w, &pd);
    pd.velocity = (tt_vec2){0, 0};
    tt_particle q = tt_particle_create(w, &pd);
    for (int s = 0; s < 10; s++) ENSURE(tt_world_step(w, 1.0) == TT_OK);
    tt_vec2 x;
    tt_particle_get_position(w, p, &x);
    ENSURE(x.x > 5e12);
    tt_pin_def pin = tt_pin_def_default();
    pin.particle = p;
    ENSURE(tt_pin_create(w, &pin).gen != 0);
    tt_distance_def dd = tt_distance_def_default();
    dd.a = p;
    dd.b = q;
    ENSURE(tt_distance_create(w, &dd).gen != 0);
    tt_spring_def sd = tt_spring_def_default(); /* rest length: their distance, > 5e12 m */
    sd.a = p;
    sd.b = q;
    ENSURE(tt_spring_create(w, &sd).gen != 0);
    tt_world *copy = scene_reload(w);
    ENSURE(copy != NULL);
    if (copy) ENSURE(tt_world_hash(copy) == tt_world_hash(w));
    tt_world_destroy(copy);
    tt_world_destroy(w);
}
