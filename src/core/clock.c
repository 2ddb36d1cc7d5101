/* tether — the fixed-step clock. The accumulator stays below dt between
 * frames, so a frame rounds only sums of numbers below (max_steps + 1)·dt,
 * each by half an ulp of them (taking the last dt away is even exact,
 * Sterbenz: dt ≤ acc < 2·dt): over a million frames at 60 Hz, under 1e-12 s.
 * Time is kept as steps × dt, never summed. */
#include "core/internal.h"
#include "tether/clock.h"

#define TT__CLOCK_MAX_STEPS 1000000u
#define TT__CLOCK_MAX_SCALE 1000.0

tt_result tt_clock_init(tt_clock *c, double dt, uint32_t max_steps)
{
    if (!c) return tt__fail(NULL, TT_EINVAL, "tt_clock_init: clock is NULL");
    if (!tt__in_range(dt, TT_MIN_DT, TT_MAX_DT))
        return tt__fail(NULL, TT_EINVAL, "tt_clock_init: dt must be in [%g, %g], got %g", TT_MIN_DT, TT_MAX_DT, dt);
    if (max_steps < 1 || max_steps > TT__CLOCK_MAX_STEPS)
        return tt__fail(NULL, TT_EINVAL, "tt_clock_init: max_steps must be in [1, %u], got %u", TT__CLOCK_MAX_STEPS, max_steps);
    *c = (tt_clock){.dt = dt, .max_steps = max_steps, .scale = 1.0};
    return TT_OK;
}

/* A clock whose fields were changed by hand into something the calls would refuse. */
static bool clock_ok(const tt_clock *c)
{
    return c && tt__in_range(c->dt, TT_MIN_DT, TT_MAX_DT) && c->max_steps >= 1 && c->max_steps <= TT__CLOCK_MAX_STEPS &&
           tt__in_range(c->scale, 0.0, TT__CLOCK_MAX_SCALE) && c->acc >= 0.0 && c->acc < c->dt;
}

tt_result tt_clock_advance(tt_clock *c, double real, uint32_t *steps)
{
    if (steps) *steps = 0;
    if (!clock_ok(c)) return tt__fail(NULL, TT_EINVAL, "tt_clock_advance: clock is NULL or not made by tt_clock_init");
    if (!steps) return tt__fail(NULL, TT_EINVAL, "tt_clock_advance: steps is NULL");
    if (!tt__in_range(real, 0.0, TT_MAX_VALUE))
        return tt__fail(NULL, TT_EINVAL, "tt_clock_advance: real must be finite and >= 0, got %g", real);
    uint32_t n = 0;
    c->capped = false;
    if (!c->paused) {
        double acc = c->acc + real * c->scale;
        /* how many whole steps fit: by division first (a long frame at a
         * tiny dt would loop for ever), then exactly by subtraction */
        double whole = floor(acc / c->dt);
        if (whole > c->max_steps) {
            double keep = acc - c->max_steps * c->dt;
            c->dropped += keep - fmod(keep, c->dt);
            acc = fmod(keep, c->dt) + c->max_steps * c->dt;
            c->capped = true;
        }
        while (acc >= c->dt && n < c->max_steps) {
            acc -= c->dt;
            n++;
        }
        if (acc >= c->dt) { /* a rounding left a whole step: the guard's, like the rest it cut */
            c->dropped += acc;
            acc = 0.0;
        }
        c->acc = acc;
    }
    if (c->single) {
        n++;
        c->single = false;
    }
    c->steps += n;
    c->time = (double)c->steps * c->dt;
    *steps = n;
    return TT_OK;
}

double tt_clock_alpha(const tt_clock *c) { return clock_ok(c) ? c->acc / c->dt : 0.0; }

tt_result tt_clock_set_scale(tt_clock *c, double scale)
{
    if (!clock_ok(c)) return tt__fail(NULL, TT_EINVAL, "tt_clock_set_scale: clock is NULL or not made by tt_clock_init");
    if (!tt__in_range(scale, 0.0, TT__CLOCK_MAX_SCALE))
        return tt__fail(NULL, TT_EINVAL, "tt_clock_set_scale: scale must be in [0, %g], got %g", TT__CLOCK_MAX_SCALE, scale);
    c->scale = scale;
    return TT_OK;
}

tt_result tt_clock_set_paused(tt_clock *c, bool paused)
{
    if (!clock_ok(c)) return tt__fail(NULL, TT_EINVAL, "tt_clock_set_paused: clock is NULL or not made by tt_clock_init");
    c->paused = paused;
    return TT_OK;
}

tt_result tt_clock_request_step(tt_clock *c)
{
    if (!clock_ok(c)) return tt__fail(NULL, TT_EINVAL, "tt_clock_request_step: clock is NULL or not made by tt_clock_init");
    c->single = true;
    return TT_OK;
}
