/* tether — golden values: the reference scenes (tests/core/scenes.c) after
 * GOLDEN_STEPS steps have these positions (a digest of their bits, computed
 * apart from tt_world_hash) and this world hash. A change of results, or of
 * what the hash covers, must be deliberate: it changes these constants in
 * the same commit, which says why. The positions digests were recorded
 * before the hash became the hash of the snapshot stream and did not change
 * with it: that change of definition moved no particle. The cloth and zoo
 * scenes, whose script moves a kinematic shape, moved when main's kinematic
 * shapes began to travel across the substeps (second foundation, point 2):
 * pinned again at the merge, main's own build giving the same positions.
 * The pour and zoo scenes moved when the velocity pass began to end with
 * the bottom-up pass (contact_lift.c, issue 21): a pile no longer throws
 * its own layers up. Sleeping on by default (issue 22): the zoo's piles
 * fall asleep (its positions moved); in the others nothing sleeps within
 * 300 steps (the pour still flows, the cloth flaps in the wind, the
 * integrators' spring swings): their positions stay, their hashes moved
 * (the hash covers the sleep section). The settle scene pins what
 * sleeping does to results: its two piles fall asleep (all 32 after step
 * 173, as this build counts), the ball dropped before step 241 wakes the left
 * one's island in step 267, and at step 300 the right pile (16) sleeps on
 * while the left one settles again (all 33 asleep after step 471, inside the
 * cross-build's 600; with the rest test on the unsmoothed position 167, 267
 * and 481, before the speed cap 192, 267 and 427, an older build's 201, 266
 * and 421). The zoo moved
 * when contacts began to pre-stabilise overlaps deeper than a tenth of the radii sum
 * (contact_prestab.c, issue 21): its spawned piles come apart without speed.
 * The zoo and settle scenes moved again when the pair grid began to hold
 * only the awake particles and the sleepers within reach of one
 * (grid_awake.c): the same pairs, in another order. The roll scene, added
 * with its pin, pins particles that turn (tt_world_def.spin): friction at
 * the contact point (contact_roll.c), discs rolling down a slope into a
 * pile (nothing asleep by step 300: the driver spins a disc every second).
 * The settle and roll scenes moved when no particle could leave its pair
 * contacts faster than the fastest of them came in (contact_cap.c). Every
 * hash moved, and the zoo and settle positions, when the rest test began to
 * read the particle's position smoothed over a few steps (sleep_rest.c):
 * the smoothed positions are in the sleep section. The pyramid scene,
 * added with its pin, pins anchored friction (collide/contact_anchor.c):
 * a pyramid of circles that it holds, one circle removed from under the
 * upper rows, a ball dropped on the top. It moved when the rub took the
 * pair's distance from the push and divided by reciprocals
 * (contact_batch.h tt__anchored_rub: other roundings), and when its driver
 * began to turn the warm start on at step 30 (contact_warm.c: its
 * corrections in the stream, dropped with the removed circle). */
#include "test.h"
#include "core/scenes.h"

#include <inttypes.h>

enum { GOLDEN_STEPS = 300 };

static const struct {
    uint64_t positions;
    uint64_t hash;
} golden[SCENE_COUNT] = {
    [SCENE_POUR] = {0xbeaeacd0b50001afull, 0xe7b2f4bca2b7c6d9ull},
    [SCENE_CLOTH] = {0xb5c92190124ff72cull, 0xc5bb71d03afbdef7ull},
    [SCENE_ZOO] = {0x5a2d4ed804f59641ull, 0x12d7efade08f2393ull},
    [SCENE_INTEGRATORS] = {0x27ae56b6631ba7eeull, 0xad7e88ab8523019full},
    [SCENE_SETTLE] = {0x6130b11f32fad7efull, 0x7dad36ae636c2d3aull},
    [SCENE_ROLL] = {0x7305931a3218983full, 0xe1f604779a002266ull},
    [SCENE_PYRAMID] = {0x05cb838418fcae18ull, 0x18d839ebb59c1da4ull},
};

TEST(golden_scenes_keep_their_positions_and_hashes)
{
    int bad = 0;
    for (int k = 0; k < SCENE_COUNT; k++) {
        scene sc;
        ENSURE(scene_build(&sc, (scene_kind)k));
        for (int s = 0; s < GOLDEN_STEPS; s++) scene_step(&sc);
        uint64_t pos = scene_positions_digest(sc.w), h = tt_world_hash(sc.w);
        if (pos != golden[k].positions || h != golden[k].hash) {
            tt_test_fail(__FILE__, __LINE__, "scene %s: positions 0x%016" PRIx64 "ull, hash 0x%016" PRIx64
                         "ull (pinned 0x%016" PRIx64 ", 0x%016" PRIx64 ")", scene_name((scene_kind)k), pos, h,
                         golden[k].positions, golden[k].hash);
            bad++;
        }
        tt_world_destroy(sc.w);
    }
    ENSURE(bad == 0);
}
