/* tether — playing a replay journal back (tether/journal.h): the world is
 * restored to the journal's snapshot, then each step's recorded change is
 * decoded against the world's own stream and restored in place, the world
 * steps with the recorded dt, and its hash is compared with the recorded
 * one. A change coded against the recording world's stream decodes
 * against the replay's only while the two are the same: after a desync
 * the next change fails the stream's checksum and is refused, the world
 * unchanged, instead of giving a world that was never recorded. */
#include "core/delta.h"
#include "core/journal_internal.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static tt_result check(const tt_journal *j, const tt_world *w, const char *fn)
{
    TT_CHECK_WORLD(w, fn);
    if (!j) return tt__fail(w, TT_EINVAL, "%s: journal is NULL", fn);
    if (j->w) return tt__fail(w, TT_ESTATE, "%s: the journal is recording (tt_journal_stop it first)", fn);
    return TT_OK;
}

tt_result tt_journal_replay_begin(tt_journal *j, tt_world *w)
{
    const char *fn = "tt_journal_replay_begin";
    tt_result r = check(j, w, fn);
    if (r != TT_OK) return r;
    if (tt_world_restore(w, j->snap, j->snap_n) != TT_OK) {
        char why[sizeof w->error];
        snprintf(why, sizeof why, "%s", tt_last_error(w));
        return tt__fail(w, TT_EINVAL, "%s: %s", fn, why);
    }
    j->playing = true;
    j->at = 0;
    j->played = 0;
    j->play_dt = 0.0;
    j->desync = j->desync_expected = j->desync_got = 0;
    return TT_OK;
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

/* The world the change recorded before the step makes of w, as a new
 * world (*out): w itself changes only once that world has stepped, so a
 * step refused for want of memory leaves w as it was. */
static tt_result changed_world(tt_journal *j, tt_world *w, const tt__jentry *e, const char *fn, tt_world **out)
{
    const unsigned long long step = (unsigned long long)(j->played + 1);
    if (!tt__journal_save_world(w, &j->ref, &j->ref_n, &j->ref_cap))
        return tt__fail(w, TT_ENOMEM, "%s: step %llu: cannot save the world (out of memory?); it is unchanged", fn, step);
    const size_t n = tt__delta_length(e->delta, e->delta_n);
    if (!reserve(&j->cur, &j->cur_cap, n ? n : 1))
        return tt__fail(w, TT_ENOMEM, "%s: step %llu: out of memory for a %zu-byte stream; the world is unchanged", fn, step, n);
    /* the coding was checked (tt__journal_read): decoding fails only for want of memory */
    if (!tt__delta_decode(e->delta, e->delta_n, j->ref, j->ref_n, j->cur, n))
        return tt__fail(w, TT_ENOMEM, "%s: step %llu: out of memory decoding the recorded change; the world is unchanged", fn, step);
    j->cur_n = n;
    char why[200];
    *out = tt__world_parse(j->cur, n, w->epoch + 1, why, sizeof why); /* as tt_world_restore does */
    if (!*out)
        return tt__fail(w, strstr(why, "out of memory") ? TT_ENOMEM : TT_EINVAL,
                        "%s: step %llu: the recorded change does not apply to this world (it is not where the "
                        "journal was: an earlier desync, or another world): %s", fn, step, why);
    return TT_OK;
}

/* The step's hash against the record: the first desync kept. */
static tt_replay compare(tt_journal *j, uint64_t h, uint64_t recorded)
{
    if (h == recorded) return TT_REPLAY_SYNC;
    if (!j->desync) {
        j->desync = j->played;
        j->desync_expected = recorded;
        j->desync_got = h;
    }
    return TT_REPLAY_DESYNC;
}

static tt_result play(tt_journal *j, tt_world *w, tt_replay *out, const char *fn)
{
    tt_result r = check(j, w, fn);
    if (r != TT_OK) return r;
    if (!j->playing) return tt__fail(w, TT_ESTATE, "%s: no replay begun (tt_journal_replay_begin)", fn);
    if (j->played >= j->steps) {
        if (out) *out = TT_REPLAY_END;
        return TT_OK;
    }
    size_t at = j->at;
    tt__jentry e;
    if (!tt__journal_read(j->rec, j->rec_n, &at, j->play_dt, j->max_stream, &e))
        return tt__fail(w, TT_EINVAL, "%s: step %llu: its record is not well formed", fn, (unsigned long long)(j->played + 1));
    tt_world *target = w;
    if (e.delta && (r = changed_world(j, w, &e, fn, &target)) != TT_OK) return r;
    const uint64_t before = target->stats.steps;
    r = tt_world_step(target, e.dt);
    char why[sizeof w->error] = "";
    if (r != TT_OK) snprintf(why, sizeof why, "%s", tt_last_error(target));
    if (r != TT_OK && target->stats.steps == before) { /* refused before the step */
        if (target != w) tt_world_destroy(target);
        return tt__fail(w, r, "%s: step %llu: %s", fn, (unsigned long long)(j->played + 1), why);
    }
    if (target != w) tt__world_take(w, target);
    j->at = at;
    j->played++;
    j->play_dt = e.dt;
    const uint64_t h = tt_world_hash(w);
    const tt_replay s = compare(j, h, e.hash);
    if (out) *out = s;
    if (r != TT_OK) /* the step ran short of memory (tt_world_step): played, one step further */
        return tt__fail(w, r, "%s: step %llu: %s", fn, (unsigned long long)j->played, why);
    if (s == TT_REPLAY_SYNC) return TT_OK;
    return tt__fail(w, TT_OK, "%s: desync at step %llu: hash %016llx, the journal has %016llx", fn,
                    (unsigned long long)j->played, (unsigned long long)h, (unsigned long long)e.hash);
}

tt_result tt_journal_replay_step(tt_journal *j, tt_world *w, tt_replay *out)
{
    return play(j, w, out, "tt_journal_replay_step");
}

tt_result tt_journal_replay_all(tt_journal *j, tt_world *w, tt_replay *out)
{
    tt_replay s = TT_REPLAY_SYNC;
    tt_result r = TT_OK;
    while (r == TT_OK && s == TT_REPLAY_SYNC) r = play(j, w, &s, "tt_journal_replay_all");
    if (out) *out = s;
    return r;
}
