/* tests/fuzz/fuzz_c_log.c — the calls as C-like lines: the last FZ_RING
 * kept in memory, printed on a failure or a crash (write(2) only, so a
 * sanitizer's death callback or a signal handler may print them), and all
 * of them as they happen with FUZZ_TRACE=1. */
#include "fuzz_c.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#define FZ_RING 64
#define FZ_LINE 1024

static char ring[FZ_RING][FZ_LINE];
static unsigned long long ring_next; /* lines logged so far */
static unsigned long long traced;    /* lines printed by the trace so far */

void fz_log(fz *f, const char *fmt, ...)
{
    char *line = ring[ring_next % FZ_RING];
    int n = snprintf(line, FZ_LINE, "#%llu ", (unsigned long long)f->call);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line + n, FZ_LINE - (size_t)n, fmt, ap);
    va_end(ap);
    ring_next++;
    if (f->trace) { /* before the call, so a crash in it still shows it */
        fputs(line, stdout);
        fputc('\n', stdout);
        fflush(stdout);
        traced = ring_next;
    }
}

void fz_log_more(fz *f, const char *fmt, ...)
{
    if (!ring_next) return;
    char *line = ring[(ring_next - 1) % FZ_RING];
    size_t n = strlen(line);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line + n, FZ_LINE - n, fmt, ap);
    va_end(ap);
    if (f->trace && traced == ring_next) {
        printf("    %s\n", line + n);
        fflush(stdout);
    }
}

/* The first handles of a bulk call's array, appended to its line. */
void fz_log_ids(fz *f, const tt_particle *ids, uint32_t n)
{
    if (!ids) return;
    fz_log_more(f, " /* ids");
    for (uint32_t i = 0; i < n && i < 24; i++) fz_log_more(f, " {%u, %#x}", ids[i].index, ids[i].gen);
    fz_log_more(f, "%s */", n > 24 ? " ..." : "");
}

static void put(int fd, const char *s)
{
    size_t n = strlen(s);
    while (n) {
        ssize_t k = write(fd, s, n);
        if (k <= 0) return;
        s += k;
        n -= (size_t)k;
    }
}

void fz_log_dump(int fd, unsigned lines)
{
    if (lines > FZ_RING) lines = FZ_RING;
    unsigned long long first = ring_next > lines ? ring_next - lines : 0;
    put(fd, "fuzz_c: the last calls:\n");
    for (unsigned long long i = first; i < ring_next; i++) {
        put(fd, "    ");
        put(fd, ring[i % FZ_RING]);
        put(fd, "\n");
    }
}

/* Short-lived strings for log lines: a ring of buffers, enough for the
 * longest line's arguments. */
static char *scratch(void)
{
    static char buf[96][128];
    static unsigned next;
    return buf[next++ % 96];
}

const char *fz_d(double v)
{
    char *s = scratch();
    if (isnan(v)) snprintf(s, 128, "%sNAN", signbit(v) ? "-" : "");
    else if (isinf(v)) snprintf(s, 128, "%sINFINITY", v < 0 ? "-" : "");
    else if (v == 0.0) snprintf(s, 128, "%s0.0", signbit(v) ? "-" : "");
    else snprintf(s, 128, "%.17g", v);
    return s;
}

const char *fz_u(unsigned long long v)
{
    char *s = scratch();
    snprintf(s, 128, "%llu", v);
    return s;
}

const char *fz_v(tt_vec2 v)
{
    char *s = scratch();
    snprintf(s, 128, "(tt_vec2){%s, %s}", fz_d(v.x), fz_d(v.y));
    return s;
}

const char *fz_wn(fz *f, const tt_world *w)
{
    if (!w) return "NULL";
    for (int i = 0; i < FZ_WORLDS; i++) {
        if (f->slots[i].w == w) {
            char *s = scratch();
            snprintf(s, 128, "w%d", f->slots[i].name);
            return s;
        }
    }
    return "w?";
}

const char *fz_hn(fz_h h, tt_kind kind)
{
    static const char *types[] = { "?", "tt_particle", "tt_spring", "tt_constraint", "tt_shape", "tt_composite", "tt_terrain" };
    char *s = scratch();
    snprintf(s, 128, "(%s){%u, %#x}", types[kind <= TT_KIND_TERRAIN ? kind : 0], h.index, h.gen);
    return s;
}

const char *fz_res_name(tt_result r)
{
    switch (r) {
    case TT_OK: return "TT_OK";
    case TT_EINVAL: return "TT_EINVAL";
    case TT_ESTALE: return "TT_ESTALE";
    case TT_ENOMEM: return "TT_ENOMEM";
    case TT_ESTATE: return "TT_ESTATE";
    }
    return "(not a tt_result)";
}
