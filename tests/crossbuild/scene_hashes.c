/* tests/crossbuild/scene_hashes.c — the reference scenes' hashes, for
 * tests/crossbuild/run.sh, which builds this program and the engine with
 * several compilers and optimisation levels and asks them to agree bit for
 * bit (-ffp-contract=off, no -ffast-math: IEEE arithmetic in source order).
 * Prints one line per scene: name, steps, world hash, positions digest. */
#include "core/scenes.h"

#include <inttypes.h>
#include <stdio.h>

int main(void)
{
    int bad = 0;
    for (int k = 0; k < SCENE_COUNT; k++) {
        scene sc;
        if (!scene_build(&sc, (scene_kind)k)) {
            printf("%s: cannot build\n", scene_name((scene_kind)k));
            bad = 1;
            continue;
        }
        for (int s = 0; s < 600; s++) scene_step(&sc);
        printf("%-12s 600 %016" PRIx64 " %016" PRIx64 "\n", scene_name((scene_kind)k), tt_world_hash(sc.w),
               scene_positions_digest(sc.w));
        tt_world_destroy(sc.w);
    }
    return bad;
}
