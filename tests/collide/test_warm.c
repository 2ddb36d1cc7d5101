/* tether — warm start (tt_collision_settings.warm_start,
 * collide/contact_warm.c): a pile's weight held from the first sweep, so a
 * few sweeps rest a pile as many did without it. Its state (the
 * corrections kept in anchored friction's table) is tested with the
 * anchors' (test_anchor.c), its bits in vector lanes with stacking's
 * (test_stacking.c). */
#include "test.h"
#include "small_pour.h"

#include <stdlib.h>

/* The small pours (1 000 circles, a box 20 wide, stacking 2, anchored
 * friction) at 1 × 4: with 0.75 of the last substep's corrections first,
 * at rest and under 1 % at 15 s; without, deeper. */
TEST(warm_start_rests_a_pour_under_one_percent_at_four_sweeps)
{
    if (getenv("TT_MEMCHECK")) return; /* 15 s pours: minutes under valgrind */
    for (uint64_t seed = 1; seed <= 2; seed++) {
        double warm, cold, ke_warm, ke_cold;
        ENSURE(small_pour(seed, true, 4, 0.75, &warm, &ke_warm));
        ENSURE(small_pour(seed, true, 4, 0.0, &cold, &ke_cold));
        ENSURE(warm <= 0.01);
        ENSURE(ke_warm <= 1e-4);
        ENSURE(cold > 0.01); /* over the 1 % without it */
    }
}
