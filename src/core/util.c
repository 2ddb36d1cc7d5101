/* tether — the engine's utilities, a leaf every part may call and that
 * calls none: error messages, the clock for stage timings, array growth,
 * and the note of memory refused inside a step. They live apart from the
 * features so that no feature depends on world.c (tests/layout.sh). */
#include "internal.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static _Thread_local char g_error[256];

tt_result tt__fail(const tt_world *w, tt_result code, const char *fmt, ...)
{
    /* The message buffer is diagnostic state, not simulation state. */
    char *buf = w ? ((tt_world *)w)->error : g_error;
    size_t n = w ? sizeof w->error : sizeof g_error;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf, n, fmt, ap);
    va_end(ap);
    return code;
}

const char *tt_last_error(const tt_world *w) { return w ? w->error : g_error; }

double tt__now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

void tt__step_oom(tt_world *w, const char *what)
{
    if (!w->scr.step_oom) w->scr.step_oom = what; /* the first says the most */
}

bool tt__grow(void **p, uint32_t *cap, uint32_t need, size_t elem)
{
    if (need <= *cap) return true;
    uint32_t n = *cap ? *cap : 16;
    while (n < need) n = n > UINT32_MAX / 2 ? need : n * 2;
    void *q = realloc(*p, (size_t)n * elem);
    if (!q) return false;
    *p = q;
    *cap = n;
    return true;
}
