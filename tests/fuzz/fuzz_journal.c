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

#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

typedef struct buf {
    unsigned char *p;
    size_t n;
} buf;

static uint64_t rng;
static uint64_t next(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return rng * 0x2545F4914F6CDD1Dull;
}
static size_t below(size_t n) { return n ? (size_t)(next() % n) : 0; }

/* A short recorded session of scene k (its driver's calls make changes). */
static buf record(scene_kind k, int steps)
{
    buf b = {NULL, 0};
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
static void reseal(buf *b)
{
    uint64_t snap;
    if (b->n < 56 + 32) return;
    memcpy(&snap, b->p + 40, 8);
    if (snap < 32 || snap > b->n - 56) return;
    uint64_t body = snap - 32, sum = tt__hash_bytes(b->p + 56 + 32, (size_t)body);
    memcpy(b->p + 56 + 16, &body, 8);
    memcpy(b->p + 56 + 24, &sum, 8);
}

static void put_field(buf *b)
{
    static const uint64_t vals[] = {0, 1, 2, 55, 56, 57, 0xFFFFFFFFull, 0x7FFFFFFFFFFFFFFFull, ~0ull, 1u << 30, (1u << 30) + 1,
                                    0x3FF0000000000000ull, 0x7FF8000000000000ull, 0x7FF0000000000000ull};
    if (b->n < 16) return;
    const uint64_t v = vals[below(sizeof vals / sizeof vals[0])];
    const size_t at = next() & 1 ? 16 + 8 * below(5) : below(b->n - 8); /* a header count, or anywhere */
    if (at + 8 <= b->n) memcpy(b->p + at, &v, 8);
}

static buf mutate(const buf *base, const buf *other)
{
    buf b = {malloc(base->n + other->n + 64), base->n};
    memcpy(b.p, base->p, base->n);
    for (int k = 1 + (int)below(3); k > 0; k--) {
        size_t at = below(b.n), len = 1 + below(16);
        if (at + len > b.n) len = b.n - at;
        switch (below(6)) {
        case 0: b.p[below(b.n)] ^= (unsigned char)(1u << below(8)); break;
        case 1: put_field(&b); break;
        case 2: /* delete */
            memmove(b.p + at, b.p + at + len, b.n - at - len);
            b.n -= len;
            break;
        case 3: /* repeat */
            if (b.n + len <= base->n + other->n) {
                memmove(b.p + at + len, b.p + at, b.n - at);
                b.n += len;
            }
            break;
        case 4: { /* splice from the other journal */
            size_t from = below(other->n);
            if (from + len > other->n) len = other->n - from;
            if (at + len <= b.n) memcpy(b.p + at, other->p + from, len);
            break;
        }
        default: b.n = below(b.n); break; /* cut short */
        }
        if (b.n == 0) break;
    }
    if (below(10)) reseal(&b);
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

static bool one(const buf *corpus, int n, unsigned long it, uint32_t *accepted, const char *path)
{
    const buf *base = &corpus[below((size_t)n)], *other = &corpus[below((size_t)n)];
    buf m = mutate(base, other);
    tt_journal *j;
    if (below(8) == 0) { /* through a file: the same bytes behind a valid header */
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
    const char *secs = getenv("FUZZ_JOURNAL_SECONDS"), *seed = getenv("FUZZ_SEED"), *its = getenv("FUZZ_JOURNAL_ITERATIONS");
    const double seconds = secs ? atof(secs) : 0.0;
    const unsigned long max_it = its ? strtoul(its, NULL, 10) : seconds > 0 ? (unsigned long)-1 : 200;
    rng = (seed && *seed ? strtoull(seed, NULL, 10) : 1) ^ 0x9E3779B97F4A7C15ull;
    if (!rng) rng = 1;
    buf corpus[2] = {record(SCENE_ZOO, 12), record(SCENE_INTEGRATORS, 12)};
    ENSURE(corpus[0].p && corpus[1].p);
    char path[128];
    snprintf(path, sizeof path, "/tmp/tether_fuzz_journal_%ld.ttj", (long)getpid());
    uint32_t accepted = 0;
    unsigned long it = 0;
    const clock_t t0 = clock();
    for (; it < max_it; it++) {
        if (seconds > 0 && (it & 15) == 0 && (double)(clock() - t0) / CLOCKS_PER_SEC > seconds) break;
        if (!one(corpus, 2, it, &accepted, path)) {
            printf("    fuzz_journal: failed at journal %lu; replay: FUZZ_SEED=%s FUZZ_JOURNAL_ITERATIONS=%lu build/test_c fuzz_journal_reader\n",
                   it, seed ? seed : "1", it + 1);
            break;
        }
    }
    printf("    fuzz_journal: %lu journals, %u accepted, seed %s\n", it, accepted, seed && *seed ? seed : "1");
    remove(path);
    free(corpus[0].p);
    free(corpus[1].p);
}
