/* tests/fuzz/fuzz_c_clock.c — wrappers of tether/clock.h on a pool of two
 * clocks (all zero at first: not made by tt_clock_init, so refused), with
 * plausible and hostile dt, max_steps, frame times and scales, and now and
 * then a field changed by hand into something the calls must refuse. A
 * refused call leaves its clock as it was, byte for byte; after every call
 * the accumulator is finite and in [0, dt), no advance gives more than
 * max_steps steps (one more for a requested single step), time is steps·dt,
 * and no time is lost or made: time + acc + dropped grows by real·scale
 * (nothing while paused). */
#include "fuzz_c.h"

#include <limits.h>
#include <math.h>
#include <string.h>

static tt_clock *pick(fz *f, int *slot)
{
    *slot = fz_chance(f, 3) ? -1 : (int)fz_below(f, FZ_CLOCKS);
    if (*slot < 0) {
        f->must_fail = true;
        f->why_must = "a NULL clock";
        return NULL;
    }
    tt_clock *c = &f->clocks[*slot];
    if (fz_chance(f, 2)) { /* a field changed by hand */
        switch (fz_below(f, 5)) {
        case 0: c->acc = fz_chance(f, 50) ? -1e-9 : c->dt; break;
        case 1: { /* refused: a valid dt changed by hand leaves time != steps·dt until the next advance (seed 20261210) */
            static const double bad[] = { 0.0, -0.0, -1.0, NAN, INFINITY, -INFINITY, 9.99e-10, 10.000001, 1e300, 4.9e-324 };
            c->dt = bad[fz_below(f, sizeof bad / sizeof bad[0])];
            break;
        }
        case 2: c->scale = fz_chance(f, 50) ? NAN : 1001; break;
        case 3: c->max_steps = fz_chance(f, 50) ? 0 : 1000001; break;
        default: c->acc = NAN; break;
        }
    }
    /* what the calls accept (clock.c's own test, restated) */
    if (!(c->dt >= TT_MIN_DT && c->dt <= TT_MAX_DT && c->max_steps >= 1 && c->max_steps <= 1000000 && c->scale >= 0 &&
          c->scale <= 1000 && c->acc >= 0 && c->acc < c->dt)) {
        f->must_fail = true;
        f->why_must = "a clock not made by tt_clock_init";
    }
    return c;
}

static void check(fz *f, const tt_clock *c)
{
    if (!(c->acc >= 0 && c->acc < c->dt)) fz_fail(f, "the clock's accumulator is %s (dt %s)", fz_d(c->acc), fz_d(c->dt));
    if (!(c->dropped >= 0 && isfinite(c->dropped))) fz_fail(f, "the clock dropped %s s", fz_d(c->dropped));
    if (c->time != (double)c->steps * c->dt) fz_fail(f, "the clock's time %s is not steps x dt", fz_d(c->time));
}

static void refused(fz *f, tt_result r, const tt_clock *c, const tt_clock *before)
{
    fz_log_more(f, " -> %s", fz_res_name(r));
    if (r != TT_OK) {
        fz_log_more(f, " \"%.200s\"", tt_last_error(NULL));
        f->failed = true;
        if (c && memcmp(c, before, sizeof *c) != 0) fz_fail(f, "a refused clock call changed the clock");
    }
    else check(f, c);
}

static void c_clock_init(fz *f)
{
    int s;
    tt_clock *c = pick(f, &s);
    f->must_fail = !c;
    double dt = fz_dt(f);
    uint32_t max = fz_chance(f, 85) ? 1 + fz_below(f, 16) : (uint32_t[]){ 0, 1000000, 1000001, UINT32_MAX }[fz_below(f, 4)];
    if (!(dt >= TT_MIN_DT && dt <= TT_MAX_DT) || max < 1 || max > 1000000) f->must_fail = true, f->why_must = "a bad dt or max_steps";
    tt_clock before = c ? *c : (tt_clock){ 0 };
    fz_log(f, "tt_clock_init(%s, %s, %u)", s < 0 ? "NULL" : s ? "&c1" : "&c0", fz_d(dt), max);
    FZ_HIT(f, tt_clock_init);
    tt_result r = tt_clock_init(c, dt, max);
    refused(f, r, c, &before);
    if (r == TT_OK && (c->dt != dt || c->max_steps != max || c->scale != 1 || c->acc != 0 || c->steps || c->paused))
        fz_fail(f, "tt_clock_init made a clock that is not at time 0");
}

static void c_clock_advance(fz *f)
{
    int s;
    tt_clock *c = pick(f, &s);
    unsigned r0 = fz_below(f, 100);
    double real = r0 < 70 ? fz_real(f, 0, 0.1) : r0 < 80 ? 0.0 : r0 < 90 ? fz_real(f, 1, 1e4) : fz_nasty(f);
    bool nsteps = fz_chance(f, 3);
    if (!(real >= 0 && real <= TT_MAX_VALUE) || nsteps) f->must_fail = true, f->why_must = "a bad frame time or out";
    tt_clock before = c ? *c : (tt_clock){ 0 };
    uint32_t steps = 77;
    fz_log(f, "tt_clock_advance(%s, %s, %s)", s < 0 ? "NULL" : s ? "&c1" : "&c0", fz_d(real), nsteps ? "NULL" : "&steps");
    FZ_HIT(f, tt_clock_advance);
    tt_result r = tt_clock_advance(c, real, nsteps ? NULL : &steps);
    refused(f, r, c, &before);
    if (r != TT_OK) {
        if (!nsteps && steps != 0) fz_fail(f, "a refused advance gave %u steps", steps);
        return;
    }
    fz_log_more(f, " %u steps, acc %s", steps, fz_d(c->acc));
    if (steps > before.max_steps + (before.single ? 1u : 0u) || c->steps != before.steps + steps)
        fz_fail(f, "an advance gave %u steps (max_steps %u, single %d)", steps, before.max_steps, before.single);
    double fed = before.paused ? 0 : real * before.scale;
    double grew = (c->time + c->acc + c->dropped) - (before.time + before.acc + before.dropped);
    double single = before.single ? before.dt : 0; /* a requested step runs on time of its own */
    double tol = 1e-9 * (1 + fed + c->time + c->dropped);
    if (!(fabs(grew - fed - single) <= tol))
        fz_fail(f, "an advance of %s s of virtual time added %s", fz_d(fed), fz_d(grew));
}

static void c_clock_alpha(fz *f)
{
    int s;
    tt_clock *c = pick(f, &s);
    bool bad = f->must_fail;
    f->must_fail = false; /* no failure channel: 0 for a bad clock */
    tt_clock before = c ? *c : (tt_clock){ 0 };
    fz_log(f, "tt_clock_alpha(%s)", s < 0 ? "NULL" : s ? "&c1" : "&c0");
    FZ_HIT(f, tt_clock_alpha);
    double a = tt_clock_alpha(c);
    fz_log_more(f, " -> %s", fz_d(a));
    if (!(a >= 0 && a < 1) || (bad && a != 0)) fz_fail(f, "tt_clock_alpha is %s", fz_d(a));
    if (c && memcmp(c, &before, sizeof *c) != 0) fz_fail(f, "tt_clock_alpha changed the clock");
}

static void c_clock_set_scale(fz *f)
{
    int s;
    tt_clock *c = pick(f, &s);
    double scale = fz_chance(f, 80) ? fz_real(f, 0, 8) : fz_chance(f, 30) ? 0.0 : fz_nasty(f);
    if (!(scale >= 0 && scale <= 1000)) f->must_fail = true, f->why_must = "a bad scale";
    tt_clock before = c ? *c : (tt_clock){ 0 };
    fz_log(f, "tt_clock_set_scale(%s, %s)", s < 0 ? "NULL" : s ? "&c1" : "&c0", fz_d(scale));
    FZ_HIT(f, tt_clock_set_scale);
    tt_result r = tt_clock_set_scale(c, scale);
    refused(f, r, c, &before);
    if (r == TT_OK && c->scale != scale) fz_fail(f, "the scale is %s, not %s", fz_d(c->scale), fz_d(scale));
}

static void c_clock_set_paused(fz *f)
{
    int s;
    tt_clock *c = pick(f, &s);
    bool p = fz_chance(f, 40);
    tt_clock before = c ? *c : (tt_clock){ 0 };
    fz_log(f, "tt_clock_set_paused(%s, %d)", s < 0 ? "NULL" : s ? "&c1" : "&c0", p);
    FZ_HIT(f, tt_clock_set_paused);
    tt_result r = tt_clock_set_paused(c, p);
    refused(f, r, c, &before);
    if (r == TT_OK && c->paused != p) fz_fail(f, "the clock is not paused as asked");
}

static void c_clock_request_step(fz *f)
{
    int s;
    tt_clock *c = pick(f, &s);
    tt_clock before = c ? *c : (tt_clock){ 0 };
    fz_log(f, "tt_clock_request_step(%s)", s < 0 ? "NULL" : s ? "&c1" : "&c0");
    FZ_HIT(f, tt_clock_request_step);
    tt_result r = tt_clock_request_step(c);
    refused(f, r, c, &before);
    if (r == TT_OK && !c->single) fz_fail(f, "no single step requested");
}

const fz_entry fz_clock_entries[] = {
    { "tt_clock_init", c_clock_init, 1 },
    { "tt_clock_advance", c_clock_advance, 3 },
    { "tt_clock_alpha", c_clock_alpha, 1 },
    { "tt_clock_set_scale", c_clock_set_scale, 1 },
    { "tt_clock_set_paused", c_clock_set_paused, 1 },
    { "tt_clock_request_step", c_clock_request_step, 1 },
    { NULL, NULL, 0 },
};
