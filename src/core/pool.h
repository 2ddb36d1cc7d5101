/* tether — generational slot pool: the id allocator behind every handle. */
#ifndef TETHER_POOL_H
#define TETHER_POOL_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "tether/base.h"

/* New slots come from a LIFO free list, else the high-water mark (deterministic).
 * Freeing bumps the slot's generation, so old handles go stale; a slot whose
 * generation would wrap is retired, never reused. A generation holds the
 * owning world's tag above TT_POOL_TAG_SHIFT, so a handle from another world
 * is stale here too; the bits below count reuses of the slot. The widths are
 * the handle budget of tether/base.h; so is the most slots a pool hands out. */
#define TT_POOL_TAG_SHIFT TT_HANDLE_GEN_BITS
#define TT_POOL_GEN_MASK ((1u << TT_HANDLE_GEN_BITS) - 1)
#define TT_POOL_MAX_TAG ((1u << TT_HANDLE_TAG_BITS) - 1)

typedef struct tt__pool {
    uint32_t *gen;       /* generation per slot; the slot is live when `live` says so */
    uint32_t *free_list;
    uint32_t free_count, free_cap;
    uint32_t count;      /* slots ever used (high-water mark) */
    uint32_t cap;
    uint32_t tag;        /* 1…TT_POOL_MAX_TAG, set by the world before first use (0 works, without the cross-world check) */
    uint64_t changes;    /* bumped by every alloc, free, unalloc and rewind: caches of what the slots hold key on it */
} tt__pool;

/* Returns a slot index, or UINT32_MAX if the pool cannot grow (limit, the
 * handle budget TT_HANDLE_MAX_SLOTS, or memory;
 * the pool is then unchanged). *grew is set when count increased (the caller
 * must size its arrays to count). */
uint32_t tt__pool_alloc(tt__pool *p, uint32_t limit, bool *grew);
void tt__pool_free(tt__pool *p, uint32_t index);
/* Room in the free list for `more` slots freed from now on, so that removals
 * that must not fail half way (a step's breaking links, a composite's
 * parts) can reserve it before changing anything. False on no memory. */
bool tt__pool_reserve_free(tt__pool *p, uint32_t more);

/* Where a pool stood before a call that allocates many slots, so that a
 * failure half way can put it back: the same handles then come next, as if
 * the call had never been made. */
typedef struct tt__pool_mark {
    uint32_t free_count, count;
} tt__pool_mark;
static inline tt__pool_mark tt__pool_mark_now(const tt__pool *p) { return (tt__pool_mark){p->free_count, p->count}; }
/* Gives slot `index`, the k-th (from 0) allocated since mark m and handed out
 * with generation `gen`, back its place and generation of then. Call it for
 * every slot allocated since m (freed again or not), then tt__pool_rewind;
 * nothing else may have been allocated or freed since m. */
void tt__pool_unalloc(tt__pool *p, tt__pool_mark m, uint32_t k, uint32_t index, uint32_t gen);
void tt__pool_rewind(tt__pool *p, tt__pool_mark m);
void tt__pool_destroy(tt__pool *p);
size_t tt__pool_bytes(const tt__pool *p);

#endif
