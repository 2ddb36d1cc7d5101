/* tether — snapshot files (src/core/snapfile.c): a saved file restores the
 * same world in place and into a new world; a truncated, corrupted, padded,
 * foreign, other-version or missing file is refused with a message naming
 * the file and the world unchanged (its hash equal before and after). */
#include "test.h"
#include "core/scenes.h"
#include "core/snapfile.h" /* tt__file_write: to write what the Lua binding writes */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* A path of this test's own in /tmp (the pid keeps parallel runs apart). */
static const char *tmp_path(const char *name)
{
    static char p[4][256];
    static int k;
    k = (k + 1) % 4;
    snprintf(p[k], sizeof p[k], "/tmp/tether_test_%ld_%s", (long)getpid(), name);
    return p[k];
}

static unsigned char *read_all(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long len = ftell(f);
    fseek(f, 0, SEEK_SET);
    unsigned char *b = malloc(len > 0 ? (size_t)len : 1);
    *n = b ? fread(b, 1, (size_t)len, f) : 0;
    fclose(f);
    return b;
}

static bool write_all(const char *path, const void *b, size_t n)
{
    FILE *f = fopen(path, "wb");
    if (!f) return false;
    bool ok = fwrite(b, 1, n, f) == n;
    return fclose(f) == 0 && ok;
}

TEST(snapfile_round_trip_in_place_and_into_a_new_world)
{
    scene sc;
    ENSURE(scene_build(&sc, SCENE_POUR));
    for (int s = 0; s < 60; s++) scene_step(&sc);
    const char *path = tmp_path("round.tts");
    ENSURE_OK(tt_world_save_file(sc.w, path));
    const uint64_t h60 = tt_world_hash(sc.w);
    for (int s = 0; s < 60; s++) scene_step(&sc);
    const uint64_t h120 = tt_world_hash(sc.w);
    ENSURE(h120 != h60);
    /* in place: back to step 60, and the next 60 steps are the same again */
    ENSURE_OK(tt_world_restore_file(sc.w, path));
    ENSURE(tt_world_hash(sc.w) == h60);
    for (int s = 0; s < 60; s++) scene_step(&sc);
    ENSURE(tt_world_hash(sc.w) == h120);
    /* into a new world: the same state, the same future, the saved handles valid */
    tt_world *w = tt_world_load_file(path);
    ENSURE(w);
    ENSURE(tt_world_hash(w) == h60);
    tt_world *orig = sc.w;
    sc.w = w;
    for (int s = 0; s < 60; s++) scene_step(&sc);
    ENSURE(tt_world_hash(w) == h120);
    tt_world_destroy(w);
    tt_world_destroy(orig);
    remove(path);
}

/* Each damaged copy of a good file is refused by both readers, with the
 * message given, and the world's hash does not move. */
static void refused(tt_world *w, const char *path, const char *expect)
{
    const uint64_t h = tt_world_hash(w);
    ENSURE(tt_world_restore_file(w, path) == TT_EINVAL);
    if (!strstr(tt_last_error(w), expect) || !strstr(tt_last_error(w), "tt_world_restore_file"))
        tt_test_fail(__FILE__, __LINE__, "'%s' lacks '%s'", tt_last_error(w), expect);
    ENSURE(tt_world_hash(w) == h);
    ENSURE(tt_world_load_file(path) == NULL);
    if (!strstr(tt_last_error(NULL), expect)) tt_test_fail(__FILE__, __LINE__, "'%s' lacks '%s'", tt_last_error(NULL), expect);
}

TEST(snapfile_truncated_corrupted_foreign_or_missing_files_are_refused_with_the_world_unchanged)
{
    scene sc;
    ENSURE(scene_build(&sc, SCENE_ZOO));
    for (int s = 0; s < 30; s++) scene_step(&sc);
    const char *good = tmp_path("good.tts"), *bad = tmp_path("bad.tts");
    ENSURE_OK(tt_world_save_file(sc.w, good));
    for (int s = 0; s < 30; s++) scene_step(&sc); /* the world is elsewhere now: a restore would show */
    size_t n;
    unsigned char *b = read_all(good, &n);
    ENSURE(b && n > 100);

    refused(sc.w, tmp_path("does-not-exist.tts"), "cannot open");
    ENSURE(write_all(bad, b, n - 1));
    refused(sc.w, bad, "truncated or padded");
    ENSURE(write_all(bad, b, 20));
    refused(sc.w, bad, "truncated");
    unsigned char *pad = malloc(n + 1);
    ENSURE(pad);
    memcpy(pad, b, n);
    pad[n] = 0;
    ENSURE(write_all(bad, pad, n + 1));
    refused(sc.w, bad, "truncated or padded");
    free(pad);
    for (size_t at = 0; at < n; at += n / 37 + 1) { /* a bit flipped anywhere but the signature */
        if (at < 8) continue;
        b[at] ^= 0x10;
        ENSURE(write_all(bad, b, n));
        refused(sc.w, bad, at < 16 ? "format version" : at >= 22 && at < 32 ? "" : "checksum");
        b[at] ^= 0x10;
    }
    b[8] = 2; /* a newer format */
    ENSURE(write_all(bad, b, n));
    refused(sc.w, bad, "file format version 2 (written by tether 0.1.0)");
    b[8] = 1;
    ENSURE(write_all(bad, "GIF89a, not a world at all..........................................", 64));
    refused(sc.w, bad, "not a tether snapshot file");
    /* an unwritable place gives an error, not a torn file */
    ENSURE(tt_world_save_file(sc.w, "/nonexistent-dir/x.tts") == TT_EINVAL);
    ENSURE(strstr(tt_last_error(sc.w), "cannot open"));
    ENSURE(tt_world_save_file(sc.w, "") == TT_EINVAL);
    ENSURE(tt_world_restore_file(sc.w, NULL) == TT_EINVAL);
    ENSURE(tt_world_save_file(NULL, good) == TT_EINVAL);
    /* and the good file still restores */
    ENSURE_OK(tt_world_restore_file(sc.w, good));
    free(b);
    tt_world_destroy(sc.w);
    remove(good);
    remove(bad);
}

TEST(snapfile_a_file_saved_from_lua_with_user_values_loads_in_c)
{
    tt_world *w = scene_small_world();
    ENSURE(w);
    size_t n = 0;
    tt_world_save(w, NULL, 0, &n);
    unsigned char *env = malloc(16 + n + 5);
    ENSURE(env);
    const uint32_t version = 1;
    const uint64_t len = n;
    memcpy(env, "TTLU", 4);
    memcpy(env + 4, &version, 4);
    memcpy(env + 8, &len, 8);
    ENSURE_OK(tt_world_save(w, env + 16, n, &n));
    memcpy(env + 16 + n, "users", 5); /* the Lua values, opaque to C */
    const char *path = tmp_path("lua.tts");
    char why[300];
    ENSURE(tt__file_write(path, TT__FILE_LUA, env, 16 + n + 5, why, sizeof why));
    tt_world *c = tt_world_load_file(path);
    ENSURE(c && tt_world_hash(c) == tt_world_hash(w));
    /* an envelope whose stream length runs past the payload holds no snapshot */
    const uint64_t over = n + 6;
    memcpy(env + 8, &over, 8);
    ENSURE(tt__file_write(path, TT__FILE_LUA, env, 16 + n + 5, why, sizeof why));
    ENSURE(tt_world_restore_file(c, path) == TT_EINVAL);
    ENSURE(strstr(tt_last_error(c), "holds no snapshot"));
    free(env);
    tt_world_destroy(c);
    tt_world_destroy(w);
    remove(path);
}

/* Found by the rewind ring's fuzz wrapper: an area constraint made from the
 * current positions of particles 1e7 m apart has a rest area of 5e13 m²,
 * which the stream reader refused as out of range (±1e12), so the world
 * saved but its own stream did not load. */
TEST(snapshot_a_large_area_from_current_positions_loads_again)
{
    tt_world_def wd = tt_world_def_default();
    tt_world *w = tt_world_create(&wd);
    ENSURE(w);
    tt_particle p[3];
    const tt_vec2 at[3] = {{0, 0}, {1e7, 0}, {0, 1e7}};
    for (int i = 0; i < 3; i++) {
        tt_particle_def pd = tt_particle_def_default();
        pd.position = at[i];
        p[i] = tt_particle_create(w, &pd);
    }
    tt_area_def ad = tt_area_def_default();
    ad.particles = p;
    ad.count = 3;
    ENSURE(tt_constraint_is_valid(w, tt_area_create(w, &ad)));
    tt_world *c = scene_reload(w);
    ENSURE(c && tt_world_hash(c) == tt_world_hash(w));
    tt_world_destroy(c);
    tt_world_destroy(w);
}

/* Found by the rewind ring's fuzz wrapper: a segment made with radius
 * INFINITY (a field segments do not use) was accepted, so the world held an
 * Inf, saved it, and its own stream did not load ("shape radius is inf").
 * NaN and Inf are refused at the door, in every field. */
TEST(shape_create_refuses_inf_and_nan_even_in_fields_its_type_does_not_use)
{
    tt_world_def wd = tt_world_def_default();
    tt_world *w = tt_world_create(&wd);
    ENSURE(w);
    tt_shape_def d = tt_shape_def_default();
    d.type = TT_SHAPE_SEGMENT;
    d.a = (tt_vec2){-1, 0};
    d.b = (tt_vec2){1, 0};
    d.radius = INFINITY;
    ENSURE(!tt_shape_is_valid(w, tt_shape_create(w, &d)));
    ENSURE(strstr(tt_last_error(w), "finite"));
    d.radius = 0.5;
    d.half_extents.y = NAN;
    ENSURE(!tt_shape_is_valid(w, tt_shape_create(w, &d)));
    d.half_extents.y = 1;
    ENSURE(tt_shape_is_valid(w, tt_shape_create(w, &d)));
    tt_world *c = scene_reload(w);
    ENSURE(c);
    tt_world_destroy(c);
    tt_world_destroy(w);
}

/* Found by the rewind ring's fuzz wrapper: tt_particle_set_material takes
 * friction up to 1e30, the stream reader only up to 1e12, so the world's
 * own stream did not load ("particle 0: material 1e+15"). */
TEST(snapshot_a_particle_friction_the_setter_takes_loads_again)
{
    tt_world_def wd = tt_world_def_default();
    tt_world *w = tt_world_create(&wd);
    ENSURE(w);
    tt_particle_def pd = tt_particle_def_default();
    tt_particle p = tt_particle_create(w, &pd);
    ENSURE_OK(tt_particle_set_material(w, p, 0.5, 1e15, 1e30));
    tt_world *c = scene_reload(w);
    ENSURE(c && tt_world_hash(c) == tt_world_hash(w));
    tt_world_destroy(c);
    tt_world_destroy(w);
}

/* Found by the rewind ring's fuzz wrapper: a link or spring whose length is
 * taken from particles far apart (up to 2√2 × TT_MAX_VALUE) was refused by
 * the stream reader above TT_MAX_VALUE ("link rest length is 1.4945e+12"). */
TEST(snapshot_links_and_springs_as_long_as_the_world_is_wide_load_again)
{
    tt_world_def wd = tt_world_def_default();
    tt_world *w = tt_world_create(&wd);
    ENSURE(w);
    tt_particle_def pd = tt_particle_def_default();
    pd.position = (tt_vec2){-TT_MAX_VALUE, -TT_MAX_VALUE};
    tt_particle a = tt_particle_create(w, &pd);
    pd.position = (tt_vec2){TT_MAX_VALUE, TT_MAX_VALUE};
    tt_particle b = tt_particle_create(w, &pd);
    tt_distance_def dd = tt_distance_def_default();
    dd.a = a;
    dd.b = b;
    ENSURE(tt_constraint_is_valid(w, tt_distance_create(w, &dd)));
    tt_spring_def sd = tt_spring_def_default();
    sd.a = a;
    sd.b = b;
    ENSURE(tt_spring_is_valid(w, tt_spring_create(w, &sd)));
    tt_world *c = scene_reload(w);
    ENSURE(c && tt_world_hash(c) == tt_world_hash(w));
    tt_world_destroy(c);
    tt_world_destroy(w);
}
