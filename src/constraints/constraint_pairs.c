/* tether — the particle pairs that must not collide because a distance
 * constraint joins them with collide = false. Counted per pair, so a pair
 * stays excluded while any constraint still names it; the collision stage
 * asks once per candidate pair, hence the hash. */
#include "constraint_internal.h"

#include <stdlib.h>

/* ---- excluded collision pairs: open addressing, linear probing ---------- */

static inline uint64_t pair_key(uint32_t a, uint32_t b)
{
    uint32_t lo = a < b ? a : b, hi = a < b ? b : a;
    return (((uint64_t)lo << 32) | hi) + 1; /* never 0: 0 marks an empty slot */
}

static inline uint32_t pair_hash(uint64_t k, uint32_t mask)
{
    k ^= k >> 33;
    k *= 0xff51afd7ed558ccdull;
    k ^= k >> 33;
    return (uint32_t)k & mask;
}

static bool pairs_rehash(tt__cgroup *g, uint32_t cap)
{
    uint64_t *keys = calloc(cap, sizeof *keys);
    uint32_t *ns = calloc(cap, sizeof *ns);
    if (!keys || !ns) {
        free(keys);
        free(ns);
        return false;
    }
    for (uint32_t i = 0; i < g->pair_cap; i++) {
        if (!g->pair_key[i]) continue;
        uint32_t j = pair_hash(g->pair_key[i], cap - 1);
        while (keys[j]) j = (j + 1) & (cap - 1);
        keys[j] = g->pair_key[i];
        ns[j] = g->pair_n[i];
    }
    free(g->pair_key);
    free(g->pair_n);
    g->pair_key = keys;
    g->pair_n = ns;
    g->pair_cap = cap;
    return true;
}

bool tt__constraint_pair_add(tt__cgroup *g, uint32_t a, uint32_t b)
{
    if ((g->pair_used + 1) * 2 > g->pair_cap && !pairs_rehash(g, g->pair_cap ? g->pair_cap * 2 : 64)) return false;
    uint64_t k = pair_key(a, b);
    uint32_t m = g->pair_cap - 1, j = pair_hash(k, m);
    while (g->pair_key[j] && g->pair_key[j] != k) j = (j + 1) & m;
    if (!g->pair_key[j]) {
        g->pair_key[j] = k;
        g->pair_used++;
    }
    g->pair_n[j]++;
    return true;
}

void tt__constraint_pair_remove(tt__cgroup *g, uint32_t a, uint32_t b)
{
    if (!g->pair_cap) return;
    uint64_t k = pair_key(a, b);
    uint32_t m = g->pair_cap - 1, j = pair_hash(k, m);
    while (g->pair_key[j] && g->pair_key[j] != k) j = (j + 1) & m;
    if (!g->pair_key[j] || --g->pair_n[j] > 0) return;
    /* backward-shift deletion keeps every probe chain unbroken */
    g->pair_key[j] = 0;
    g->pair_n[j] = 0;
    g->pair_used--;
    uint32_t i = j;
    for (;;) {
        i = (i + 1) & m;
        if (!g->pair_key[i]) break;
        uint32_t home = pair_hash(g->pair_key[i], m);
        /* move i into the hole j if its home is not cyclically in (j, i] */
        bool move = j <= i ? (home <= j || home > i) : (home <= j && home > i);
        if (move) {
            g->pair_key[j] = g->pair_key[i];
            g->pair_n[j] = g->pair_n[i];
            g->pair_key[i] = 0;
            g->pair_n[i] = 0;
            j = i;
        }
    }
}

bool tt__constraint_pair_excluded(const tt_world *w, uint32_t a, uint32_t b)
{
    const tt__cgroup *g = tt__cgroup_peek(w);
    if (!g || !g->pair_used) return false;
    uint64_t k = pair_key(a, b);
    uint32_t m = g->pair_cap - 1, j = pair_hash(k, m);
    while (g->pair_key[j]) {
        if (g->pair_key[j] == k) return true;
        j = (j + 1) & m;
    }
    return false;
}

bool tt__constraint_pairs_any(const tt_world *w)
{
    const tt__cgroup *g = tt__cgroup_peek(w);
    return g && g->pair_used;
}
