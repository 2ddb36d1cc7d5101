/* tether — sleeping's section of the snapshot ('SLEP'): the settings, and
 * per live particle its time at rest, the time since its anchor, the
 * anchor, its island, whether something held it in the last step and its
 * smoothed position, so a restored world falls asleep and wakes exactly as
 * the original would.
 *
 * The section has no version of its own, and the builds before the present
 * layout wrote fewer fields a particle (28 bytes: rest, anchor, island; then
 * 36: the time since the anchor after rest; then 40: the held flag last).
 * The payload's length tells the four apart (its 20-byte head, then the
 * same record for every live particle), so the streams those builds saved
 * still load. Their missing fields get what the rest test would have held:
 * the anchor of the old rest test was where the rest began, so the time
 * since it is the time at rest; a particle that was resting was held in the
 * step it was saved after; its smoothed position is where it is. */
#include "stream.h"
#include "sleep_internal.h"

#include <stdlib.h>

enum { HEAD = 8 + 8 + 4, REC_OLD = 8 + 8 + 8 + 4, REC_HELD = REC_OLD + 8, REC_FLAG = REC_HELD + 4, REC_NOW = REC_FLAG + 16 };

void tt__sleep_save(const tt_world *w, const void *self, tt__sink *snk)
{
    const tt__sleep *s = self;
    tt__put_f64(snk, s->speed);
    tt__put_f64(snk, s->time);
    tt__put_u32(snk, s->next_island);
    for (uint32_t i = 0; i < w->ppool.count; i++) {
        if (!(w->flags[i] & TT__PF_ALIVE)) continue;
        tt__put_f64(snk, i < s->cap ? s->rest[i] : 0.0);
        tt__put_f64(snk, i < s->cap ? s->held[i] : 0.0);
        tt__put_f64(snk, i < s->cap ? s->ax[i] : 0.0);
        tt__put_f64(snk, i < s->cap ? s->ay[i] : 0.0);
        tt__put_u32(snk, i < s->cap ? s->island[i] : 0);
        tt__put_u32(snk, i < s->cap && s->seen[i] == s->tick); /* held in the last step */
        tt__put_f64(snk, i < s->cap ? s->mx[i] : 0.0); /* as the arrays grown for it will hold */
        tt__put_f64(snk, i < s->cap ? s->my[i] : 0.0);
    }
}

/* The bytes a particle's record takes in this payload: REC_NOW, or an older
 * layout's; 0 when the length fits none (the reader then fails on it). */
static size_t record_size(const tt_world *w, const tt__source *src)
{
    uint32_t alive = 0;
    for (uint32_t i = 0; i < w->ppool.count; i++) alive += (w->flags[i] & TT__PF_ALIVE) != 0;
    if (alive == 0 || src->len - src->at < HEAD) return REC_NOW;
    const size_t body = src->len - src->at - HEAD;
    static const size_t sizes[] = {REC_NOW, REC_FLAG, REC_HELD, REC_OLD};
    for (int k = 0; k < 4; k++)
        if (body == (size_t)alive * sizes[k]) return sizes[k];
    return REC_NOW;
}

/* One particle's record into slot i; false when it does not hold together. */
static bool load_one(tt_world *w, tt__sleep *s, tt__source *src, uint32_t i, size_t rec)
{
    s->rest[i] = tt__get_num(src, 0.0, TT_MAX_VALUE, "time at rest");
    s->held[i] = rec >= REC_HELD ? tt__get_num(src, 0.0, TT_MAX_VALUE, "time since the anchor") : s->rest[i];
    s->ax[i] = tt__get_num(src, -TT_DIVERGED, TT_DIVERGED, "the anchor");
    s->ay[i] = tt__get_num(src, -TT_DIVERGED, TT_DIVERGED, "the anchor");
    s->island[i] = tt__get_u32(src);
    const uint32_t held = rec >= REC_FLAG ? tt__get_u32(src) : s->rest[i] > 0.0;
    s->mx[i] = rec == REC_NOW ? tt__get_num(src, -TT_DIVERGED, TT_DIVERGED, "the smoothed position") : w->px[i];
    s->my[i] = rec == REC_NOW ? tt__get_num(src, -TT_DIVERGED, TT_DIVERGED, "the smoothed position") : w->py[i];
    if (held > 1) return tt__src_fail(src, "sleep: particle %u held flag %u", i, held);
    s->seen[i] = held ? 2 : 0;
    const bool asleep = (w->flags[i] & TT__PF_ASLEEP) != 0;
    if (asleep != (s->island[i] != 0) || (asleep && (s->rest[i] != 0.0 || s->held[i] != 0.0)))
        return tt__src_fail(src, "sleep: particle %u is %s but its island is %u", i, asleep ? "asleep" : "awake", s->island[i]);
    s->asleep += asleep;
    return true;
}

void *tt__sleep_load(tt_world *w, tt__source *src)
{
    tt__sleep *s = calloc(1, sizeof *s);
    if (!s || !tt__sleep_grow(s, w->ppool.count ? w->ppool.count : 1)) {
        tt__sleep_destroy(w, s);
        tt__src_fail(src, "out of memory for the sleep state");
        return NULL;
    }
    const size_t rec = record_size(w, src);
    s->speed = tt__get_num(src, 0.0, TT_MAX_VALUE, "sleep speed");
    s->time = tt__get_num(src, 0.0, TT_MAX_VALUE, "sleep time");
    s->tick = 2;
    s->next_island = tt__get_u32(src);
    if (s->next_island == 0) tt__src_fail(src, "sleep: island counter 0");
    for (uint32_t i = 0; i < w->ppool.count && !src->failed; i++)
        if (w->flags[i] & TT__PF_ALIVE) load_one(w, s, src, i, rec);
    if (!src->failed && !tt__sleep_link_rings(w, s)) tt__src_fail(src, "out of memory for the sleep state");
    if (src->failed) {
        tt__sleep_destroy(w, s);
        return NULL;
    }
    return s;
}
