/* tether — the byte-stream fuzzers' shared parts: see fuzz_bytes.h. */
#include "fuzz_bytes.h"
#include "test.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static uint64_t rng = 1;

uint64_t fuzz_next(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return rng * 0x2545F4914F6CDD1Dull;
}

size_t fuzz_below(size_t n) { return n ? (size_t)(fuzz_next() % n) : 0; }

fuzz_buf fuzz_mutate(const fuzz_buf *base, const fuzz_buf *other, size_t keep, void (*put_field)(fuzz_buf *))
{
    const size_t cap = base->n + other->n + 64;
    fuzz_buf b = {malloc(cap), base->n};
    if (!b.p) return b;
    memcpy(b.p, base->p, base->n);
    for (int k = 1 + (int)fuzz_below(3); k > 0 && b.n > keep; k--) {
        size_t at = keep + fuzz_below(b.n - keep), len = 1 + fuzz_below(16);
        if (at + len > b.n) len = b.n - at;
        switch (fuzz_below(6)) {
        case 0: b.p[keep + fuzz_below(b.n - keep)] ^= (unsigned char)(1u << fuzz_below(8)); break;
        case 1: put_field(&b); break;
        case 2: /* delete */
            memmove(b.p + at, b.p + at + len, b.n - at - len);
            b.n -= len;
            break;
        case 3: /* repeat */
            if (b.n + len <= cap) {
                memmove(b.p + at + len, b.p + at, b.n - at);
                b.n += len;
            }
            break;
        case 4: /* splice from the other input */
            if (other->n > keep) {
                size_t from = keep + fuzz_below(other->n - keep);
                if (from + len > other->n) len = other->n - from;
                if (at + len <= b.n) memcpy(b.p + at, other->p + from, len);
            }
            break;
        default: b.n = keep + fuzz_below(b.n - keep); break; /* cut short */
        }
    }
    return b;
}

void fuzz_run(const char *what, const char *test, unsigned long default_its,
              bool (*one)(void *ctx, unsigned long it, uint32_t *accepted), void *ctx)
{
    char up[32], var[64];
    size_t i = 0;
    for (; what[i] && i + 1 < sizeof up; i++) up[i] = (char)toupper((unsigned char)what[i]);
    up[i] = '\0';
    snprintf(var, sizeof var, "FUZZ_%s_SECONDS", up);
    const char *secs = getenv(var), *seed = getenv("FUZZ_SEED");
    snprintf(var, sizeof var, "FUZZ_%s_ITERATIONS", up);
    const char *its = getenv(var);
    const double seconds = secs ? atof(secs) : 0.0;
    const unsigned long max_it = its ? strtoul(its, NULL, 10) : seconds > 0 ? (unsigned long)-1 : default_its;
    const char *shown = seed && *seed ? seed : "1";
    rng = strtoull(shown, NULL, 10) ^ 0x9E3779B97F4A7C15ull;
    if (!rng) rng = 1;
    uint32_t accepted = 0;
    unsigned long it = 0;
    const clock_t t0 = clock();
    for (; it < max_it; it++) {
        if (seconds > 0 && (it & 15) == 0 && (double)(clock() - t0) / CLOCKS_PER_SEC > seconds) break;
        if (!one(ctx, it, &accepted)) {
            printf("    fuzz_%s: failed at %s %lu; replay: FUZZ_SEED=%s %s=%lu build/test_c %s\n", what, what, it, shown, var,
                   it + 1, test);
            break;
        }
    }
    printf("    fuzz_%s: %lu %ss, %u accepted, seed %s\n", what, it, what, accepted, shown);
}
