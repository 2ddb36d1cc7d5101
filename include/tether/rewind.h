/* tether — the rewind ring: the last stretch of a world's history, kept as
 * keyframes (snapshots every `every` steps, delta-coded against each other)
 * so that a game can scrub back to any step and play on from there.
 *
 * The contract: a keyframe holds the whole world, but the steps between
 * two keyframes are rebuilt by stepping again from the older one, so the
 * game must feed those steps the inputs it fed them the first time (forces,
 * moved targets, new particles). A game whose per-step inputs are a
 * function of the world's step counter (w.stats.steps) and its own state
 * saved in the world meets it as is; otherwise record the inputs (a replay
 * journal) and play them back. A step that is a keyframe needs nothing. */
#ifndef TETHER_REWIND_H
#define TETHER_REWIND_H

#include "base.h"
#include "world.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct tt_rewind tt_rewind;

typedef struct tt_rewind_def {
    uint32_t every;       ///< a keyframe every this many steps, 1 … 1 000 000; default 10
    uint64_t keep_steps;  ///< the history kept, steps (≥ every); default 600 (10 s at 60 Hz)
    size_t max_bytes;     ///< the most memory the ring holds, bytes (≥ 1024); default 256 MB: oldest keyframes go first
} tt_rewind_def;

TT_API tt_rewind_def tt_rewind_def_default(void);
/// A new, empty ring; NULL when def is out of range or memory ran out
/// (tt_last_error(NULL) says why).
TT_API tt_rewind *tt_rewind_create(const tt_rewind_def *def);
TT_API void tt_rewind_destroy(tt_rewind *r);
/// Call after each step (and once before the first): when the world's
/// step counter is a multiple of `every`, keeps a keyframe of it. A step
/// counter at or before the newest keyframe's starts a new timeline: the
/// keyframes after it are dropped first. Keyframes older than keep_steps,
/// or past max_bytes, are dropped (the newest one always stays). Errors
/// (TT_EINVAL, TT_ENOMEM) are set on w; the ring then holds no keyframe it
/// did not hold before (a new timeline may have dropped some).
TT_API tt_result tt_rewind_record(tt_rewind *r, const tt_world *w);
/// Makes w the newest keyframe at or before `step` (as tt_world_restore)
/// and puts its step in *at (may be NULL): step w from there to `step`
/// with the same inputs. TT_EINVAL when `step` is older than the oldest
/// keyframe or newer than the newest recorded step; w then unchanged.
TT_API tt_result tt_rewind_seek(tt_rewind *r, tt_world *w, uint64_t step, uint64_t *at);
/// The oldest keyframe's step and the newest step recorded (TT_ESTATE when
/// the ring is empty).
TT_API tt_result tt_rewind_get_range(const tt_rewind *r, uint64_t *first, uint64_t *last);
/// Bytes the ring holds now (keyframes, the decoding cache, its tables).
TT_API size_t tt_rewind_get_memory(const tt_rewind *r);
/// Keyframes held now.
TT_API uint32_t tt_rewind_get_count(const tt_rewind *r);

#ifdef __cplusplus
}
#endif

#endif
