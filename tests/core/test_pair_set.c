/* The sets of particle pairs that must not collide (core/pair_set.c): the
 * same answers as a plain reference list under random adds, removes and
 * particle drops, and listed in order. */
#include "test.h"
#include "tether.h"
#include "core/pair_set.h"

#include <stdlib.h>

enum { NP = 40 }; /* few particles: many pairs share one, so drops and probe chains meet */

static uint32_t rnd(uint64_t *s)
{
    *s = *s * 6364136223846793005ull + 1442695040888963407ull;
    return (uint32_t)(*s >> 33);
}

TEST(pair_set_counts_as_a_reference_table_under_adds_removes_and_drops)
{
    static uint32_t ref[NP][NP]; /* ref[lo][hi]: references */
    tt__pair_set s;
    tt__pair_set_init(&s, true);
    uint64_t seed = 20261202;
    for (int op = 0; op < 20000; op++) {
        uint32_t a = rnd(&seed) % NP, b = rnd(&seed) % NP, r = rnd(&seed) % 16;
        if (a == b) continue;
        uint32_t lo = a < b ? a : b, hi = a < b ? b : a;
        if (r < 9) {
            ENSURE(tt__pair_set_add(&s, b, a));
            ref[lo][hi]++;
        } else if (r < 15) {
            tt__pair_set_remove(&s, a, b);
            if (ref[lo][hi]) ref[lo][hi]--;
        } else {
            tt__pair_set_drop(&s, a);
            for (uint32_t k = 0; k < NP; k++) ref[k < a ? k : a][k < a ? a : k] = 0;
        }
        if (op % 97) continue;
        uint32_t used = 0;
        for (uint32_t i = 0; i < NP; i++)
            for (uint32_t j = i + 1; j < NP; j++) {
                ENSURE(tt__pair_set_count(&s, i, j) == ref[i][j] && tt__pair_set_count(&s, j, i) == ref[i][j]);
                used += ref[i][j] != 0;
            }
        ENSURE(s.used == used);
        uint32_t n;
        const uint64_t *keys = tt__pair_set_sorted(&s, &n);
        ENSURE(n == used);
        for (uint32_t k = 0; k < n; k++) {
            ENSURE(k == 0 || keys[k - 1] < keys[k]);
            ENSURE(ref[keys[k] >> 32][(uint32_t)keys[k]] != 0);
        }
    }
    tt__pair_set_free(&s);
}

TEST(pair_set_reserve_makes_room_so_adds_cannot_fail)
{
    tt__pair_set s;
    tt__pair_set_init(&s, true);
    ENSURE(tt__pair_set_reserve(&s, 0) && s.cap == 0); /* nothing asked, nothing allocated */
    ENSURE(tt__pair_set_reserve(&s, 1000));
    const uint32_t cap = s.cap;
    for (uint32_t k = 0; k < 1000; k++) ENSURE(tt__pair_set_add(&s, k, k + 1));
    ENSURE(s.cap == cap && s.used == 1000);
    uint32_t n;
    ENSURE(tt__pair_set_sorted(&s, &n) && n == 1000);
    tt__pair_set_free(&s);
    ENSURE(s.cap == 0 && s.used == 0 && tt__pair_set_count(&s, 1, 2) == 0);
}
