/* tether — generational slot pool. */
#include "pool.h"

#include <stdlib.h>

uint32_t tt__pool_alloc(tt__pool *p, uint32_t limit, bool *grew)
{
    *grew = false;
    if (p->free_count > 0) {
        p->changes++;
        return p->free_list[--p->free_count];
    }
    if (p->count >= limit || p->count >= TT_HANDLE_MAX_SLOTS) return UINT32_MAX;
    if (p->count == p->cap) {
        uint32_t cap = p->cap ? (p->cap > UINT32_MAX / 2 ? UINT32_MAX : p->cap * 2) : 64;
        uint32_t *gen = realloc(p->gen, (size_t)cap * sizeof *gen);
        if (!gen) return UINT32_MAX;
        p->gen = gen;
        p->cap = cap;
    }
    uint32_t i = p->count++;
    p->gen[i] = (p->tag << TT_POOL_TAG_SHIFT) | 1u;
    p->changes++;
    *grew = true;
    return i;
}

bool tt__pool_reserve_free(tt__pool *p, uint32_t more)
{
    /* The free list grows only with removals, so worlds that never remove never pay. */
    uint64_t need = (uint64_t)p->free_count + more;
    if (need > p->count) need = p->count; /* at most every slot is free */
    if (need <= p->free_cap) return true;
    uint64_t cap = p->free_cap ? p->free_cap : 64;
    while (cap < need) cap *= 2;
    if (cap > p->cap) cap = p->cap;
    uint32_t *fl = realloc(p->free_list, (size_t)cap * sizeof *fl);
    if (!fl) return false;
    p->free_list = fl;
    p->free_cap = (uint32_t)cap;
    return true;
}

void tt__pool_free(tt__pool *p, uint32_t index)
{
    p->changes++; /* retired or recycled, the slot no longer holds what it did */
    if ((p->gen[index] & TT_POOL_GEN_MASK) == TT_POOL_GEN_MASK) return; /* retired: its handles stay stale forever */
    p->gen[index]++;
    /* Removals reserve their room first (tt__pool_reserve_free); without it
     * the slot is retired rather than recycled: its handles stay stale. */
    if (!tt__pool_reserve_free(p, 1)) return;
    p->free_list[p->free_count++] = index;
}

void tt__pool_unalloc(tt__pool *p, tt__pool_mark m, uint32_t k, uint32_t index, uint32_t gen)
{
    /* The free list hands out its top first, so the k-th slot came from
     * m.free_count − 1 − k; past the list's end, from the high-water mark,
     * which the rewind lowers (a slot above it starts afresh when reached). */
    p->changes++;
    if (k >= m.free_count) return;
    p->free_list[m.free_count - 1 - k] = index;
    p->gen[index] = gen;
}

void tt__pool_rewind(tt__pool *p, tt__pool_mark m)
{
    p->free_count = m.free_count;
    p->count = m.count;
    p->changes++;
}

void tt__pool_destroy(tt__pool *p)
{
    uint32_t tag = p->tag;
    uint64_t changes = p->changes + 1; /* a cache keyed on the count sees the pool emptied */
    free(p->gen);
    free(p->free_list);
    *p = (tt__pool){0};
    p->tag = tag;
    p->changes = changes;
}

size_t tt__pool_bytes(const tt__pool *p)
{
    return (size_t)p->cap * sizeof(uint32_t) + (size_t)p->free_cap * sizeof(uint32_t);
}
