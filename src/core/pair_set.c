/* tether — sets of particle pairs that must not collide, counted (see
 * pair_set.h): open addressing with linear probing, at most half full,
 * backward-shift deletion so that no tombstone lengthens a probe. */
#include "pair_set.h"

#include <stdlib.h>
#include <string.h>

void tt__pair_set_init(tt__pair_set *s, bool ordered)
{
    memset(s, 0, sizeof *s);
    s->ordered = ordered;
}

static bool rehash(tt__pair_set *s, uint32_t cap)
{
    uint64_t *keys = calloc(cap, sizeof *keys);
    uint32_t *ns = calloc(cap, sizeof *ns);
    uint64_t *order = s->ordered ? malloc((size_t)(cap / 2) * sizeof *order) : NULL;
    if (!keys || !ns || (s->ordered && !order)) {
        free(keys);
        free(ns);
        free(order);
        return false;
    }
    for (uint32_t i = 0; i < s->cap; i++) {
        if (!s->key[i]) continue;
        uint32_t j = tt__pair_set_hash(s->key[i], cap - 1);
        while (keys[j]) j = (j + 1) & (cap - 1);
        keys[j] = s->key[i];
        ns[j] = s->n[i];
    }
    free(s->key);
    free(s->n);
    free(s->order);
    s->key = keys;
    s->n = ns;
    s->order = order;
    s->cap = cap;
    return true;
}

bool tt__pair_set_reserve(tt__pair_set *s, uint32_t more)
{
    if (!more) return true;
    uint64_t need = ((uint64_t)s->used + more) * 2, cap = s->cap ? s->cap : 64;
    while (cap < need) cap *= 2;
    if (cap > (1ull << 31)) return false;
    return cap == s->cap || rehash(s, (uint32_t)cap);
}

bool tt__pair_set_contains(const tt__pair_set *s, uint32_t a, uint32_t b) { return tt__pair_set_has(s, a, b); }

bool tt__pair_set_add(tt__pair_set *s, uint32_t a, uint32_t b)
{
    if ((s->used + 1) * 2 > s->cap && !rehash(s, s->cap ? s->cap * 2 : 64)) return false;
    const uint64_t k = tt__pair_set_key(a, b) + 1;
    const uint32_t m = s->cap - 1;
    uint32_t j = tt__pair_set_hash(k, m);
    while (s->key[j] && s->key[j] != k) j = (j + 1) & m;
    if (!s->key[j]) {
        s->key[j] = k;
        s->used++;
    }
    s->n[j]++;
    return true;
}

/* Empties slot j and moves later entries of its probe chain back, so that
 * every chain stays unbroken. */
static void delete_at(tt__pair_set *s, uint32_t j)
{
    const uint32_t m = s->cap - 1;
    s->key[j] = 0;
    s->n[j] = 0;
    s->used--;
    for (uint32_t i = j;;) {
        i = (i + 1) & m;
        if (!s->key[i]) return;
        uint32_t home = tt__pair_set_hash(s->key[i], m);
        /* move i into the hole j if its home is not cyclically in (j, i] */
        bool move = j <= i ? (home <= j || home > i) : (home <= j && home > i);
        if (move) {
            s->key[j] = s->key[i];
            s->n[j] = s->n[i];
            s->key[i] = 0;
            s->n[i] = 0;
            j = i;
        }
    }
}

void tt__pair_set_remove(tt__pair_set *s, uint32_t a, uint32_t b)
{
    if (!s->used) return;
    const uint64_t k = tt__pair_set_key(a, b) + 1;
    const uint32_t m = s->cap - 1;
    uint32_t j = tt__pair_set_hash(k, m);
    while (s->key[j] && s->key[j] != k) j = (j + 1) & m;
    if (s->key[j] && --s->n[j] == 0) delete_at(s, j);
}

void tt__pair_set_drop(tt__pair_set *s, uint32_t i)
{
    /* a deletion may pull a later entry into j (looked at again) or an
     * earlier one past it (looked at twice, harmless) */
    for (uint32_t j = 0; s->used && j < s->cap;) {
        const uint64_t k = s->key[j] - 1;
        if (s->key[j] && ((uint32_t)(k >> 32) == i || (uint32_t)k == i)) delete_at(s, j);
        else j++;
    }
}

static int cmp_key(const void *x, const void *y)
{
    const uint64_t a = *(const uint64_t *)x, b = *(const uint64_t *)y;
    return (a > b) - (a < b);
}

const uint64_t *tt__pair_set_sorted(const tt__pair_set *s, uint32_t *count)
{
    uint32_t n = 0;
    for (uint32_t j = 0; j < s->cap && s->order; j++)
        if (s->key[j]) s->order[n++] = s->key[j] - 1;
    if (n > 1) qsort(s->order, n, sizeof *s->order, cmp_key);
    *count = n;
    return s->order;
}

size_t tt__pair_set_bytes(const tt__pair_set *s)
{
    return (size_t)s->cap * (sizeof *s->key + sizeof *s->n) + (s->order ? (size_t)(s->cap / 2) * sizeof *s->order : 0);
}

void tt__pair_set_free(tt__pair_set *s)
{
    free(s->key);
    free(s->n);
    free(s->order);
    tt__pair_set_init(s, s->ordered);
}
