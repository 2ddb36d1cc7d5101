/* tether — a tiny test harness: TEST(name) registers itself; ENSURE* check.
 * `build/test_c [filter]` runs the tests whose name contains filter. */
#ifndef TETHER_TEST_H
#define TETHER_TEST_H

#include <math.h>
#include <stdio.h>

typedef void (*tt_test_fn)(void);
void tt_test_register(const char *name, const char *file, tt_test_fn fn);
void tt_test_fail(const char *file, int line, const char *fmt, ...);

#define TEST(name)                                                               \
    static void test_##name(void);                                               \
    __attribute__((constructor)) static void register_##name(void)               \
    {                                                                            \
        tt_test_register(#name, __FILE__, test_##name);                          \
    }                                                                            \
    static void test_##name(void)

/* A failed check reports and returns from the test (later checks would only repeat it). */
#define ENSURE(c)                                                                \
    do { if (!(c)) { tt_test_fail(__FILE__, __LINE__, "ENSURE(%s)", #c); return; } } while (0)
#define ENSURE_NEAR(a, b, tol)                                                   \
    do {                                                                         \
        double a_ = (a), b_ = (b), t_ = (tol);                                   \
        if (!(fabs(a_ - b_) <= t_)) {                                            \
            tt_test_fail(__FILE__, __LINE__, "ENSURE_NEAR(%s, %s, %s): %.17g vs %.17g (diff %.3g)", \
                         #a, #b, #tol, a_, b_, fabs(a_ - b_));                   \
            return;                                                              \
        }                                                                        \
    } while (0)
#define ENSURE_OK(r) ENSURE((r) == TT_OK)

#endif
