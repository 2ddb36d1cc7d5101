/* tests/fuzz/fuzz_c_stream.c — the C fuzzer's wrappers of the snapshot
 * stream (tt_world_save, tt_world_restore, tt_world_load): buffers of every
 * size, whole and damaged streams. A refused
 * restore must leave the world as it was (the harness checks its hash); a
 * load that succeeds gives a world whose hash is the saved one's. */
#include "fuzz_c.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* A stream of world w (NULL on no memory), *n its size. */
static unsigned char *stream_of(tt_world *w, size_t *n)
{
    *n = 0;
    if (tt_world_save(w, NULL, 0, n) != TT_OK && *n == 0) return NULL;
    unsigned char *b = malloc(*n ? *n : 1);
    size_t m = 0;
    if (b && tt_world_save(w, b, *n, &m) != TT_OK) {
        free(b);
        return NULL;
    }
    return b;
}

/* Flips a few bytes, or cuts the stream short, now and then. */
static void damage(fz *f, unsigned char *b, size_t *n)
{
    if (*n == 0 || !fz_chance(f, 40)) return;
    if (fz_chance(f, 30)) {
        *n = fz_below(f, (uint32_t)(*n < UINT32_MAX ? *n : UINT32_MAX));
        return;
    }
    for (unsigned k = 1 + fz_below(f, 4); k > 0; k--) b[fz_below(f, (uint32_t)(*n < UINT32_MAX ? *n : UINT32_MAX))] ^= (unsigned char)(1u << fz_below(f, 8));
}

static void c_world_save(fz *f)
{
    tt_world *w = fz_world_pick(f);
    f->readonly = true;
    size_t need = 0;
    tt_world_save(w, NULL, 0, &need);
    const uint32_t how = fz_below(f, 4); /* size query, too small, exact, NULL size */
    size_t cap = how == 0 ? 0 : how == 1 && need ? need - 1 : need;
    unsigned char *b = cap ? malloc(cap) : NULL;
    size_t got = 0;
    fz_log(f, "tt_world_save(%s, %s, %zu, %s)", fz_wn(f, w), b ? "buf" : "NULL", cap, how == 3 ? "NULL" : "&size");
    FZ_HIT(f, tt_world_save);
    tt_result r = tt_world_save(w, b, cap, how == 3 ? NULL : &got);
    fz_res(f, r);
    if (r == TT_OK && how == 2 && got != need) fz_fail(f, "tt_world_save wrote %zu bytes of %zu", got, need);
    free(b);
}

static void c_world_restore(fz *f)
{
    /* Its own stream, whole or damaged: a world restored from another takes
     * that world's tag and handles (tests/core covers it), which the
     * harness's record of whose handle is whose would not follow. */
    tt_world *w = fz_world_pick(f), *from = w;
    size_t n = 0;
    unsigned char *b = from ? stream_of(from, &n) : NULL;
    if (b) damage(f, b, &n);
    fz_log(f, "tt_world_restore(%s, %s, %zu)", fz_wn(f, w), b ? "stream" : "NULL", n);
    FZ_HIT(f, tt_world_restore);
    tt_result r = tt_world_restore(w, b, n);
    fz_res(f, r);
    free(b);
}

static void c_world_load(fz *f)
{
    tt_world *from = fz_world_pick(f);
    size_t n = 0;
    unsigned char *b = from ? stream_of(from, &n) : NULL;
    const size_t whole = n;
    if (b) damage(f, b, &n);
    f->readonly = true;
    fz_log(f, "tt_world_load(%s, %zu)", b ? "stream" : "NULL", n);
    FZ_HIT(f, tt_world_load);
    tt_world *w = tt_world_load(b, n);
    fz_log_more(f, " -> %s", w ? "world" : "NULL");
    f->failed = w == NULL; /* what the harness checks against a NULL source world */
    if (w && from && n == whole && tt_world_hash(w) != tt_world_hash(from))
        fz_fail(f, "a world loaded from a stream hashes unlike the world saved");
    tt_world_destroy(w);
    free(b);
}

/* ---- files: a world's own file, whole or damaged after writing ---------- */

static char file_path[128];
static void remove_file(void) { remove(file_path); }

static const char *fz_file_path(void)
{
    if (!file_path[0]) {
        snprintf(file_path, sizeof file_path, "/tmp/tether_fuzz_c_%ld.tts", (long)getpid());
        atexit(remove_file);
    }
    return file_path;
}

/* Saves w's file (NULL w: no file), then damages it now and then. */
static void file_of(fz *f, tt_world *w)
{
    const char *path = fz_file_path();
    if (!w || tt_world_save_file(w, path) != TT_OK) {
        remove(path);
        return;
    }
    FILE *fp = fopen(path, "rb");
    if (!fp) return;
    unsigned char b[1 << 16];
    size_t n = fread(b, 1, sizeof b, fp);
    fclose(fp);
    if (n == sizeof b || !fz_chance(f, 50)) return; /* a big file stays whole */
    damage(f, b, &n);
    fp = fopen(path, "wb");
    if (!fp) return;
    fwrite(b, 1, n, fp);
    fclose(fp);
}

static void c_world_save_file(fz *f)
{
    tt_world *w = fz_world_pick(f);
    f->readonly = true;
    const bool bad = fz_chance(f, 10);
    const char *path = bad ? (fz_chance(f, 50) ? "" : "/nonexistent-dir/x.tts") : fz_file_path();
    fz_log(f, "tt_world_save_file(%s, \"%s\")", fz_wn(f, w), path);
    FZ_HIT(f, tt_world_save_file);
    fz_res(f, tt_world_save_file(w, path));
}

static void c_world_restore_file(fz *f)
{
    tt_world *w = fz_world_pick(f); /* its own file: see c_world_restore */
    file_of(f, w);
    const char *path = fz_chance(f, 5) ? NULL : fz_file_path();
    fz_log(f, "tt_world_restore_file(%s, %s)", fz_wn(f, w), path ? "file" : "NULL");
    FZ_HIT(f, tt_world_restore_file);
    fz_res(f, tt_world_restore_file(w, path));
}

static void c_world_load_file(fz *f)
{
    tt_world *from = fz_world_pick(f);
    file_of(f, from);
    f->readonly = true;
    fz_log(f, "tt_world_load_file(file)");
    FZ_HIT(f, tt_world_load_file);
    tt_world *w = tt_world_load_file(fz_file_path());
    fz_log_more(f, " -> %s", w ? "world" : "NULL");
    f->failed = w == NULL;
    tt_world_destroy(w);
}

const fz_entry fz_stream_entries[] = {
    { "tt_world_save_file", c_world_save_file, 1 },
    { "tt_world_restore_file", c_world_restore_file, 1 },
    { "tt_world_load_file", c_world_load_file, 1 },
    { "tt_world_save", c_world_save, 2 },
    { "tt_world_restore", c_world_restore, 2 },
    { "tt_world_load", c_world_load, 1 },
    { NULL, NULL, 0 },
};
