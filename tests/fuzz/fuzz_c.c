/* tests/fuzz/fuzz_c.c — a seeded fuzzer of tether's C API: random calls of
 * every public function of tether.h through the wrapper tables, with
 * hostile arguments and plausible scenes. `build/fuzz_c [--list]`.
 * Environment: FUZZ_SEED (default: the clock), FUZZ_SECONDS (default 10),
 * FUZZ_CALLS (stop right after this call: replay), FUZZ_TRACE=1 (print every
 * call as a C-like line as it is made), FUZZ_KEEP_GOING=1 (a survey: each
 * kind of failure once, then on), FUZZ_COUNTS=1 (calls and seconds per
 * wrapper at the end), FUZZ_SKIP (calls to draw and not make: "12,40-97" or
 * "@FILE" holding such a list; tests/fuzz/minimise_c.lua uses it), FUZZ_ONLY
 * (comma-separated name prefixes, "tt_mask_,tt_clock_": only those wrappers,
 * and only those functions must be reached; for a campaign on one part).
 * Each call draws from its own stream, seeded by the seed and the call
 * number, so a skipped call leaves every later call's draws as they were.
 * After every call: a call that failed, or only read, left its world's hash
 * and counts as they were; a call that had to fail (NULL world, stale,
 * foreign, null or kind-turned handle) failed; after every step every
 * position, velocity and number the API returns is finite and bounded.
 * A failure or a crash prints the seed, the call number, the last calls and
 * the replay command. The end: "fuzz_c: N calls, seed S, K of M functions
 * reached" and "1 passed, 0 failed" (a function never reached fails). */
#include "fuzz_c.h"

#include <ctype.h>
#include <setjmp.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

static const char *const api_names[FZ_API_COUNT] = {
#define FZ_API(name) #name,
#include "fuzz_c_api.h"
#undef FZ_API
};

static fz *g_fz; /* for the crash handlers */
/* FUZZ_KEEP_GOING=1 (a survey): each kind of failure is reported once and
 * the run goes on with the next call. */
static bool keep_going;
static jmp_buf next_call;
static unsigned failures;

/* Whether a failure of this kind (its message without numbers) was reported. */
static bool seen_before(const char *msg)
{
    static char kinds[64][64];
    static unsigned nkinds;
    char k[64];
    unsigned n = 0;
    for (const char *p = msg; *p && n < sizeof k - 1; p++)
        if (!isdigit((unsigned char)*p) && *p != '.' && *p != '-' && *p != '+') k[n++] = *p;
    k[n] = 0;
    for (unsigned i = 0; i < nkinds; i++)
        if (strcmp(kinds[i], k) == 0) return true;
    if (nkinds < 64) memcpy(kinds[nkinds++], k, sizeof k);
    return false;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + (double)ts.tv_nsec * 1e-9;
}

void fz_hit(fz *f, enum fz_api_id id) { f->hits[id]++; }

/* The world's last error, for the log of a failed call. */
static const char *why(const fz *f)
{
    return tt_last_error(f->cur >= 0 ? f->slots[f->cur].w : NULL);
}

void fz_res(fz *f, tt_result r)
{
    fz_log_more(f, " -> %s", fz_res_name(r));
    if (r != TT_OK) fz_log_more(f, " \"%.200s\"", why(f));
    if ((unsigned)r > TT_ESTATE) fz_fail(f, "the call returned %d, not a tt_result", (int)r);
    if (r != TT_OK) f->failed = true;
}

/* A creating call: the null handle is its failure; a new handle is remembered. */
void fz_hres(fz *f, tt_kind kind, fz_h h)
{
    fz_log_more(f, " -> %s", fz_hn(h, kind));
    if (h.index == 0 && h.gen == 0) {
        f->failed = true;
        fz_log_more(f, " \"%.200s\"", why(f));
    }
    else fz_remember(f, kind, h);
}

static void replay_hint(int fd, const fz *f)
{
    char buf[256];
    snprintf(buf, sizeof buf, "fuzz_c: replay: FUZZ_SEED=%llu FUZZ_CALLS=%llu FUZZ_TRACE=1 %s\n",
             (unsigned long long)f->seed, (unsigned long long)f->call,
#ifdef __SANITIZE_ADDRESS__
             "build-san/fuzz_c"
#else
             "build/fuzz_c"
#endif
    );
    if (write(fd, buf, strlen(buf)) < 0) return;
}

void fz_fail(fz *f, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    fflush(stdout);
    if (keep_going) {
        failures++;
        if (!seen_before(msg)) {
            fprintf(stderr, "FUZZ FAILURE at call %llu, seed %llu: %s\n", (unsigned long long)f->call,
                    (unsigned long long)f->seed, msg);
            fz_log_dump(2, 6);
        }
        for (int i = 0; i < FZ_WORLDS; i++) f->slots[i].snap_valid = false;
        longjmp(next_call, 1);
    }
    fprintf(stderr, "FUZZ FAILURE at call %llu, seed %llu: %s\n", (unsigned long long)f->call,
            (unsigned long long)f->seed, msg);
    fz_log_dump(2, 40);
    replay_hint(2, f);
    printf("0 passed, 1 failed\n");
    exit(1);
}

/* A crash (sanitizer report, signal): the log says which call it was. */
static void on_death(void)
{
    if (!g_fz) return;
    char buf[160];
    snprintf(buf, sizeof buf, "FUZZ CRASH at call %llu, seed %llu\n", (unsigned long long)g_fz->call,
             (unsigned long long)g_fz->seed);
    if (write(2, buf, strlen(buf)) < 0) return;
    fz_log_dump(2, 40);
    replay_hint(2, g_fz);
}

#ifdef __SANITIZE_ADDRESS__
void __sanitizer_set_death_callback(void (*callback)(void));
static void install_crash_report(void) { __sanitizer_set_death_callback(on_death); }
#else
static void on_signal(int sig)
{
    on_death();
    signal(sig, SIG_DFL);
    raise(sig);
}
static void install_crash_report(void)
{
    int sigs[] = { SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT };
    for (unsigned i = 0; i < sizeof sigs / sizeof sigs[0]; i++) signal(sigs[i], on_signal);
}
#endif

/* The whole table, every wrapper once, and the total weight. */
static const fz_entry *entries[512];
static unsigned entry_count, total_weight;
static uint64_t entry_calls[512];
static double entry_seconds[512];

/* Whether a name is one of FUZZ_ONLY's prefixes (every name without it). */
static bool selected(const char *name)
{
    const char *only = getenv("FUZZ_ONLY");
    if (!only || !*only) return true;
    for (const char *p = only; *p;) {
        size_t n = strcspn(p, ",");
        if (n && strncmp(name, p, n) == 0) return true;
        p += n + (p[n] == ',');
    }
    return false;
}

static void gather(void)
{
    const fz_entry *tables[] = { fz_world_entries, fz_particle_entries, fz_constraint_entries,
                                 fz_composite_entries, fz_collide_entries, fz_scene_entries, fz_stream_entries,
                                 fz_terrain_entries, fz_rewind_entries, fz_journal_entries, fz_mask_entries, fz_mask2_entries,
                                 fz_mask3_entries, fz_clock_entries };
    for (unsigned t = 0; t < sizeof tables / sizeof tables[0]; t++)
        for (const fz_entry *e = tables[t]; e->name; e++) {
            if (!selected(e->name)) continue;
            if (entry_count == 512) abort();
            entries[entry_count++] = e;
            total_weight += e->weight;
        }
}

static unsigned pick_entry(fz *f)
{
    uint32_t r = fz_below(f, total_weight);
    for (unsigned i = 0; i < entry_count; i++) {
        if (r < entries[i]->weight) return i;
        r -= entries[i]->weight;
    }
    return entry_count - 1;
}

static void check_unchanged(fz *f, const char *what)
{
    fz_world *s = &f->slots[f->cur];
    uint32_t c[5] = { tt_world_particle_count(s->w), tt_world_spring_count(s->w), tt_world_constraint_count(s->w),
                      tt_world_shape_count(s->w), tt_world_composite_count(s->w) };
    uint64_t h = tt_world_hash(s->w);
    if (h != s->hash || memcmp(c, s->counts, sizeof c) != 0)
        fz_fail(f, "%s changed the world: hash %016llx -> %016llx, counts (particles, springs, constraints, "
                   "shapes, composites) %u %u %u %u %u -> %u %u %u %u %u", what, (unsigned long long)s->hash,
                (unsigned long long)h, s->counts[0], s->counts[1], s->counts[2], s->counts[3], s->counts[4], c[0],
                c[1], c[2], c[3], c[4]);
}

/* The invariants of one call, after it. */
static void after_call(fz *f)
{
    if (f->must_fail && !f->failed)
        fz_fail(f, "the call succeeded with %s: %s", f->why_must, f->why_must[0] == 'a' && f->why_must[2] == 'N' ? "" : fz_hn(f->must_h, f->must_k));
    if (f->cur < 0 || !f->slots[f->cur].w) return;
    fz_world *s = &f->slots[f->cur];
    if (f->failed) check_unchanged(f, "a call that failed");
    else if (f->readonly) check_unchanged(f, "a read");
    else s->snap_valid = false;
    if (f->stepped) {
        fz_snapshot(s);
        fz_check_world(f, s->w);
        check_unchanged(f, "reading every particle, constraint and stat");
    }
}

/* World 0 always exists, so most calls have a world to work on. */
static void ensure_world(fz *f)
{
    fz_world_too_big(f);
    if (f->slots[0].w) return;
    f->slots[0].w = tt_world_create(NULL);
    f->slots[0].name = f->names++;
    f->slots[0].snap_valid = false;
    fz_log(f, "w%d = tt_world_create(NULL)", f->slots[0].name);
    FZ_HIT(f, tt_world_create);
    if (!f->slots[0].w) fz_fail(f, "tt_world_create(NULL) failed: %s", tt_last_error(NULL));
}


/* FUZZ_SKIP: sorted, merged ranges of call numbers. */
static struct { unsigned long long lo, hi; } *skips;
static size_t nskips;

static void parse_skips(void)
{
    const char *s = getenv("FUZZ_SKIP");
    char *text = NULL;
    if (s && s[0] == '@') {
        FILE *fp = fopen(s + 1, "r");
        if (!fp) {
            fprintf(stderr, "fuzz_c: FUZZ_SKIP: cannot read %s\n", s + 1);
            exit(2);
        }
        size_t cap = 4096, n = 0;
        text = malloc(cap);
        for (int c; text && (c = fgetc(fp)) != EOF;) {
            if (n + 1 == cap) text = realloc(text, cap *= 2);
            if (text) text[n++] = (char)c;
        }
        fclose(fp);
        if (!text) exit(2);
        text[n] = 0;
        s = text;
    }
    for (const char *p = s; p && *p;) {
        if (!isdigit((unsigned char)*p)) { p++; continue; }
        char *end;
        unsigned long long lo = strtoull(p, &end, 10), hi = lo;
        if (*end == '-') hi = strtoull(end + 1, &end, 10);
        p = end;
        void *grown = realloc(skips, (nskips + 1) * sizeof *skips);
        if (!grown) exit(2);
        skips = grown;
        skips[nskips].lo = lo;
        skips[nskips++].hi = hi;
    }
    free(text);
}

static bool skipped(unsigned long long call)
{
    for (size_t i = 0; i < nskips; i++)
        if (call >= skips[i].lo && call <= skips[i].hi) return true;
    return false;
}

/* The stream of one call (splitmix64 of seed and call number). */
static uint64_t call_stream(uint64_t seed, uint64_t call)
{
    uint64_t z = seed ^ 0x9E3779B97F4A7C15ull ^ (call * 0xBF58476D1CE4E5B9ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return z ? z : 1;
}

static unsigned long long env_u64(const char *name, unsigned long long dflt)
{
    const char *s = getenv(name);
    return s && *s ? strtoull(s, NULL, 10) : dflt;
}

static void cleanup(fz *f)
{
    for (int i = 0; i < FZ_WORLDS; i++) {
        tt_world_destroy(f->slots[i].w);
        for (int k = 0; k < FZ_KINDS; k++) {
            fz_list_free(&f->slots[i].live[k]);
            fz_list_free(&f->slots[i].stale[k]);
        }
    }
    for (int k = 0; k < FZ_KINDS; k++) fz_list_free(&f->foreign[k]);
    fz_mask_free_all(f);
}

static int report(fz *f, double seconds, bool replay)
{
    unsigned reached = 0, wanted = 0;
    for (unsigned i = 0; i < FZ_API_COUNT; i++) {
        wanted += selected(api_names[i]);
        reached += f->hits[i] > 0 && selected(api_names[i]);
    }
    printf("fuzz_c: %llu calls in %.0f s, seed %llu, %u of %u functions reached\n", (unsigned long long)f->call,
           seconds, (unsigned long long)f->seed, reached, wanted);
    if (getenv("FUZZ_COUNTS"))
        for (unsigned i = 0; i < entry_count; i++)
            printf("    %10llu %8.2f s %s\n", (unsigned long long)entry_calls[i], entry_seconds[i], entries[i]->name);
    if (reached < wanted && !replay) {
        for (unsigned i = 0; i < FZ_API_COUNT; i++)
            if (!f->hits[i] && selected(api_names[i])) printf("fuzz_c: never reached: %s\n", api_names[i]);
        printf("0 passed, 1 failed\n");
        return 1;
    }
    printf("1 passed, 0 failed\n");
    return 0;
}

int main(int argc, char **argv)
{
    if (argc > 1 && strcmp(argv[1], "--list") == 0) {
        for (unsigned i = 0; i < FZ_API_COUNT; i++) puts(api_names[i]);
        return 0;
    }
    static fz state;
    fz *f = &state;
    f->seed = env_u64("FUZZ_SEED", (unsigned long long)time(NULL));
    parse_skips();
    f->trace = getenv("FUZZ_TRACE") && strcmp(getenv("FUZZ_TRACE"), "1") == 0;
    keep_going = getenv("FUZZ_KEEP_GOING") && strcmp(getenv("FUZZ_KEEP_GOING"), "1") == 0;
    const double seconds = (double)env_u64("FUZZ_SECONDS", 10);
    const unsigned long long max_calls = env_u64("FUZZ_CALLS", 0);
    g_fz = f;
    install_crash_report();
    gather();
    printf("fuzz_c: seed %llu, %.0f s, %u wrappers\n", (unsigned long long)f->seed, seconds, entry_count);
    static double start, elapsed;
    start = now_s();
    setjmp(next_call); /* FUZZ_KEEP_GOING: a failed call's run goes on from here */
    while (max_calls ? f->call < max_calls : elapsed < seconds) {
        f->call++;
        f->rng = call_stream(f->seed, f->call);
        ensure_world(f);
        f->cur = -1;
        f->failed = f->must_fail = f->readonly = f->stepped = false;
        if ((f->call & 63) == 0) elapsed = now_s() - start;
        unsigned e = pick_entry(f);
        if (nskips && skipped(f->call)) continue;
        entry_calls[e]++;
        double t0 = now_s();
        entries[e]->fn(f);
        after_call(f);
        entry_seconds[e] += now_s() - t0;
    }
    cleanup(f);
    free(skips);
    if (failures) {
        printf("fuzz_c: %u failed calls (FUZZ_KEEP_GOING)\n0 passed, 1 failed\n", failures);
        return 1;
    }
    return report(f, now_s() - start, max_calls != 0);
}
