/* The fixed-step clock: real frame times in, steps out, time never lost or
 * made; the spiral-of-death guard; pause, time scale, single steps. */
#include "test.h"
#include "tether.h"

#include <stdint.h>

/* A million frames of irregular length (0 … 50 ms, a few long stalls),
 * with the scale changed now and then: what was fed in, times the scale,
 * is what the clock stepped, holds or dropped, to 1e-9 s. */
TEST(clock_a_million_irregular_frames_lose_and_make_no_time)
{
    tt_clock c;
    ENSURE_OK(tt_clock_init(&c, 1.0 / 60, 8));
    uint64_t rng = 12345;
    double fed = 0, fed_c = 0; /* virtual time fed in, compensated (Kahan) so the reference itself does not drift */
    uint64_t steps = 0;
    const double scales[] = {1, 0.25, 4, 1, 0.5};
    for (long f = 0; f < 1000000; f++) {
        if (f % 100000 == 0) ENSURE_OK(tt_clock_set_scale(&c, scales[(f / 100000) % 5]));
        rng = rng * 6364136223846793005ull + 1442695040888963407ull;
        double real = (double)(rng >> 11) / 9007199254740992.0 * 0.05;
        if (f % 50000 == 777) real = 1.5; /* a stall: the guard drops what 8 steps cannot take */
        uint32_t n;
        ENSURE_OK(tt_clock_advance(&c, real, &n));
        ENSURE(n <= 8 && c.acc >= 0 && c.acc < c.dt);
        steps += n;
        double y = real * c.scale - fed_c, t = fed + y;
        fed_c = (t - fed) - y;
        fed = t;
    }
    ENSURE(c.steps == steps);
    ENSURE(c.time == (double)steps * c.dt);
    ENSURE(c.dropped > 0);
    ENSURE_NEAR(c.time + c.acc + c.dropped, fed, 1e-9);
}

TEST(clock_caps_a_long_frame_and_says_so)
{
    tt_clock c;
    ENSURE_OK(tt_clock_init(&c, 0.01, 4));
    uint32_t n;
    ENSURE_OK(tt_clock_advance(&c, 0.025, &n));
    ENSURE(n == 2 && !c.capped && c.dropped == 0);
    ENSURE_NEAR(tt_clock_alpha(&c), 0.5, 1e-9);
    ENSURE_OK(tt_clock_advance(&c, 1.0, &n)); /* 100 steps' worth: 4 taken, the rest dropped, the fraction kept */
    ENSURE(n == 4 && c.capped);
    ENSURE_NEAR(c.dropped, 1.005 - 0.04 - c.acc, 1e-12);
    ENSURE(c.acc < c.dt);
    ENSURE_OK(tt_clock_advance(&c, 0.0, &n));
    ENSURE(n == 0 && !c.capped);
    /* a huge frame at the smallest dt is no endless loop */
    ENSURE_OK(tt_clock_init(&c, TT_MIN_DT, 8));
    ENSURE_OK(tt_clock_advance(&c, 1e12, &n));
    ENSURE(n == 8 && c.capped && c.acc < c.dt);
}

TEST(clock_pause_scale_and_single_steps)
{
    tt_clock c;
    ENSURE_OK(tt_clock_init(&c, 0.1, 8));
    uint32_t n;
    ENSURE_OK(tt_clock_set_paused(&c, true));
    ENSURE_OK(tt_clock_advance(&c, 5.0, &n));
    ENSURE(n == 0 && c.acc == 0 && c.time == 0);
    ENSURE_OK(tt_clock_request_step(&c));
    ENSURE_OK(tt_clock_advance(&c, 5.0, &n));
    ENSURE(n == 1 && c.steps == 1 && c.acc == 0);
    ENSURE_OK(tt_clock_advance(&c, 5.0, &n));
    ENSURE(n == 0);
    ENSURE_OK(tt_clock_set_paused(&c, false));
    ENSURE_OK(tt_clock_set_scale(&c, 0.25));
    ENSURE_OK(tt_clock_advance(&c, 1.0, &n)); /* 0.25 s of virtual time: two steps, 0.05 s left */
    ENSURE(n == 2);
    ENSURE_NEAR(c.acc, 0.05, 1e-12);
    ENSURE_OK(tt_clock_set_scale(&c, 0));
    ENSURE_OK(tt_clock_advance(&c, 100.0, &n));
    ENSURE(n == 0);
}

TEST(clock_refuses_bad_input_and_stays_as_it_was)
{
    tt_clock c;
    ENSURE(tt_clock_init(NULL, 0.1, 8) == TT_EINVAL);
    ENSURE(tt_clock_init(&c, 0.0, 8) == TT_EINVAL);
    ENSURE(tt_clock_init(&c, NAN, 8) == TT_EINVAL);
    ENSURE(tt_clock_init(&c, 0.1, 0) == TT_EINVAL);
    ENSURE_OK(tt_clock_init(&c, 0.1, 8));
    uint32_t n = 99;
    ENSURE_OK(tt_clock_advance(&c, 0.15, &n));
    tt_clock before = c;
    const double bad[] = {-1.0, NAN, INFINITY, -INFINITY};
    for (int k = 0; k < 4; k++) {
        ENSURE(tt_clock_advance(&c, bad[k], &n) == TT_EINVAL && n == 0);
        ENSURE(tt_clock_set_scale(&c, bad[k]) == TT_EINVAL);
    }
    ENSURE(tt_clock_set_scale(&c, 1001) == TT_EINVAL);
    ENSURE(tt_clock_advance(&c, 0.1, NULL) == TT_EINVAL);
    ENSURE(before.acc == c.acc && before.steps == c.steps && before.scale == c.scale && before.time == c.time &&
           before.dropped == c.dropped && before.capped == c.capped && before.paused == c.paused);
    c.dt = -1; /* fields changed by hand into nonsense are refused, not trusted */
    ENSURE(tt_clock_advance(&c, 0.1, &n) == TT_EINVAL && n == 0);
    ENSURE(tt_clock_alpha(&c) == 0.0 && tt_clock_alpha(NULL) == 0.0);
}
