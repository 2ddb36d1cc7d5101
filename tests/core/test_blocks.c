/* The solver's contract with its groups (solver.c, internal.h tt__block):
 * a sweep relaxes each group in consecutive blocks of its units, and any
 * split gives the same world bit for bit, so the blocks can later be solved
 * apart. The reference scenes (cloth, contacts, every constraint kind,
 * Jacobi) and a cloth catching balls (distance links in vector lanes and
 * contact batches in the same sweeps) are stepped with each group in
 * k = 1, 2, 3 and 8 blocks, with vector lanes and without, and hashed. */
#include "test.h"
#include "collide/collide_internal.h"
#include "constraints/constraint_internal.h"
#include "core/internal.h"
#include "core/scenes.h"
#include "scenes/scene.h"

#include <inttypes.h>

enum { STEPS = 150, CATCH_STEPS = 90 };

static const uint32_t splits[] = {1, 2, 3, 8};

typedef struct digest {
    uint64_t positions, hash;
} digest;

static digest reference_scene(scene_kind k, uint32_t blocks, tt__simd_mode simd)
{
    scene sc;
    digest d = {0, 0};
    if (!scene_build(&sc, k)) return d;
    sc.w->blocks = blocks;
    tt__constraints_set_simd(sc.w, simd);
    tt__contacts_set_simd(sc.w, simd);
    for (int s = 0; s < STEPS; s++) scene_step(&sc);
    d = (digest){scene_positions_digest(sc.w), tt_world_hash(sc.w)};
    tt_world_destroy(sc.w);
    return d;
}

static tt_world *catch_world(uint32_t iterations)
{
    const ts_cloth_catch cd = {16, 60, iterations};
    return ts_cloth_catch_build(&cd, NULL);
}

static digest catch_scene(uint32_t blocks, tt__simd_mode simd)
{
    tt_world *w = catch_world(6);
    digest d = {0, 0};
    if (!w) return d;
    w->blocks = blocks;
    tt__constraints_set_simd(w, simd);
    tt__contacts_set_simd(w, simd);
    for (int s = 0; s < CATCH_STEPS; s++) tt_world_step(w, 1.0 / 60);
    d = (digest){scene_positions_digest(w), tt_world_hash(w)};
    tt_world_destroy(w);
    return d;
}

/* The scalar loops and each width of lanes (those this processor and build
 * lack run as the scalar loops: tt__simd_kind). */
static const tt__simd_mode modes[] = {TT__SIMD_SCALAR, TT__SIMD_AVX2, TT__SIMD_AVX512};

static int compare(const char *what, tt__simd_mode m, uint32_t k, digest got, digest one)
{
    if (got.positions == one.positions && got.hash == one.hash) return 0;
    tt_test_fail(__FILE__, __LINE__, "%s, simd mode %d (1 scalar, 2 AVX2, 3 AVX-512), %u blocks: positions 0x%016" PRIx64 " hash 0x%016" PRIx64
                 " (one block: 0x%016" PRIx64 ", 0x%016" PRIx64 ")", what, (int)m, k, got.positions, got.hash,
                 one.positions, one.hash);
    return 1;
}

TEST(any_split_into_blocks_gives_the_reference_scenes_bit_for_bit)
{
    int bad = 0;
    for (size_t m = 0; m < sizeof modes / sizeof modes[0]; m++)
        for (int k = 0; k < SCENE_COUNT; k++) {
            const digest one = reference_scene((scene_kind)k, 1, modes[m]);
            ENSURE(one.positions != 0);
            for (size_t b = 1; b < sizeof splits / sizeof splits[0]; b++)
                bad += compare(scene_name((scene_kind)k), modes[m], splits[b], reference_scene((scene_kind)k, splits[b], modes[m]), one);
        }
    ENSURE(bad == 0);
}

TEST(any_split_into_blocks_gives_a_cloth_catching_balls_bit_for_bit)
{
    int bad = 0;
    const digest scalar = catch_scene(1, TT__SIMD_SCALAR);
    ENSURE(scalar.positions != 0);
    for (size_t m = 0; m < sizeof modes / sizeof modes[0]; m++)
        for (size_t b = 0; b < sizeof splits / sizeof splits[0]; b++)
            bad += compare("cloth catching balls", modes[m], splits[b], catch_scene(splits[b], modes[m]), scalar);
    ENSURE(bad == 0);
}

/* The balls reach the cloth: pair contacts between cloth and balls, and
 * links, in the same sweeps (else the scene above would test less). */
TEST(the_cloth_catches_the_balls)
{
    tt_world *w = catch_world(6);
    ENSURE(w != NULL);
    uint32_t touching = 0;
    for (int s = 0; s < CATCH_STEPS; s++) {
        tt_world_step(w, 1.0 / 60);
        const tt__collide *c = tt__collide_peek(w);
        ENSURE(c != NULL);
        for (uint32_t k = 0; k < c->scr.npairs; k++) touching += (c->scr.pairs[k].a < 256) != (c->scr.pairs[k].b < 256);
    }
    ENSURE(touching > 100);
    tt_world_destroy(w);
}

/* The rows the vector sweeps work on are packed once before a substep's
 * sweeps and unpacked once after, however many sweeps run: no group packs
 * its own copy per sweep. */
TEST(a_cloth_touching_particles_packs_once_a_substep_whatever_the_sweeps)
{
    const bool lanes = tt__simd_kind(TT__SIMD_AUTO) != TT__SIMD_SCALAR;
    for (uint32_t it = 2; it <= 16; it *= 2) {
        tt_world *w = catch_world(it);
        ENSURE(w != NULL);
        const uint64_t before = w->scr.packs;
        for (int s = 0; s < 40; s++) tt_world_step(w, 1.0 / 60);
        ENSURE(w->scr.packs - before == (lanes ? 2 * 40u : 0u));
        tt_world_destroy(w);
    }
}
