/* tether — virtual time: a clock that turns the real time between frames
 * into fixed physics steps. It needs no world: a game asks it each frame
 * how many steps of clock.dt to take, and how far between the last two
 * states to draw. */
#ifndef TETHER_CLOCK_H
#define TETHER_CLOCK_H

#include "base.h"

#ifdef __cplusplus
extern "C" {
#endif

/// A fixed-step clock with an accumulator. Read its fields; change them only
/// through the calls below (they validate). Time is virtual: `scale`
/// seconds of it pass per real second (0.25 slow motion, 4 fast forward);
/// while paused none passes, but a requested single step still runs.
/// Time is never lost or made: every real second fed in ends up, times the
/// scale, in `time` (stepped), `acc` (not yet) or `dropped` (thrown away by
/// the spiral-of-death guard when a frame would need more than `max_steps`).
typedef struct tt_clock {
    double dt;           ///< the physics step, s; (0, TT_MAX_DT]
    uint32_t max_steps;  ///< most steps in one frame, 1 … 1 000 000
    double scale;        ///< virtual seconds per real one, [0, 1000]
    bool paused;
    bool single;         ///< a single step requested (runs at the next advance, paused or not)
    double acc;          ///< virtual time not yet stepped, s, [0, dt)
    double time;         ///< virtual time stepped, s (steps × dt)
    uint64_t steps;      ///< steps taken
    double dropped;      ///< virtual time the guard threw away, s
    bool capped;         ///< the last advance hit max_steps and dropped time
} tt_clock;

/// A clock at time 0: dt > 0 (≤ TT_MAX_DT), max_steps ≥ 1 (8 is a good
/// default at 60 Hz), scale 1, running.
TT_API tt_result tt_clock_init(tt_clock *c, double dt, uint32_t max_steps);
/// Feeds `real` seconds (≥ 0, finite) of the frame; *steps gets how many
/// steps of c->dt to take now (0 … max_steps, or one more for a requested
/// single step). On an error *steps is 0 and the clock is unchanged.
TT_API tt_result tt_clock_advance(tt_clock *c, double real, uint32_t *steps);
/// How far the world is from its last step towards its next, [0, 1): draw
/// the previous state blended with the current one by this much
/// (tt_debug_draw.alpha, with tt_world_set_interpolation on; the runner's window does).
TT_API double tt_clock_alpha(const tt_clock *c);
TT_API tt_result tt_clock_set_scale(tt_clock *c, double scale);
TT_API tt_result tt_clock_set_paused(tt_clock *c, bool paused);
/// One step at the next advance, even while paused (the accumulator keeps
/// what it had).
TT_API tt_result tt_clock_request_step(tt_clock *c);

#ifdef __cplusplus
}
#endif

#endif
