/* tether — private side of the mask library (src/mask/).
 *
 * Layout: each row is `stride` 64-bit words; pixel x of row y is bit (x & 63)
 * of word bits[y·stride + (x >> 6)], the lowest bit being the leftmost
 * pixel. The bits past w in a row's last word are always zero: every
 * operation keeps them so, and the overlap loops count on it (they AND
 * whole words without masking the tail). */
#ifndef TETHER_MASK_INTERNAL_H
#define TETHER_MASK_INTERNAL_H

#include "tether/mask.h"

struct tt_mask {
    int w, h;
    int stride;     /* words per row */
    uint64_t *bits; /* h·stride words, in the same allocation after the struct */
};

#define TT__MASK_PRINTF(a, b) __attribute__((format(printf, a, b)))

/* Records the message for tt_mask_last_error and returns code. */
tt_result tt__mask_fail(tt_result code, const char *fmt, ...) TT__MASK_PRINTF(2, 3);
/* Forgets the last message: a call that succeeds leaves "". */
void tt__mask_ok(void);

/* A mask with every bit clear, no checks but the allocation (NULL with a message). */
tt_mask *tt__mask_alloc(const char *fn, int w, int h);
/* The same with its bits unset: the caller writes every word. */
tt_mask *tt__mask_alloc_raw(const char *fn, int w, int h);
/* Checks w, h as the public calls document (1…TT_MASK_MAX_SIDE). */
tt_result tt__mask_check_size(const char *fn, int w, int h);
/* Checks a mask argument (not NULL). */
tt_result tt__mask_check(const char *fn, const char *name, const tt_mask *m);
/* Checks an offset (|d| ≤ TT_MASK_MAX_OFFSET). */
tt_result tt__mask_check_offset(const char *fn, int dx, int dy);

/* Zeroes the bits past w in every row's last word. */
void tt__mask_clear_tail(tt_mask *m);

static inline uint64_t *tt__mask_row(const tt_mask *m, int y)
{
    return m->bits + (size_t)y * (size_t)m->stride;
}

static inline int tt__mask_bit(const tt_mask *m, int x, int y)
{
    return (int)((tt__mask_row(m, y)[x >> 6] >> (x & 63)) & 1u);
}

static inline void tt__mask_put(tt_mask *m, int x, int y, bool v)
{
    uint64_t *w = tt__mask_row(m, y) + (x >> 6), b = (uint64_t)1 << (x & 63);
    *w = v ? (*w | b) : (*w & ~b);
}

/* --- placing B on A at (dx, dy), a word at a time ---------------------------
 * dx = 64·q + r with 0 ≤ r < 64 (floor division). The bits of B's row that
 * land on A's word k are B's words j − 1 and j with j = k − q: the high
 * 64 − r... bits of word j − 1 shifted down and word j shifted up. */
typedef struct tt__mask_shift {
    int q;        /* whole words */
    unsigned r;   /* bits, 0…63 */
    int k0, k1;   /* A's words that can receive any of B's bits, inclusive (k1 < k0: none) */
    int ki0, ki1; /* of those, the words where both B words exist (no bounds checks there) */
    int y0, y1;   /* A's rows B covers, [y0, y1) */
    int dy;       /* A's row y meets B's row y − dy */
} tt__mask_shift;

/* Fills s for B at (dx, dy) on A;
 * false when nothing of B lands on A. */
bool tt__mask_shift_of(tt__mask_shift *s, const tt_mask *a, const tt_mask *b, int dx, int dy);

/* B's bits landing on A's word k, with bounds checks (for the edge words). */
static inline __attribute__((always_inline)) uint64_t tt__mask_bword(const uint64_t *b, int sb, const tt__mask_shift *s, int k)
{
    int j = k - s->q;
    uint64_t lo = (j >= 1 && j - 1 < sb) ? b[j - 1] : 0, hi = (j >= 0 && j < sb) ? b[j] : 0;
    return s->r ? (lo >> (64 - s->r)) | (hi << s->r) : hi;
}

#endif
