/* tether — the pairs of particles switched off by tt_world_set_pair_collision:
 * the lookup the broadphases ask (through tt__pair_filter) before they
 * keep a candidate pair. */
#include "collide_internal.h"

static bool excluded(const tt__collide *c, uint64_t key)
{
    uint32_t lo = 0, hi = c->nexcl;
    while (lo < hi) {
        uint32_t mid = (lo + hi) / 2;
        if (c->excl[mid] < key) lo = mid + 1;
        else hi = mid;
    }
    return lo < c->nexcl && c->excl[lo] == key;
}

bool tt__pair_excluded(const tt__collide *c, uint32_t a, uint32_t b)
{
    return excluded(c, tt__pair_key(a, b));
}

