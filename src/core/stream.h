/* tether — the byte stream a world saves to and restores from (snapshot.c
 * writes the header and the world's own section; every feature writes and
 * reads its section through its group hooks). These primitives live apart
 * from the world code and depend on nothing in the engine, so that every
 * feature may use them without a circle of dependencies between files. */
#ifndef TETHER_STREAM_H
#define TETHER_STREAM_H

#include "internal.h"

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

/* A streaming 64-bit hash (four lanes over 32-byte blocks, xxHash64's
 * round and avalanche): the stream's checksum and the world hash, fast
 * enough for 10 000 particles in a few tens of microseconds. */
typedef struct tt__hasher {
    uint64_t v[4];
    unsigned char stash[32];
    size_t nstash;
    uint64_t total;
} tt__hasher;
void tt__hasher_init(tt__hasher *h);
void tt__hasher_feed(tt__hasher *h, const void *data, size_t n);
uint64_t tt__hasher_end(const tt__hasher *h);
uint64_t tt__hash_bytes(const void *data, size_t n);

/* Where a save goes: a growable buffer; the caller's buffer (fixed: past
 * its end only the length is counted, so the caller learns the size it
 * needs); or (hashing) the hasher, with the world tag left out of every
 * generation, since the tag tells live worlds apart and is not simulation
 * state. */
typedef struct tt__sink {
    unsigned char *buf;
    size_t len, cap;
    bool failed;   /* out of memory: the stream is incomplete */
    bool fixed, overflow;
    bool hashing;
    tt__hasher hs;
} tt__sink;
void tt__put(tt__sink *s, const void *p, size_t n);
static inline void tt__put_u8(tt__sink *s, uint8_t v) { tt__put(s, &v, 1); }
static inline void tt__put_u16(tt__sink *s, uint16_t v) { tt__put(s, &v, 2); }
static inline void tt__put_u32(tt__sink *s, uint32_t v) { tt__put(s, &v, 4); }
static inline void tt__put_u64(tt__sink *s, uint64_t v) { tt__put(s, &v, 8); }
static inline void tt__put_f64(tt__sink *s, double v) { tt__put(s, &v, 8); }
/* A handle's generation (the tag masked out when hashing). */
void tt__put_gen(tt__sink *s, uint32_t gen);
/* A pool's raw fields: count, generations, free list, tag. */
void tt__put_pool(tt__sink *s, const tt__pool *p);
/* Opens a section (id: four ASCII letters); returns where its length goes. */
size_t tt__section_open(tt__sink *s, uint32_t id);
void tt__section_close(tt__sink *s, size_t at);
#define TT__ID(a, b, c, d) ((uint32_t)(a) | (uint32_t)(b) << 8 | (uint32_t)(c) << 16 | (uint32_t)(d) << 24)

/* What a restore reads from: every read is bounds-checked; the first
 * failure sets failed and why, and later reads return zeros. */
typedef struct tt__source {
    const unsigned char *p;
    size_t len, at;
    bool failed;
    char why[200];
} tt__source;
bool tt__src_fail(tt__source *s, const char *fmt, ...) TT_PRINTF(2, 3); /* returns false */
bool tt__get(tt__source *s, void *out, size_t n);
/* n bytes to read in place, or NULL (and failed) when fewer are left. */
const void *tt__get_span(tt__source *s, size_t n);
/* A count of items of `elem` bytes each that the rest of the stream can hold. */
uint32_t tt__get_count(tt__source *s, size_t elem, const char *what);
uint8_t tt__get_u8(tt__source *s);
uint16_t tt__get_u16(tt__source *s);
uint32_t tt__get_u32(tt__source *s);
uint64_t tt__get_u64(tt__source *s);
/* A finite double in [lo, hi]; what names it in the error. */
double tt__get_num(tt__source *s, double lo, double hi, const char *what);
/* A bool stored as 0 or 1. */
bool tt__get_bool(tt__source *s, const char *what);
/* A pool written by tt__put_pool into p (fresh allocations): free list
 * entries distinct and below count, count at most max, tag the world's. */
bool tt__get_pool(tt__source *s, tt__pool *p, uint32_t max, uint32_t tag, const char *what);
/* Sections: reads a header, limits s to its payload; tt__section_end checks
 * that the payload was read whole and moves past it. */
typedef struct tt__section {
    uint32_t id;
    size_t end, outer_len;
} tt__section;
bool tt__section_begin(tt__source *s, tt__section *sec);
bool tt__section_end(tt__source *s, const tt__section *sec);

/* Features that keep state in a world register their group hooks here
 * (from a constructor), so that a stream naming a feature the world has not
 * used yet can still be loaded. */
void tt__feature_register(const tt__group_ops *ops);
const tt__group_ops *tt__feature_find(uint32_t id);

#endif
