/* tether — the replay journal's insides, shared by its three files:
 * journal.c (recording, the per-step record's format), journal_replay.c
 * (playing it back) and journal_file.c (bytes and files). */
#ifndef TETHER_JOURNAL_INTERNAL_H
#define TETHER_JOURNAL_INTERNAL_H

#include "core/internal.h"
#include "tether/journal.h"

struct tt_journal {
    tt_journal_def def;
    tt_world *w;             /* the world being recorded; NULL when not recording */
    bool full;               /* recording stopped at max_bytes or for want of memory */
    unsigned char *snap;     /* the first snapshot (a stream) */
    size_t snap_n;
    unsigned char *rec;      /* the per-step record: one entry per step (journal.c) */
    size_t rec_n, rec_cap;
    uint64_t steps, changed;
    size_t max_stream;       /* the longest of the snapshot and the streams the deltas decode to */
    double last_dt;          /* recording: the dt of the last entry (0 before the first) */
    /* Work space. Recording: ref is the stream at the end of the last step,
     * cur the one at the start of this step, delta their coding when they
     * differ. Replay: ref is the world's stream before a change is applied,
     * cur the stream the change gives. */
    unsigned char *ref, *cur, *delta;
    size_t ref_n, ref_cap, cur_n, cur_cap, delta_n;
    bool pending;            /* recording: delta holds this step's change */
    /* the replay */
    bool playing;
    size_t at;               /* where the next step's entry starts in rec */
    uint64_t played;
    double play_dt;          /* the dt of the entry played last */
    uint64_t desync, desync_expected, desync_got;
};

/* One step's entry of the record. */
typedef struct tt__jentry {
    double dt;
    uint64_t hash;
    const unsigned char *delta; /* NULL: no change before this step */
    size_t delta_n;
} tt__jentry;

/* Reads the entry at rec[*at..n), prev_dt being the dt of the entry
 * before (0 for the first), and moves *at past it; false when it is not
 * well formed (its delta's coding included, decoding to at most
 * max_stream bytes). */
bool tt__journal_read(const unsigned char *rec, size_t n, size_t *at, double prev_dt, size_t max_stream,
                      tt__jentry *out);
/* A new, empty journal that records nothing, or NULL. */
tt_journal *tt__journal_new(const tt_journal_def *def);
/* buf[0..*n) := w's stream, growing buf (*cap) as needed; false (w's
 * error message as it was) when memory ran out or w cannot be saved. */
bool tt__journal_save_world(const tt_world *w, unsigned char **buf, size_t *n, size_t *cap);

#endif
