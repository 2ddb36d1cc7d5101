/* tether — a fuzzer of the snapshot stream reader (tt_world_restore,
 * tt_world_load): valid streams of a few reference worlds, mutated (bits
 * flipped, fields set to hostile numbers and counts, bytes deleted,
 * repeated, spliced from another stream, cut short), then mostly resealed
 * with a matching length and checksum so the mutation reaches the section
 * readers. Each stream must be refused with the target world unchanged, or
 * be a valid world: every position and velocity finite and within
 * TT_DIVERGED (as restored and after stepping), it steps, saves, and its
 * stream loads again to the same hash.
 *
 *   build/test_c fuzz_stream_reader                      (make test: 300 streams, seed 1)
 *   FUZZ_STREAM_SECONDS=60 FUZZ_SEED=n build/test_c fuzz_stream_reader   (make fuzz)
 *   FUZZ_STREAM_ITERATIONS=k: stop after k streams (to replay a failure) */
#include "test.h"
#include "core/scenes.h"
#include "core/stream.h" /* tt__hash_bytes: to forge valid checksums */
#include "fuzz_bytes.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static fuzz_buf save(const tt_world *w)
{
    fuzz_buf b = {NULL, 0};
    b.p = scene_save(w, &b.n);
    return b;
}

/* Length and checksum made to match the (mutated) body. */
static void reseal(fuzz_buf *b)
{
    if (b->n < 32) return;
    uint64_t body = b->n - 32, sum = tt__hash_bytes(b->p + 32, b->n - 32);
    memcpy(b->p + 16, &body, 8);
    memcpy(b->p + 24, &sum, 8);
}

static void put_field(fuzz_buf *b)
{
    static const uint32_t u32s[] = {0, 1, 2, 3, 0xFFFFFFFFu, 0x7FFFFFFFu, 0x80000000u, 0xFFFFu, 0x10000u, 1000, 64};
    static const uint64_t f64s[] = {0x7FF8000000000000ull, 0x7FF0000000000000ull, 0xFFF0000000000000ull,
                                    0x7E37E43C8800759Cull /* 1e300 */, 0x8000000000000000ull, 1ull,
                                    0x4341C37937E08000ull /* 1e16 */, 0x3FF0000000000000ull};
    if (b->n < 40) return;
    size_t at = 32 + fuzz_below(b->n - 40);
    if (fuzz_next() & 1) memcpy(b->p + at, &u32s[fuzz_below(sizeof u32s / sizeof u32s[0])], 4);
    else memcpy(b->p + at, &f64s[fuzz_below(sizeof f64s / sizeof f64s[0])], 8);
}

/* A copy of base, mutated once or a few times past its header, mostly resealed. */
static fuzz_buf mutate(const fuzz_buf *base, const fuzz_buf *other)
{
    fuzz_buf b = fuzz_mutate(base, other, 32, put_field);
    if (b.p && fuzz_below(10)) reseal(&b);
    return b;
}

/* Every position and velocity finite and within TT_DIVERGED, the bound no
 * step leaves (the loader once held x_old to 1e3·TT_DIVERGED instead, so a
 * stream could carry |v| past it). */
static bool bounded(tt_world *w, unsigned long it, const char *when)
{
    uint32_t n = tt_world_particle_count(w);
    tt_particle *ids = malloc((n ? n : 1) * sizeof *ids);
    double *xy = malloc(2 * (size_t)(n ? n : 1) * sizeof *xy);
    bool ok = ids && xy && tt_world_list_particles(w, ids, n) == n && tt_world_read_positions(w, xy, n) == n;
    for (uint32_t i = 0; ok && i < n; i++) {
        tt_vec2 v = {0, 0};
        tt_result r = tt_particle_get_velocity(w, ids[i], &v);
        if (r != TT_OK) tt_test_fail(__FILE__, __LINE__, "stream %lu, %s: particle %u (index %u, generation %u) listed, yet refused: %s",
                                     it, when, i, ids[i].index, ids[i].gen, tt_last_error(w));
        ok = r == TT_OK && fabs(xy[2 * i]) <= TT_DIVERGED &&
             fabs(xy[2 * i + 1]) <= TT_DIVERGED && fabs(v.x) <= TT_DIVERGED && fabs(v.y) <= TT_DIVERGED;
        if (!ok)
            tt_test_fail(__FILE__, __LINE__, "stream %lu, %s: particle %u at (%g, %g), v (%g, %g): past TT_DIVERGED or not finite",
                         it, when, i, xy[2 * i], xy[2 * i + 1], v.x, v.y);
    }
    free(ids);
    free(xy);
    return ok;
}

/* An accepted world is a world: its particles are within the guard, it
 * steps (kept short), saves, and loads again alike. */
static bool check_accepted(tt_world *w, unsigned long it)
{
    if (!bounded(w, it, "as restored")) return false;
    if (tt_world_get_substeps(w) > 4) tt_world_set_substeps(w, 4);
    if (tt_world_get_iterations(w) > 20) tt_world_set_iterations(w, 20);
    for (int s = 0; s < 3; s++) tt_world_step(w, 1.0 / 60);
    if (!bounded(w, it, "after 3 steps")) return false;
    fuzz_buf again = save(w);
    if (!again.p) return false;
    tt_world *c = tt_world_load(again.p, again.n);
    bool ok = c && tt_world_hash(c) == tt_world_hash(w);
    tt_world_destroy(c);
    free(again.p);
    return ok;
}

enum { N = 3 };
typedef struct streams {
    fuzz_buf corpus[N];
    tt_world *targets[N];
} streams;

static bool one_stream(void *ctx, unsigned long it, uint32_t *accepted)
{
    const fuzz_buf *corpus = ((streams *)ctx)->corpus;
    tt_world **targets = ((streams *)ctx)->targets;
    int k = (int)fuzz_below(N), o = (int)fuzz_below(N);
    fuzz_buf m = mutate(&corpus[k], &corpus[o]);
    if (!m.p) return false;
    bool ok = true;
    if (tt_world_restore(targets[k], m.p, m.n) == TT_OK) {
        (*accepted)++;
        ok = check_accepted(targets[k], it);
        if (ok) ok = tt_world_restore(targets[k], corpus[k].p, corpus[k].n) == TT_OK;
    } else {
        fuzz_buf now = save(targets[k]);
        ok = now.p && now.n == corpus[k].n && memcmp(now.p, corpus[k].p, now.n) == 0;
        free(now.p);
        if (!ok) tt_test_fail(__FILE__, __LINE__, "stream %lu: refused, yet the world changed", it);
    }
    tt_world *fresh = tt_world_load(m.p, m.n);
    if (fresh && ok) ok = check_accepted(fresh, it);
    tt_world_destroy(fresh);
    free(m.p);
    if (!ok) tt_test_fail(__FILE__, __LINE__, "stream %lu: an accepted stream is not a valid world", it);
    return ok;
}

TEST(fuzz_stream_reader)
{
    streams st;
    scene sc[2];
    ENSURE(scene_build(&sc[0], SCENE_ZOO) && scene_build(&sc[1], SCENE_INTEGRATORS));
    for (int s = 0; s < 20; s++) scene_step(&sc[0]);
    for (int s = 0; s < 70; s++) scene_step(&sc[1]);
    st.targets[0] = scene_small_world();
    st.targets[1] = sc[0].w;
    st.targets[2] = sc[1].w;
    for (int k = 0; k < N; k++) {
        ENSURE(st.targets[k]);
        st.corpus[k] = save(st.targets[k]);
        ENSURE(st.corpus[k].p);
    }
    fuzz_run("stream", "fuzz_stream_reader", 300, one_stream, &st);
    for (int k = 0; k < N; k++) {
        free(st.corpus[k].p);
        tt_world_destroy(st.targets[k]);
    }
}
