/* tether — sets of particle pairs that must not collide, with a reference
 * count per pair (pair_set.c). One implementation for every such set: the
 * links that join two particles with collide = false (the constraints
 * group's, a pair stays while any link names it) and the pairs the script
 * switched off (the collision state's, count 1). The broadphases ask
 * tt__pair_set_has once per candidate pair, hence a hash. */
#ifndef TETHER_PAIR_SET_H
#define TETHER_PAIR_SET_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef struct tt__pair_set {
    uint64_t *key;    /* open addressing, linear probing: tt__pair_set_key + 1; 0 is an empty slot */
    uint32_t *n;      /* references per slot */
    uint32_t cap, used; /* slots (a power of two, 0 until the first pair), pairs */
    /* ordered sets only (tt__pair_set_init): room for every pair, so that
     * listing them in order (a snapshot) never allocates */
    uint64_t *order;
    bool ordered;
} tt__pair_set;

/* The key of the unordered pair {a, b}: the smaller slot in the high half. */
static inline uint64_t tt__pair_set_key(uint32_t a, uint32_t b)
{
    return a < b ? ((uint64_t)a << 32) | b : ((uint64_t)b << 32) | a;
}

static inline uint32_t tt__pair_set_hash(uint64_t k, uint32_t mask)
{
    k ^= k >> 33;
    k *= 0xff51afd7ed558ccdull;
    k ^= k >> 33;
    return (uint32_t)k & mask;
}

/* An empty set; ordered: tt__pair_set_sorted works on it. */
void tt__pair_set_init(tt__pair_set *s, bool ordered);
/* One more reference to {a, b}; false on no memory (the set unchanged). */
bool tt__pair_set_add(tt__pair_set *s, uint32_t a, uint32_t b);
/* One reference less to {a, b} (none: nothing); the pair goes at 0. */
void tt__pair_set_remove(tt__pair_set *s, uint32_t a, uint32_t b);
/* Every pair naming particle i goes, whatever its count. */
void tt__pair_set_drop(tt__pair_set *s, uint32_t i);
/* Room for `more` pairs beyond those held (a load adds many); false on no memory. */
bool tt__pair_set_reserve(tt__pair_set *s, uint32_t more);
/* An ordered set's keys (tt__pair_set_key) in increasing order, in room
 * the set holds (valid until it changes); *count gets how many. */
const uint64_t *tt__pair_set_sorted(const tt__pair_set *s, uint32_t *count);
size_t tt__pair_set_bytes(const tt__pair_set *s);
void tt__pair_set_free(tt__pair_set *s);

/* References to {a, b}: 0 when it is not in the set. */
static inline uint32_t tt__pair_set_count(const tt__pair_set *s, uint32_t a, uint32_t b)
{
    if (!s->used) return 0;
    const uint64_t k = tt__pair_set_key(a, b) + 1;
    const uint32_t m = s->cap - 1;
    for (uint32_t j = tt__pair_set_hash(k, m); s->key[j]; j = (j + 1) & m)
        if (s->key[j] == k) return s->n[j];
    return 0;
}

/* Whether {a, b} is in the set: the broadphases' question, answered from
 * the keys alone (a stored key has a count of at least 1). */
static inline bool tt__pair_set_has(const tt__pair_set *s, uint32_t a, uint32_t b)
{
    if (!s->used) return false;
    const uint64_t k = tt__pair_set_key(a, b) + 1;
    const uint32_t m = s->cap - 1;
    for (uint32_t j = tt__pair_set_hash(k, m); s->key[j]; j = (j + 1) & m)
        if (s->key[j] == k) return true;
    return false;
}
/* The same question out of line, for a hot loop that seldom asks it (the
 * broadphases' filter, behind a test of used): the probe's code stays out
 * of the loop. */
bool tt__pair_set_contains(const tt__pair_set *s, uint32_t a, uint32_t b);

#endif
