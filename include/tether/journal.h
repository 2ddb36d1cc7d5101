/* tether — replay journals: record a world's session, save it to a file,
 * and play it back later (in this process or another, into the same world
 * or a new one) step for step, with desync detection.
 *
 * What a journal holds: a snapshot of the world when recording started
 * (the snapshot stream, tt_world_save), then per step the step's dt, the
 * changes that calls made to the world since the end of the step before,
 * and the world hash (tt_world_hash) after the step.
 *
 * How the changes are found: not by hooking each public call, but by their
 * effect. At the start of each step the world is saved to a stream and
 * compared with the stream kept at the end of the step before; when they
 * differ, the byte delta between the two (the rewind ring's codec) is what
 * the journal records. So every call that changes a world, present or
 * future, C or Lua, is journaled per step, and nothing a call did can be
 * missed: what is not in the snapshot stream is not world state. The dt
 * is the step's only input besides the world; substeps, iterations and
 * every other setting are in the stream, so their changes are in the delta.
 * The recording world steps on as it would unrecorded: a world and a copy
 * loaded from its stream step alike (the random-call test of
 * tests/lua/test_journal.lua holds the engine to that).
 *
 * Cost: paid only while a world is journaled (two saves, a compare and a
 * hash per step, and the delta when calls changed the world); a world that never
 * journals has two NULL checks per step and keeps every hash. Memory: the
 * snapshot, two streams of work space, and per step about 10 bytes when no
 * call changed anything (a flag byte, the hash, the dt when it changed)
 * plus the delta when one did; bounded by max_bytes, where recording stops
 * (the world steps on; tt_journal_info.full says so).
 *
 * Replay: tt_journal_replay_begin restores the world to the snapshot; each
 * tt_journal_replay_step decodes the step's delta (if any) against the
 * world's current stream and restores it in place, steps with the recorded
 * dt and compares the hash with the recorded one. A mismatch is a desync:
 * the step is reported (the first one is kept in tt_journal_info) and the
 * replay may go on. Stepping one step per call lets a game play a replay
 * back at its own speed; tt_journal_replay_all runs to the end.
 *
 * User values of the Lua binding and anything a game keeps outside the
 * world are not in a journal. Journal files and byte strings are in this
 * machine's byte order (as the snapshot stream), and a file is refused
 * when truncated, corrupted, foreign or of another version. */
#ifndef TETHER_JOURNAL_H
#define TETHER_JOURNAL_H

#include "base.h"
#include "world.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct tt_journal tt_journal;

/// The largest snapshot stream a journal records or plays (bytes): a
/// world past it stops recording (full); a delta that decodes to more is refused.
#define TT_JOURNAL_MAX_STREAM ((size_t)1 << 30)

typedef struct tt_journal_def {
    size_t max_bytes; ///< the most memory the journal holds, bytes (≥ 1024); default 256 MB: recording stops there
} tt_journal_def;

/// What a journal holds and where its replay is.
typedef struct tt_journal_info {
    uint64_t steps;           ///< steps recorded
    uint64_t changed;         ///< of them, steps that calls changed the world before (a delta recorded)
    size_t bytes;             ///< memory held now: snapshot, per-step record, work space
    size_t record_bytes;      ///< of it, the per-step record (bytes per step = record_bytes / steps)
    size_t snapshot_bytes;    ///< of it, the first snapshot
    bool recording;           ///< attached to a world and recording its steps
    bool full;                ///< recording stopped at max_bytes or for want of memory
    uint64_t replayed;        ///< steps the replay has played (0 before its first step)
    uint64_t desync;          ///< the first replayed step (1 = the journal's first) whose hash was not the recorded one; 0: none
    uint64_t desync_expected; ///< that step's recorded hash
    uint64_t desync_got;      ///< the hash the replay got there
} tt_journal_info;

/// What one replay step did.
typedef enum tt_replay {
    TT_REPLAY_END = 0,    ///< the replay is at the journal's end: nothing done
    TT_REPLAY_SYNC = 1,   ///< a step played; the world's hash is the recorded one
    TT_REPLAY_DESYNC = 2, ///< a step played; its hash differs from the recorded one
} tt_replay;

TT_API tt_journal_def tt_journal_def_default(void);
/// Starts journaling w: snapshots it now and records each of its next steps
/// until tt_journal_stop (or tt_journal_destroy, or w's destruction). NULL
/// when def is out of range, w is already journaled, cannot be saved, or
/// memory ran out (tt_last_error(w) says why; w is unchanged either way).
TT_API tt_journal *tt_journal_start(tt_world *w, const tt_journal_def *def);
/// Stops recording; the journal keeps what it holds (save it, replay it).
/// TT_OK also when it was not recording.
TT_API tt_result tt_journal_stop(tt_journal *j);
/// Stops recording and frees the journal. NULL is allowed.
TT_API void tt_journal_destroy(tt_journal *j);
/// What the journal holds and where its replay is.
TT_API tt_result tt_journal_get_info(const tt_journal *j, tt_journal_info *out);

/// Makes w the journal's first snapshot (as tt_world_restore, w keeps its
/// address) and puts the replay before the first step. TT_ESTATE while the
/// journal records; w unchanged on any error.
TT_API tt_result tt_journal_replay_begin(tt_journal *j, tt_world *w);
/// Plays the next step on w (the world the replay began on): applies the
/// recorded change, steps with the recorded dt, compares the hash; *out
/// (may be NULL) says which of TT_REPLAY_* happened. TT_ESTATE before
/// tt_journal_replay_begin or while recording; TT_EINVAL when the recorded
/// change cannot be applied to w (w is not where the journal was: an
/// earlier desync, or another world) and TT_ENOMEM, each with w unchanged
/// and the replay where it was.
TT_API tt_result tt_journal_replay_step(tt_journal *j, tt_world *w, tt_replay *out);
/// Plays steps until the end or the first desync (*out says which; may be
/// NULL): call again to play on past a desync. Errors as tt_journal_replay_step.
TT_API tt_result tt_journal_replay_all(tt_journal *j, tt_world *w, tt_replay *out);

/// The journal as bytes (a header with its format version, the snapshot,
/// the per-step record) into buf[0..cap), its size into *size (may be
/// NULL); with cap too small (buf NULL and cap 0 to ask) sets *size and
/// returns TT_ENOMEM. A recording journal gives the steps recorded so far.
TT_API tt_result tt_journal_save(const tt_journal *j, void *buf, size_t cap, size_t *size);
/// A journal from bytes of tt_journal_save, checked whole (the snapshot
/// loads, every step's record and delta is well formed); NULL when refused
/// (tt_last_error(NULL) says why).
TT_API tt_journal *tt_journal_load(const void *data, size_t size);
/// The bytes behind the snapshot files' header (signature, format and engine
/// version, length, checksum), written to path.tmp and renamed over path.
TT_API tt_result tt_journal_save_file(const tt_journal *j, const char *path);
/// A journal from a file; NULL when the file cannot be read, is not a
/// tether journal file, is truncated, padded, corrupted or of another
/// version (tt_last_error(NULL) names the file and says why).
TT_API tt_journal *tt_journal_load_file(const char *path);

#ifdef __cplusplus
}
#endif

#endif
