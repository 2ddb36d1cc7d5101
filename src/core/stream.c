/* tether — the snapshot stream's primitives: hasher, sink, source, and the
 * registry of features that save state (stream.h). */
#include "stream.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- hasher --------------------------------------------------------------- */

static const uint64_t P1 = 0x9E3779B185EBCA87ull, P2 = 0xC2B2AE3D27D4EB4Full, P3 = 0x165667B19E3779F9ull,
                      P4 = 0x85EBCA77C2B2AE63ull, P5 = 0x27D4EB2F165667C5ull;

static inline uint64_t rotl(uint64_t x, int r) { return (x << r) | (x >> (64 - r)); }
static inline uint64_t round64(uint64_t acc, uint64_t in) { return rotl(acc + in * P2, 31) * P1; }
static inline uint64_t merge(uint64_t acc, uint64_t v) { return (acc ^ round64(0, v)) * P1 + P4; }
static inline uint64_t load64(const unsigned char *p)
{
    uint64_t v;
    memcpy(&v, p, 8);
    return v;
}

void tt__hasher_init(tt__hasher *h)
{
    memset(h, 0, sizeof *h);
    h->v[0] = P1 + P2;
    h->v[1] = P2;
    h->v[2] = 0;
    h->v[3] = 0 - P1;
}

static void blocks(tt__hasher *h, const unsigned char *p, size_t nblocks)
{
    uint64_t a = h->v[0], b = h->v[1], c = h->v[2], d = h->v[3];
    for (size_t i = 0; i < nblocks; i++, p += 32) {
        a = round64(a, load64(p));
        b = round64(b, load64(p + 8));
        c = round64(c, load64(p + 16));
        d = round64(d, load64(p + 24));
    }
    h->v[0] = a, h->v[1] = b, h->v[2] = c, h->v[3] = d;
}

void tt__hasher_feed(tt__hasher *h, const void *data, size_t n)
{
    const unsigned char *p = data;
    h->total += n;
    if (h->nstash) {
        size_t take = 32 - h->nstash < n ? 32 - h->nstash : n;
        memcpy(h->stash + h->nstash, p, take);
        h->nstash += take;
        p += take;
        n -= take;
        if (h->nstash < 32) return;
        blocks(h, h->stash, 1);
        h->nstash = 0;
    }
    blocks(h, p, n / 32);
    p += n / 32 * 32;
    n %= 32;
    memcpy(h->stash, p, n);
    h->nstash = n;
}

uint64_t tt__hasher_end(const tt__hasher *h)
{
    uint64_t r = rotl(h->v[0], 1) + rotl(h->v[1], 7) + rotl(h->v[2], 12) + rotl(h->v[3], 18);
    for (int k = 0; k < 4; k++) r = merge(r, h->v[k]);
    r += h->total;
    const unsigned char *p = h->stash;
    size_t n = h->nstash;
    for (; n >= 8; n -= 8, p += 8) r = rotl(r ^ round64(0, load64(p)), 27) * P1 + P4;
    for (; n > 0; n--, p++) r = rotl(r ^ (*p * P5), 11) * P1;
    r ^= r >> 33;
    r *= P2;
    r ^= r >> 29;
    r *= P3;
    r ^= r >> 32;
    return r;
}

uint64_t tt__hash_bytes(const void *data, size_t n)
{
    tt__hasher h;
    tt__hasher_init(&h);
    tt__hasher_feed(&h, data, n);
    return tt__hasher_end(&h);
}

/* ---- sink ------------------------------------------------------------------ */

void tt__put(tt__sink *s, const void *p, size_t n)
{
    if (s->failed || n == 0) return;
    if (s->hashing) {
        tt__hasher_feed(&s->hs, p, n);
        return;
    }
    if (s->overflow || (s->fixed && n > s->cap - s->len)) {
        s->overflow = true;
        s->len += n;
        return;
    }
    if (s->len + n > s->cap) {
        size_t cap = s->cap ? s->cap : 4096;
        while (cap < s->len + n) cap = cap > SIZE_MAX / 2 ? s->len + n : cap * 2;
        unsigned char *b = realloc(s->buf, cap);
        if (!b) {
            s->failed = true;
            return;
        }
        s->buf = b;
        s->cap = cap;
    }
    memcpy(s->buf + s->len, p, n);
    s->len += n;
}

void tt__put_gen(tt__sink *s, uint32_t gen) { tt__put_u32(s, s->hashing ? gen & TT_POOL_GEN_MASK : gen); }

void tt__put_pool(tt__sink *s, const tt__pool *p)
{
    tt__put_u32(s, p->count);
    if (s->hashing)
        for (uint32_t i = 0; i < p->count; i++) tt__put_gen(s, p->gen[i]);
    else
        tt__put(s, p->gen, (size_t)p->count * sizeof *p->gen);
    tt__put_u32(s, p->free_count);
    tt__put(s, p->free_list, (size_t)p->free_count * sizeof *p->free_list);
    tt__put_u32(s, s->hashing ? 0 : p->tag);
}

size_t tt__section_open(tt__sink *s, uint32_t id)
{
    tt__put_u32(s, id);
    tt__put_u32(s, 0);
    size_t at = s->len;
    tt__put_u64(s, 0); /* hashing: the length is never patched, and need not be: the content is all hashed */
    return at;
}

void tt__section_close(tt__sink *s, size_t at)
{
    if (s->hashing || s->failed || s->overflow) return;
    uint64_t n = s->len - at - 8;
    memcpy(s->buf + at, &n, 8);
}

/* ---- source ---------------------------------------------------------------- */

bool tt__src_fail(tt__source *s, const char *fmt, ...)
{
    if (s->failed) return false;
    s->failed = true;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(s->why, sizeof s->why, fmt, ap);
    va_end(ap);
    return false;
}

const void *tt__get_span(tt__source *s, size_t n)
{
    if (s->failed) return NULL;
    if (n > s->len - s->at) {
        tt__src_fail(s, "truncated at byte %zu (%zu more bytes needed)", s->at, n);
        return NULL;
    }
    const void *p = s->p + s->at;
    s->at += n;
    return p;
}

bool tt__get(tt__source *s, void *out, size_t n)
{
    if (n == 0) return !s->failed; /* out may be NULL for an empty array */
    const void *p = tt__get_span(s, n);
    if (!p) {
        memset(out, 0, n);
        return false;
    }
    memcpy(out, p, n);
    return true;
}

uint32_t tt__get_count(tt__source *s, size_t elem, const char *what)
{
    uint32_t n = 0;
    tt__get(s, &n, 4);
    if (!s->failed && elem && n > (s->len - s->at) / elem) {
        tt__src_fail(s, "%s: count %u is more than the stream holds", what, n);
        return 0;
    }
    return n;
}

uint8_t tt__get_u8(tt__source *s)
{
    uint8_t v;
    tt__get(s, &v, 1);
    return v;
}
uint16_t tt__get_u16(tt__source *s)
{
    uint16_t v;
    tt__get(s, &v, 2);
    return v;
}
uint32_t tt__get_u32(tt__source *s)
{
    uint32_t v;
    tt__get(s, &v, 4);
    return v;
}
uint64_t tt__get_u64(tt__source *s)
{
    uint64_t v;
    tt__get(s, &v, 8);
    return v;
}

double tt__get_num(tt__source *s, double lo, double hi, const char *what)
{
    double v;
    tt__get(s, &v, 8);
    if (s->failed) return 0.0;
    if (!(v >= lo && v <= hi)) {
        tt__src_fail(s, "%s is %g, outside [%g, %g]", what, v, lo, hi);
        return 0.0;
    }
    return v;
}

bool tt__get_bool(tt__source *s, const char *what)
{
    uint8_t v = tt__get_u8(s);
    if (v > 1) tt__src_fail(s, "%s is %u, not a boolean", what, v);
    return v == 1;
}

bool tt__get_pool(tt__source *s, tt__pool *p, uint32_t max, uint32_t tag, const char *what)
{
    *p = (tt__pool){0};
    p->tag = tag;
    uint32_t n = tt__get_count(s, 4, what);
    if (n > max) return tt__src_fail(s, "%s: %u slots, at most %u", what, n, max);
    const void *gen = tt__get_span(s, (size_t)n * 4);
    uint32_t nf = tt__get_count(s, 4, what);
    const uint32_t *fl = tt__get_span(s, (size_t)nf * 4);
    uint32_t t = tt__get_u32(s);
    if (s->failed) return false;
    if (nf > n) return tt__src_fail(s, "%s: %u free slots of %u", what, nf, n);
    if (t != tag) return tt__src_fail(s, "%s: tag %u, the world's is %u", what, t, tag);
    p->gen = malloc((size_t)(n ? n : 1) * sizeof *p->gen);
    p->free_list = malloc((size_t)(nf ? nf : 1) * sizeof *p->free_list);
    unsigned char *seen = calloc(n ? n : 1, 1);
    if (!p->gen || !p->free_list || !seen) {
        free(seen);
        tt__pool_destroy(p);
        return tt__src_fail(s, "%s: out of memory", what);
    }
    tt__copy(p->gen, gen, (size_t)n * 4);
    tt__copy(p->free_list, fl, (size_t)nf * 4);
    p->count = p->cap = n;
    p->free_count = p->free_cap = nf;
    bool ok = true;
    for (uint32_t k = 0; k < nf && ok; k++) {
        uint32_t i = p->free_list[k];
        ok = i < n && !seen[i];
        if (ok) seen[i] = 1;
    }
    free(seen);
    if (!ok) {
        tt__pool_destroy(p);
        return tt__src_fail(s, "%s: a free list entry is out of range or repeated", what);
    }
    /* Every generation one the pool could have handed out: the world's tag
     * above a reuse count of 1 or more (tt__pool_alloc, tt__pool_free). A
     * live slot of generation 0 would list the null handle. */
    for (uint32_t i = 0; i < n; i++)
        if (p->gen[i] >> TT_POOL_TAG_SHIFT != tag || (p->gen[i] & TT_POOL_GEN_MASK) == 0) {
            uint32_t g = p->gen[i];
            tt__pool_destroy(p);
            return tt__src_fail(s, "%s: slot %u has generation 0x%x, not one of tag %u", what, i, g, tag);
        }
    return true;
}

bool tt__section_begin(tt__source *s, tt__section *sec)
{
    sec->id = tt__get_u32(s);
    uint32_t zero = tt__get_u32(s);
    uint64_t n = tt__get_u64(s);
    if (s->failed) return false;
    if (zero != 0) return tt__src_fail(s, "section at byte %zu: reserved field is %u", s->at - 16, zero);
    if (n > s->len - s->at) return tt__src_fail(s, "section at byte %zu: length %llu runs past the end", s->at - 16,
                                                 (unsigned long long)n);
    sec->outer_len = s->len;
    sec->end = s->at + (size_t)n;
    s->len = sec->end;
    return true;
}

bool tt__section_end(tt__source *s, const tt__section *sec)
{
    if (s->failed) return false;
    if (s->at != sec->end)
        return tt__src_fail(s, "section '%.4s': %zu bytes left unread", (const char *)&sec->id, sec->end - s->at);
    s->len = sec->outer_len;
    return true;
}

/* ---- registry ---------------------------------------------------------------- */

enum { TT__MAX_FEATURES = 8 };
static const tt__group_ops *features[TT__MAX_FEATURES];
static int nfeatures;

void tt__feature_register(const tt__group_ops *ops)
{
    for (int k = 0; k < nfeatures; k++)
        if (features[k] == ops) return;
    if (nfeatures < TT__MAX_FEATURES) features[nfeatures++] = ops;
}

const tt__group_ops *tt__feature_find(uint32_t id)
{
    for (int k = 0; k < nfeatures; k++)
        if (features[k]->id == id) return features[k];
    return NULL;
}
