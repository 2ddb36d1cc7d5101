/* tether — a fuzzer of the replay journal reader (tt_journal_load, and
 * tt_journal_load_file through the snapshot files' header): valid journals
 * of two recorded sessions, mutated (bits flipped, header fields and
 * lengths set to hostile numbers, bytes deleted, repeated, spliced from
 * the other journal, cut short), the inner snapshot's checksum mostly
 * resealed so that the mutation reaches the record's reader. Each must be
 * refused, or be a journal whose replay into a fresh world either plays
 * or refuses a step (a change that no longer decodes to a valid world)
 * with that world left as it was, and whose bytes save and load again.
 *
 *   build/test_c fuzz_journal_reader                       (make test: 200 journals, seed 1)
 *   FUZZ_JOURNAL_SECONDS=30 FUZZ_SEED=n build/test_c fuzz_journal_reader   (make fuzz)
 *   FUZZ_JOURNAL_ITERATIONS=k: stop after k journals (to replay a failure) */
#include "test.h"
#include "core/scenes.h"
#include "core/snapfile.h" /* tt__file_write: a mutated payload behind a valid file header */
#include "core/stream.h"   /* tt__hash_bytes: to forge the snapshot's checksum */
#include "fuzz_bytes.h"

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* A short recorded session of scene k (its driver's calls make changes). */
static fuzz_buf record(scene_kind k, int steps)
{
    fuzz_buf b = {NULL, 0};
    scene sc;
    if (!scene_build(&sc, k)) return b;
    tt_journal *j = tt_journal_start(sc.w, &(tt_journal_def){.max_bytes = 1 << 24});
    for (int s = 0; j && s < steps; s++) scene_step(&sc);
    if (j && tt_journal_save(j, NULL, 0, &b.n) == TT_ENOMEM && (b.p = malloc(b.n)) && tt_journal_save(j, b.p, b.n, &b.n) != TT_OK) {
        free(b.p);
        b.p = NULL;
    }
    tt_journal_destroy(j);
    tt_world_destroy(sc.w);
    return b;
}

/* The snapshot inside a journal, its checksum made to match its (mutated) body. */
static void reseal(fuzz_buf *b)
{
    uint64_t snap;
    if (b->n < 56 + 32) return;
    memcpy(&snap, b->p + 40, 8);
    if (snap < 32 || snap > b->n - 56) return;
    uint64_t body = snap - 32, sum = tt__hash_bytes(b->p + 56 + 32, (size_t)body);
    memcpy(b->p + 56 + 16, &body, 8);
    memcpy(b->p + 56 + 24, &sum, 8);
}

static void put_field(fuzz_buf *b)
{
    static const uint64_t vals[] = {0, 1, 2, 55, 56, 57, 0xFFFFFFFFull, 0x7FFFFFFFFFFFFFFFull, ~0ull, 1u << 30, (1u << 30) + 1,
                                    0x3FF0000000000000ull, 0x7FF8000000000000ull, 0x7FF0000000000000ull};
    if (b->n < 16) return;
    const uint64_t v = vals[fuzz_below(sizeof vals / sizeof vals[0])];
    const size_t at = fuzz_next() & 1 ? 16 + 8 * fuzz_below(5) : fuzz_below(b->n - 8); /* a header count, or anywhere */
    if (at + 8 <= b->n) memcpy(b->p + at, &v, 8);
}

/* A copy of base, mutated once or a few times, its inner snapshot mostly resealed. */
static fuzz_buf mutate(const fuzz_buf *base, const fuzz_buf *other)
{
    fuzz_buf b = fuzz_mutate(base, other, 0, put_field);
    if (b.p && fuzz_below(10)) reseal(&b);
    return b;
}

/* An accepted journal: replays (steps that play, or that are refused with
 * the world unchanged), and saves and loads again. */
static bool check_accepted(tt_journal *j, unsigned long it)
{
    tt_world *w = tt_world_create(NULL);
    bool ok = w != NULL;
    if (ok && tt_journal_replay_begin(j, w) == TT_OK) {
        for (int s = 0; s < 40; s++) {
            const uint64_t h = tt_world_hash(w);
            tt_replay r;
            tt_result res = tt_journal_replay_step(j, w, &r);
            if (res == TT_OK && r == TT_REPLAY_END) break;
            if (res != TT_OK) {
                ok = tt_world_hash(w) == h;
                if (!ok) tt_test_fail(__FILE__, __LINE__, "journal %lu: a refused replay step changed the world", it);
                break;
            }
        }
    }
    size_t n = 0;
    tt_journal_save(j, NULL, 0, &n);
    unsigned char *b = malloc(n);
    tt_journal *k = b && tt_journal_save(j, b, n, &n) == TT_OK ? tt_journal_load(b, n) : NULL;
    if (!k) {
        ok = false;
        tt_test_fail(__FILE__, __LINE__, "journal %lu: an accepted journal does not load again: %s", it, tt_last_error(NULL));
    }
    tt_journal_destroy(k);
    free(b);
    tt_world_destroy(w);
    return ok;
}

typedef struct journals {
    fuzz_buf corpus[2];
    char path[128];
} journals;

static bool one(void *ctx, unsigned long it, uint32_t *accepted)
{
    const fuzz_buf *corpus = ((journals *)ctx)->corpus;
    const char *path = ((journals *)ctx)->path;
    const fuzz_buf *base = &corpus[fuzz_below(2)], *other = &corpus[fuzz_below(2)];
    fuzz_buf m = mutate(base, other);
    if (!m.p) return false;
    tt_journal *j;
    if (fuzz_below(8) == 0) { /* through a file: the same bytes behind a valid header */
        char why[200];
        j = tt__file_write(path, TT__FILE_JOURNAL, m.p, m.n, why, sizeof why) ? tt_journal_load_file(path) : NULL;
    } else {
        j = tt_journal_load(m.p, m.n);
    }
    bool ok = true;
    if (j) {
        (*accepted)++;
        ok = check_accepted(j, it);
    }
    tt_journal_destroy(j);
    free(m.p);
    return ok;
}

TEST(fuzz_journal_reader)
{
    journals js = {{record(SCENE_ZOO, 12), record(SCENE_INTEGRATORS, 12)}, {0}};
    ENSURE(js.corpus[0].p && js.corpus[1].p);
    snprintf(js.path, sizeof js.path, "/tmp/tether_fuzz_journal_%ld.ttj", (long)getpid());
    fuzz_run("journal", "fuzz_journal_reader", 200, one, &js);
    remove(js.path);
    free(js.corpus[0].p);
    free(js.corpus[1].p);
}
