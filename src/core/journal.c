/* tether — replay journals: recording (tether/journal.h says what a
 * journal holds and why changes are found by comparing streams rather than
 * by hooking calls). The world's step calls the two hooks below through
 * w->journal_hooks; nothing else of the engine knows journals.
 *
 * The per-step record is a run of entries, one per step, in this
 * machine's byte order (as the snapshot stream):
 *
 *   flags (u8): 1 = the dt differs from the entry before's (always on the
 *               first), 2 = a change precedes the step;
 *   dt (f64), when flag 1;
 *   the world hash after the step (u64);
 *   when flag 2: the delta's length (LEB128), then the delta (delta.c) of
 *               the stream at the step's start against the stream at the
 *               end of the step before.
 *
 * A step that no call preceded costs 9 bytes, 17 when its dt changed. */
#include "core/delta.h"
#include "core/journal_internal.h"

#include <stdio.h>
#include <stdlib.h>

enum { F_DT = 1, F_DELTA = 2 };

tt_journal_def tt_journal_def_default(void) { return (tt_journal_def){.max_bytes = (size_t)256 << 20}; }

tt_journal *tt__journal_new(const tt_journal_def *def)
{
    tt_journal *j = calloc(1, sizeof *j);
    if (j) j->def = *def;
    return j;
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

bool tt__journal_save_world(const tt_world *w, unsigned char **buf, size_t *n, size_t *cap)
{
    char error[sizeof w->error];
    memcpy(error, w->error, sizeof error);
    tt_result r = tt_world_save(w, *buf, *cap, n);
    if (r == TT_ENOMEM && *n <= TT_JOURNAL_MAX_STREAM && reserve(buf, cap, *n + *n / 8))
        r = tt_world_save(w, *buf, *cap, n);
    /* the journal's own saves are not the caller's business: its message stays */
    memcpy(((tt_world *)w)->error, error, sizeof error);
    return r == TT_OK && *n <= TT_JOURNAL_MAX_STREAM;
}

static size_t memory_of(const tt_journal *j)
{
    return sizeof *j + j->snap_n + j->rec_cap + j->ref_cap + j->cur_cap + j->delta_n;
}

static void free_work(tt_journal *j)
{
    free(j->ref);
    free(j->cur);
    free(j->delta);
    j->ref = j->cur = j->delta = NULL;
    j->ref_n = j->ref_cap = j->cur_n = j->cur_cap = j->delta_n = 0;
    j->pending = false;
}

static void detach(tt_journal *j)
{
    if (!j->w) return;
    j->w->journal = NULL;
    j->w->journal_hooks = NULL;
    j->w = NULL;
    free_work(j);
}

/* Recording cannot go on (memory, max_bytes): what is recorded stays whole. */
static void halt(tt_journal *j)
{
    j->full = true;
    detach(j);
}

static void on_before(tt_journal *j, tt_world *w)
{
    /* a step refused for want of memory after this hook ran left its coding here */
    free(j->delta);
    j->delta = NULL;
    j->delta_n = 0;
    j->pending = false;
    if (!tt__journal_save_world(w, &j->cur, &j->cur_n, &j->cur_cap)) { halt(j); return; }
    if (j->cur_n == j->ref_n && memcmp(j->cur, j->ref, j->cur_n) == 0) return;
    if (!tt__delta_encode(j->cur, j->cur_n, j->ref, j->ref_n, &j->delta, &j->delta_n)) { halt(j); return; }
    j->pending = true;
}

/* Appends the step's entry; false when it does not fit in max_bytes or memory. */
static bool append(tt_journal *j, double dt, uint64_t hash)
{
    unsigned char head[1 + 8 + 8 + 10];
    size_t n = 1;
    head[0] = (unsigned char)((dt != j->last_dt ? F_DT : 0) | (j->pending ? F_DELTA : 0));
    if (head[0] & F_DT) {
        memcpy(head + n, &dt, 8);
        n += 8;
    }
    memcpy(head + n, &hash, 8);
    n += 8;
    if (j->pending) n += tt__leb_put(head + n, j->delta_n);
    const size_t need = j->rec_n + n + (j->pending ? j->delta_n : 0);
    if (need > j->rec_cap) {
        size_t cap = j->rec_cap < 4096 ? 4096 : j->rec_cap * 2;
        if (cap < need) cap = need;
        if (memory_of(j) - j->rec_cap + cap > j->def.max_bytes) cap = need;
        if (memory_of(j) - j->rec_cap + cap > j->def.max_bytes || !reserve(&j->rec, &j->rec_cap, cap)) return false;
    }
    memcpy(j->rec + j->rec_n, head, n);
    j->rec_n += n;
    if (j->pending) {
        memcpy(j->rec + j->rec_n, j->delta, j->delta_n);
        j->rec_n += j->delta_n;
        j->changed++;
        if (j->cur_n > j->max_stream) j->max_stream = j->cur_n; /* only what the record holds: the reader checks it */
    }
    j->steps++;
    j->last_dt = dt;
    return true;
}

static void on_after(tt_journal *j, const tt_world *w, double dt)
{
    const bool ok = append(j, dt, tt_world_hash(w));
    free(j->delta);
    j->delta = NULL;
    j->delta_n = 0;
    j->pending = false;
    if (!ok || !tt__journal_save_world(w, &j->ref, &j->ref_n, &j->ref_cap) || memory_of(j) > j->def.max_bytes) halt(j);
}

static void on_gone(tt_journal *j) { detach(j); }

static const tt__journal_hooks hooks = {on_before, on_after, on_gone};

tt_journal *tt_journal_start(tt_world *w, const tt_journal_def *def)
{
    const char *fn = "tt_journal_start";
    if (!w) { tt__fail(NULL, TT_EINVAL, "%s: world is NULL", fn); return NULL; }
    if (!def) { tt__fail(w, TT_EINVAL, "%s: def is NULL", fn); return NULL; }
    if (def->max_bytes < 1024) { tt__fail(w, TT_EINVAL, "%s: max_bytes must be at least 1024, got %zu", fn, def->max_bytes); return NULL; }
    if (w->journal) { tt__fail(w, TT_ESTATE, "%s: the world is journaled already (one journal per world)", fn); return NULL; }
    tt_journal *j = tt__journal_new(def);
    size_t cap = 0;
    if (!j) { tt__fail(w, TT_ENOMEM, "%s: out of memory", fn); return NULL; }
    if (!tt__journal_save_world(w, &j->snap, &j->snap_n, &cap)) {
        size_t need = 0;
        tt_result r = tt_world_save(w, NULL, 0, &need); /* again, for its reason */
        if (r != TT_ENOMEM) tt__fail(w, r, "%s: %s", fn, tt_last_error(w));
        else if (need > TT_JOURNAL_MAX_STREAM) tt__fail(w, TT_ENOMEM, "%s: the world's stream (%zu bytes) is over TT_JOURNAL_MAX_STREAM", fn, need);
        else tt__fail(w, TT_ENOMEM, "%s: out of memory", fn);
        tt_journal_destroy(j);
        return NULL;
    }
    const size_t n = j->snap_n;
    unsigned char *exact = realloc(j->snap, n);
    if (exact) j->snap = exact;
    if (!reserve(&j->ref, &j->ref_cap, n)) {
        tt_journal_destroy(j);
        tt__fail(w, TT_ENOMEM, "%s: out of memory", fn);
        return NULL;
    }
    memcpy(j->ref, j->snap, n);
    j->ref_n = j->max_stream = n;
    if (memory_of(j) + n > def->max_bytes) { /* the snapshot and the two streams of work space */
        tt__fail(w, TT_ENOMEM, "%s: the snapshot and work space take %zu bytes, over max_bytes %zu", fn, memory_of(j) + n, def->max_bytes);
        tt_journal_destroy(j);
        return NULL;
    }
    j->w = w;
    w->journal = j;
    w->journal_hooks = &hooks;
    return j;
}

tt_result tt_journal_stop(tt_journal *j)
{
    if (!j) return tt__fail(NULL, TT_EINVAL, "tt_journal_stop: journal is NULL");
    detach(j);
    return TT_OK;
}

void tt_journal_destroy(tt_journal *j)
{
    if (!j) return;
    detach(j);
    free_work(j);
    free(j->snap);
    free(j->rec);
    free(j);
}

tt_result tt_journal_get_info(const tt_journal *j, tt_journal_info *out)
{
    if (!j || !out) return tt__fail(NULL, TT_EINVAL, "tt_journal_get_info: %s is NULL", j ? "out" : "journal");
    *out = (tt_journal_info){
        .steps = j->steps,
        .changed = j->changed,
        .bytes = memory_of(j),
        .record_bytes = j->rec_n,
        .snapshot_bytes = j->snap_n,
        .recording = j->w != NULL,
        .full = j->full,
        .replayed = j->played,
        .desync = j->desync,
        .desync_expected = j->desync_expected,
        .desync_got = j->desync_got,
    };
    return TT_OK;
}

bool tt__journal_read(const unsigned char *rec, size_t n, size_t *at, double prev_dt, size_t max_stream,
                      tt__jentry *out)
{
    size_t a = *at;
    if (a >= n) return false;
    const unsigned flags = rec[a++];
    if (flags & ~(unsigned)(F_DT | F_DELTA)) return false;
    out->dt = prev_dt;
    if (flags & F_DT) {
        if (n - a < 8) return false;
        memcpy(&out->dt, rec + a, 8);
        a += 8;
    }
    if (!(out->dt >= TT_MIN_DT && out->dt <= TT_MAX_DT) || n - a < 8) return false;
    memcpy(&out->hash, rec + a, 8);
    a += 8;
    out->delta = NULL;
    out->delta_n = 0;
    if (flags & F_DELTA) {
        uint64_t len;
        if (!tt__leb_get(rec, n, &a, &len) || len > n - a || !tt__delta_check(rec + a, (size_t)len, max_stream))
            return false;
        out->delta = rec + a;
        out->delta_n = (size_t)len;
        a += (size_t)len;
    }
    *at = a;
    return true;
}
