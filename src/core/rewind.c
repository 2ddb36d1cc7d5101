/* tether — the rewind ring. Keyframes are snapshot streams, oldest first in
 * one array; the newest is kept as it is and every older one is coded
 * (delta.c) against the next newer, so dropping the oldest costs nothing
 * and adding a keyframe re-codes only the one before it. Every ANCHOR-th
 * keyframe is coded against nothing instead (it costs more, about twice
 * the others on the pour), so rebuilding one decodes at most ANCHOR of them,
 * not the whole history back from the newest; a cache keeps the last one
 * rebuilt, so scrubbing backwards decodes one keyframe per keyframe passed. */
#include "core/delta.h"
#include "core/internal.h"
#include "tether/rewind.h"

#include <stdlib.h>
#include <string.h>

enum { MAX_EVERY = 1000000, ANCHOR = 8 };

typedef struct keyframe {
    uint64_t step;
    unsigned char *data; /* the stream (newest) or its coding against the next newer */
    size_t n;            /* bytes of data */
    bool anchor;         /* coded against nothing (older ones than the newest only) */
} keyframe;

struct tt_rewind {
    tt_rewind_def def;
    keyframe *k;
    uint32_t count, cap;
    uint64_t last;       /* the newest step recorded */
    size_t bytes;        /* sum of k[].n */
    /* the cache: keyframe cache_step's stream in buf[0..buf_n), when cache_ok */
    bool cache_ok;
    uint64_t cache_step;
    unsigned char *buf, *work;
    size_t buf_n, buf_cap, work_cap;
};

tt_rewind_def tt_rewind_def_default(void)
{
    return (tt_rewind_def){.every = 10, .keep_steps = 600, .max_bytes = (size_t)256 << 20};
}

tt_rewind *tt_rewind_create(const tt_rewind_def *def)
{
    if (!def) { tt__fail(NULL, TT_EINVAL, "tt_rewind_create: def is NULL"); return NULL; }
    if (def->every < 1 || def->every > MAX_EVERY) {
        tt__fail(NULL, TT_EINVAL, "tt_rewind_create: every must be in [1, %d], got %u", MAX_EVERY, def->every);
        return NULL;
    }
    if (def->keep_steps < def->every || def->keep_steps > (uint64_t)1 << 53) {
        tt__fail(NULL, TT_EINVAL, "tt_rewind_create: keep_steps must be in [every, 2^53], got %llu",
                 (unsigned long long)def->keep_steps);
        return NULL;
    }
    if (def->max_bytes < 1024) {
        tt__fail(NULL, TT_EINVAL, "tt_rewind_create: max_bytes must be at least 1024, got %zu", def->max_bytes);
        return NULL;
    }
    tt_rewind *r = calloc(1, sizeof *r);
    if (!r) { tt__fail(NULL, TT_ENOMEM, "tt_rewind_create: out of memory"); return NULL; }
    r->def = *def;
    return r;
}

void tt_rewind_destroy(tt_rewind *r)
{
    if (!r) return;
    for (uint32_t i = 0; i < r->count; i++) free(r->k[i].data);
    free(r->k);
    free(r->buf);
    free(r->work);
    free(r);
}

static bool reserve(unsigned char **p, size_t *cap, size_t n)
{
    if (n <= *cap) return true;
    unsigned char *q = realloc(*p, n);
    if (!q) return false;
    *p = q;
    *cap = n;
    return true;
}

/* Keyframe j's stream into r->buf (r->buf_n); false when out of memory
 * (or a coding that does not decode: a bug, reported as such). */
static bool decode_into_work(tt_rewind *r, const keyframe *f, const unsigned char *ref, size_t refn, const char **why)
{
    size_t n = tt__delta_length(f->data, f->n);
    if (!reserve(&r->work, &r->work_cap, n ? n : 1)) { *why = "out of memory"; return false; }
    if (!n || !tt__delta_decode(f->data, f->n, ref, refn, r->work, n)) { *why = "a keyframe does not decode"; return false; }
    unsigned char *t = r->buf;
    size_t tc = r->buf_cap;
    r->buf = r->work;
    r->buf_cap = r->work_cap;
    r->work = t;
    r->work_cap = tc;
    r->buf_n = n;
    return true;
}

/* Keyframe j's stream into r->buf (r->buf_n); false when out of memory
 * (or a coding that does not decode: a bug, reported as such). Starts
 * from the nearest of: the cache, an anchor, the newest, at or after j. */
static bool rebuild(tt_rewind *r, uint32_t j, const char **why)
{
    uint32_t c = j;
    while (c < r->count - 1 && !r->k[c].anchor && !(r->cache_ok && r->k[c].step == r->cache_step)) c++;
    const bool cached = r->cache_ok && r->k[c].step == r->cache_step;
    r->cache_ok = false;
    if (!cached && c == r->count - 1) {
        if (!reserve(&r->buf, &r->buf_cap, r->k[c].n)) { *why = "out of memory"; return false; }
        memcpy(r->buf, r->k[c].data, r->k[c].n);
        r->buf_n = r->k[c].n;
    } else if (!cached && !decode_into_work(r, &r->k[c], NULL, 0, why)) {
        return false;
    }
    for (uint32_t i = c; i > j; i--)
        if (!decode_into_work(r, &r->k[i - 1], r->buf, r->buf_n, why)) return false;
    r->cache_ok = true;
    r->cache_step = r->k[j].step;
    return true;
}

/* Drops keyframes after step (a new timeline): the newest left becomes a
 * stream again. */
static bool truncate_after(tt_rewind *r, uint64_t step, const char **why)
{
    uint32_t keep = r->count;
    while (keep > 0 && r->k[keep - 1].step > step) keep--;
    if (keep == r->count) return true;
    if (keep > 0) {
        if (!rebuild(r, keep - 1, why)) return false;
        unsigned char *s = malloc(r->buf_n ? r->buf_n : 1);
        if (!s) { *why = "out of memory"; return false; }
        memcpy(s, r->buf, r->buf_n);
        r->bytes -= r->k[keep - 1].n;
        free(r->k[keep - 1].data);
        r->k[keep - 1].data = s;
        r->k[keep - 1].n = r->buf_n;
        r->k[keep - 1].anchor = false;
        r->bytes += r->buf_n;
    }
    for (uint32_t i = keep; i < r->count; i++) {
        r->bytes -= r->k[i].n;
        free(r->k[i].data);
    }
    r->count = keep;
    return true;
}

/* Appends the stream s[0..n) (owned by the ring from now) as keyframe
 * step, re-coding the newest against it. */
static bool append(tt_rewind *r, uint64_t step, unsigned char *s, size_t n, const char **why)
{
    if (r->count == r->cap) {
        uint32_t cap = r->cap ? r->cap * 2 : 16;
        keyframe *k = realloc(r->k, cap * sizeof *k);
        if (!k) { *why = "out of memory"; return false; }
        r->k = k;
        r->cap = cap;
    }
    if (r->count > 0) {
        keyframe *prev = &r->k[r->count - 1];
        const bool anchor = (prev->step / r->def.every) % ANCHOR == 0;
        unsigned char *d;
        size_t dn;
        if (!tt__delta_encode(prev->data, prev->n, anchor ? NULL : s, anchor ? 0 : n, &d, &dn)) { *why = "out of memory"; return false; }
        prev->anchor = anchor;
        r->bytes += dn - prev->n;
        free(prev->data);
        prev->data = d;
        prev->n = dn;
    }
    r->k[r->count++] = (keyframe){step, s, n, false};
    r->bytes += n;
    r->cache_ok = false;
    return true;
}

static void drop_old(tt_rewind *r, uint64_t now)
{
    uint32_t drop = 0;
    size_t bytes = r->bytes;
    while (drop + 1 < r->count &&
           (r->k[drop + 1].step + r->def.keep_steps <= now || bytes > r->def.max_bytes)) {
        bytes -= r->k[drop].n;
        free(r->k[drop].data);
        drop++;
    }
    if (!drop) return;
    memmove(r->k, r->k + drop, (r->count - drop) * sizeof *r->k);
    r->count -= drop;
    r->bytes = bytes;
}

tt_result tt_rewind_record(tt_rewind *r, const tt_world *w)
{
    TT_CHECK_WORLD(w, "tt_rewind_record");
    if (!r) return tt__fail(w, TT_EINVAL, "tt_rewind_record: ring is NULL");
    const uint64_t step = w->stats.steps;
    const char *why = NULL;
    unsigned char *s = NULL;
    size_t n = 0;
    const bool key = step % r->def.every == 0;
    if (key) { /* the stream first: a failure after this point changes nothing */
        if (tt_world_save(w, NULL, 0, &n) != TT_ENOMEM || !(s = malloc(n ? n : 1)) ||
            tt_world_save(w, s, n, &n) != TT_OK) {
            free(s);
            return tt__fail(w, TT_ENOMEM, "tt_rewind_record: cannot save the world: %s", tt_last_error(w));
        }
    }
    bool same = false;
    if (r->count > 0 && step <= r->k[r->count - 1].step) {
        if (!truncate_after(r, step, &why)) goto fail;
        /* the same state again (a replay after a seek): the keyframe stands */
        same = key && r->count > 0 && r->k[r->count - 1].step == step && r->k[r->count - 1].n == n &&
               memcmp(r->k[r->count - 1].data, s, n) == 0;
        if (key && !same && r->count > 0 && r->k[r->count - 1].step == step) {
            /* another state at a kept step (restored from elsewhere): it replaces that keyframe */
            if (step > 0 && !truncate_after(r, step - 1, &why)) goto fail;
            if (step == 0) {
                free(r->k[0].data);
                r->count = 0;
                r->cache_ok = false;
                r->bytes = 0;
            }
        }
    }
    if (key && !same && !append(r, step, s, n, &why)) goto fail;
    if (same) free(s);
    r->last = step;
    drop_old(r, step);
    return TT_OK;
fail:
    free(s);
    return tt__fail(w, TT_ENOMEM, "tt_rewind_record: %s", why);
}

tt_result tt_rewind_seek(tt_rewind *r, tt_world *w, uint64_t step, uint64_t *at)
{
    TT_CHECK_WORLD(w, "tt_rewind_seek");
    if (!r) return tt__fail(w, TT_EINVAL, "tt_rewind_seek: ring is NULL");
    if (r->count == 0 || step < r->k[0].step || step > r->last)
        return tt__fail(w, TT_EINVAL, "tt_rewind_seek: step %llu is not in the ring (%s%llu … %llu)",
                        (unsigned long long)step, r->count ? "" : "empty: ", r->count ? (unsigned long long)r->k[0].step : 0ull,
                        (unsigned long long)r->last);
    uint32_t j = r->count - 1;
    while (r->k[j].step > step) j--;
    const char *why = NULL;
    if (!rebuild(r, j, &why)) return tt__fail(w, TT_ENOMEM, "tt_rewind_seek: %s; the world is unchanged", why);
    tt_result res = tt_world_restore(w, r->buf, r->buf_n);
    if (res != TT_OK) return res;
    if (at) *at = r->k[j].step;
    return TT_OK;
}

tt_result tt_rewind_get_range(const tt_rewind *r, uint64_t *first, uint64_t *last)
{
    if (!r || !first || !last) return tt__fail(NULL, TT_EINVAL, "tt_rewind_get_range: NULL argument");
    if (r->count == 0) return tt__fail(NULL, TT_ESTATE, "tt_rewind_get_range: the ring is empty");
    *first = r->k[0].step;
    *last = r->last;
    return TT_OK;
}

size_t tt_rewind_get_memory(const tt_rewind *r)
{
    return r ? sizeof *r + r->cap * sizeof *r->k + r->bytes + r->buf_cap + r->work_cap : 0;
}

uint32_t tt_rewind_get_count(const tt_rewind *r) { return r ? r->count : 0; }
