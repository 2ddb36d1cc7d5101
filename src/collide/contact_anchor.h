/* tether — anchored friction's table and scratch (contact_anchor.c): the
 * types the collision state holds, and the calls that keep the table as
 * state (saved, hashed, put back with a failed step, dropped with a
 * particle). The substep's calls are in collide_internal.h. */
#ifndef TETHER_CONTACT_ANCHOR_H
#define TETHER_CONTACT_ANCHOR_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

struct tt__sink;
struct tt__source;

/* One pair's entry, kept whole: the lookup, the sort, a removed
 * particle's compaction and the undo's copy each move one record. (As four
 * arrays it ran no slower: the reference pour at 1 × 4 took the same time,
 * with the same bits.) */
typedef struct tt__anchor {
    uint64_t key;         /* lower slot << 32 | higher slot */
    double rx, ry;        /* the lower particle's position less the higher one's where the pair stuck */
    double lm;            /* the pair's normal correction in that substep, m, with warm_start on (else 0) */
} tt__anchor;

/* Where each pair that touched at the end of the last substep stuck, sorted by key. */
typedef struct tt__anchors {
    tt__anchor *e;        /* ascending by key */
    uint32_t n, cap;
    uint32_t *first;      /* the entries whose lower slot is p: [first[p], first[p + 1]), p + 1 < nfirst */
    uint32_t nfirst, fcap;
} tt__anchors;

/* What a relax call does: every contact (the sweeps), or one of the extra
 * passes of anchored friction after them. */
enum { TT__PASS_ALL = 0, TT__PASS_FRICTION = 1, TT__PASS_SHAPES = 2 };

/* The substep's, per unit (a batch entry when the substep batches its
 * pairs, else a pair): its anchor (rxy: x, y of a − b), friction so far
 * (lt), whether it is slow (slower than thr before the sweeps: its friction
 * is anchored) and then its static friction (mu, else 0); at the end the
 * touching pairs' entries before sorting (kept: apart from rxy, which the
 * velocity pass reads after) and the sort's counts (bucket, one per
 * particle + 2). wl: the normal correction the pair had in the last
 * substep (warm start, contact_warm.c), else 0. */
typedef struct tt__anchor_scratch {
    bool on;              /* the setting applies this substep */
    uint8_t pass;         /* TT__PASS_* */
    double thr;           /* pairs slower than this, m/s, hold to their anchor */
    double h;             /* the substep, s */
    double warm;          /* the warm start's largest push this substep, m */
    double *rxy, *lt, *mu, *wl;
    tt__anchor *kept;
    uint8_t *slow;
    uint32_t *resting;    /* the slow units with a correction in the last substep (wl > 0), ascending: the warm start's */
    uint32_t nresting;
    uint32_t cap;         /* units of rxy (two each), lt, mu, wl, kept, slow, resting */
    uint32_t *bucket, bcap;
} tt__anchor_scratch;

void tt__anchors_clear(tt__anchors *t);
void tt__anchors_drop(tt__anchors *t, uint32_t i);
/* Room for n entries and the sentinels past them (not their index); false on no memory. */
bool tt__anchors_room(tt__anchors *t, uint32_t n);
/* The entries of from into to (its index not kept up: the undo's copy); false on no memory. */
bool tt__anchors_copy(tt__anchors *to, const tt__anchors *from);
/* The undo's copy back into the table it was taken from (which only grew since: allocates nothing). */
void tt__anchors_restore(tt__anchors *t, const tt__anchors *from);
void tt__anchors_free(tt__anchors *t);
size_t tt__anchors_bytes(const tt__anchors *t);
/* The stream's section: its id, the count, the entries. load reads what
 * follows the id, each pair of slots below n. */
void tt__anchors_save(const tt__anchors *t, struct tt__sink *s);
bool tt__anchors_load(tt__anchors *t, struct tt__source *s, uint32_t n);
/* warm_start's section: its id, the setting, then each entry's normal
 * correction (the table's count, 0 without anchors). load reads what
 * follows the id into the table just loaded (or none); false on a bad one. */
void tt__anchors_save_warm(const tt__anchors *t, double warm, struct tt__sink *s);
bool tt__anchors_load_warm(tt__anchors *t, struct tt__source *s, double *warm);
/* Every entry's normal correction to 0 (warm start switched off). */
void tt__anchors_cool(tt__anchors *t);

#endif
