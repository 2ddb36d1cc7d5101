/* tether — replay journals as bytes and as files. The bytes, in this
 * machine's byte order (as the snapshot stream inside them):
 *
 *   0  "TTJR"                        4  format version (u32)
 *   8  0x01020304 as written (u32)  12 header size (u32, 56)
 *   16 steps (u64)                   24 steps with a change (u64)
 *   32 the longest of the snapshot and the streams its deltas decode to (u64)
 *   40 the snapshot's length (u64)   48 the record's length (u64)
 *   56 the snapshot (tt_world_save's stream), then the record (journal.c)
 *
 * A file is those bytes behind the snapshot files' header and checksum
 * (snapfile.c, payload kind TT__FILE_JOURNAL). A reader checks everything
 * before it keeps anything: the snapshot must load, every entry and every
 * delta's coding must be well formed, and the counts must agree, so a
 * replay of a loaded journal meets no malformed byte. */
#include "core/delta.h"
#include "core/journal_internal.h"
#include "core/snapfile.h"

#include <stdio.h>
#include <stdlib.h>

enum { VERSION = 1, HEADER = 56 };
static const char magic[4] = {'T', 'T', 'J', 'R'};

tt_result tt_journal_save(const tt_journal *j, void *buf, size_t cap, size_t *size)
{
    if (!j) return tt__fail(NULL, TT_EINVAL, "tt_journal_save: journal is NULL");
    if (!buf && cap) return tt__fail(NULL, TT_EINVAL, "tt_journal_save: buf is NULL with cap %zu", cap);
    const size_t n = HEADER + j->snap_n + j->rec_n;
    if (size) *size = n;
    if (cap < n) return tt__fail(NULL, TT_ENOMEM, "tt_journal_save: the journal takes %zu bytes, the buffer holds %zu", n, cap);
    unsigned char *b = buf;
    const uint32_t v[3] = {VERSION, 0x01020304u, HEADER};
    const uint64_t q[5] = {j->steps, j->changed, j->max_stream, j->snap_n, j->rec_n};
    memcpy(b, magic, 4);
    memcpy(b + 4, v, 12);
    memcpy(b + 16, q, 40);
    memcpy(b + HEADER, j->snap, j->snap_n);
    if (j->rec_n) memcpy(b + HEADER + j->snap_n, j->rec, j->rec_n);
    return TT_OK;
}

/* The record walked: entries and changes counted; false with why. */
static bool check_record(const unsigned char *rec, size_t n, uint64_t steps, uint64_t changed, size_t max_stream,
                         size_t snap_n, char *why, size_t whylen)
{
    size_t at = 0, longest = snap_n;
    uint64_t k = 0, c = 0;
    double dt = 0.0;
    tt__jentry e;
    while (at < n) {
        if (k == steps) { snprintf(why, whylen, "the record holds more than its %llu steps", (unsigned long long)steps); return false; }
        if (!tt__journal_read(rec, n, &at, dt, max_stream, &e)) {
            snprintf(why, whylen, "step %llu's record is not well formed", (unsigned long long)(k + 1));
            return false;
        }
        dt = e.dt;
        c += e.delta != NULL;
        if (e.delta && tt__delta_length(e.delta, e.delta_n) > longest) longest = tt__delta_length(e.delta, e.delta_n);
        k++;
    }
    if (longest != max_stream) {
        snprintf(why, whylen, "its longest stream is %zu bytes, the header says %zu", longest, max_stream);
        return false;
    }
    if (k != steps || c != changed) {
        snprintf(why, whylen, "the record holds %llu steps (%llu with a change), the header says %llu (%llu)",
                 (unsigned long long)k, (unsigned long long)c, (unsigned long long)steps, (unsigned long long)changed);
        return false;
    }
    return true;
}

/* The bytes checked whole into a new journal, or NULL with why. */
static tt_journal *parse(const unsigned char *b, size_t size, char *why, size_t whylen)
{
    uint32_t v[3];
    uint64_t q[5];
    if (!b || size < HEADER) { snprintf(why, whylen, "%zu bytes is too short for a journal", b ? size : 0); return NULL; }
    if (memcmp(b, magic, 4) != 0) { snprintf(why, whylen, "not a tether journal (no 'TTJR' at its start)"); return NULL; }
    memcpy(v, b + 4, 12);
    memcpy(q, b + 16, 40);
    if (v[1] != 0x01020304u) { snprintf(why, whylen, "saved on a machine of the other byte order"); return NULL; }
    if (v[0] != VERSION || v[2] != HEADER) { snprintf(why, whylen, "journal format version %u, this build reads version %d", v[0], VERSION); return NULL; }
    const uint64_t steps = q[0], changed = q[1], max_stream = q[2], snap_n = q[3], rec_n = q[4];
    if (snap_n > size - HEADER || rec_n != size - HEADER - snap_n) {
        snprintf(why, whylen, "%zu bytes, the header says %llu + %llu + %d (truncated or padded)", size,
                 (unsigned long long)snap_n, (unsigned long long)rec_n, HEADER);
        return NULL;
    }
    if (max_stream < snap_n || max_stream > TT_JOURNAL_MAX_STREAM || changed > steps) {
        snprintf(why, whylen, "its counts are not valid (corrupted?)");
        return NULL;
    }
    tt_world *probe = tt_world_load(b + HEADER, (size_t)snap_n);
    if (!probe) { snprintf(why, whylen, "its snapshot: %s", tt_last_error(NULL)); return NULL; }
    tt_world_destroy(probe);
    const unsigned char *rec = b + HEADER + snap_n;
    if (!check_record(rec, (size_t)rec_n, steps, changed, (size_t)max_stream, (size_t)snap_n, why, whylen)) return NULL;
    tt_journal_def def = tt_journal_def_default();
    tt_journal *j = tt__journal_new(&def);
    if (j && (j->snap = malloc((size_t)snap_n)) && (!rec_n || (j->rec = malloc((size_t)rec_n)))) {
        memcpy(j->snap, b + HEADER, (size_t)snap_n);
        if (rec_n) memcpy(j->rec, rec, (size_t)rec_n);
        j->snap_n = (size_t)snap_n;
        j->rec_n = j->rec_cap = (size_t)rec_n;
        j->steps = steps;
        j->changed = changed;
        j->max_stream = (size_t)max_stream;
        return j;
    }
    tt_journal_destroy(j);
    snprintf(why, whylen, "out of memory");
    return NULL;
}

tt_journal *tt_journal_load(const void *data, size_t size)
{
    char why[300];
    tt_journal *j = parse(data, size, why, sizeof why);
    if (!j) tt__fail(NULL, TT_EINVAL, "tt_journal_load: %s", why);
    return j;
}

tt_result tt_journal_save_file(const tt_journal *j, const char *path)
{
    const char *fn = "tt_journal_save_file";
    if (!j) return tt__fail(NULL, TT_EINVAL, "%s: journal is NULL", fn);
    if (!path || !*path) return tt__fail(NULL, TT_EINVAL, "%s: path is %s", fn, path ? "empty" : "NULL");
    size_t n = 0;
    tt_journal_save(j, NULL, 0, &n);
    unsigned char *b = malloc(n);
    if (!b) return tt__fail(NULL, TT_ENOMEM, "%s: out of memory for %zu bytes", fn, n);
    tt_journal_save(j, b, n, &n);
    char why[300];
    const bool ok = tt__file_write(path, TT__FILE_JOURNAL, b, n, why, sizeof why);
    free(b);
    return ok ? TT_OK : tt__fail(NULL, TT_EINVAL, "%s: %s", fn, why);
}

tt_journal *tt_journal_load_file(const char *path)
{
    const char *fn = "tt_journal_load_file";
    if (!path || !*path) {
        tt__fail(NULL, TT_EINVAL, "%s: path is %s", fn, path ? "empty" : "NULL");
        return NULL;
    }
    char why[300];
    unsigned kind = 0;
    size_t n = 0;
    unsigned char *p = tt__file_read(path, &kind, &n, why, sizeof why);
    tt_journal *j = NULL;
    if (p && kind != TT__FILE_JOURNAL) snprintf(why, sizeof why, "it holds a snapshot, not a replay journal");
    else if (p) j = parse(p, n, why, sizeof why);
    free(p);
    if (!j) tt__fail(NULL, TT_EINVAL, "%s: '%s': %s", fn, path, why);
    return j;
}
