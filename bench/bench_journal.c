/* tether — replay journals on the 10 000-circle reference pour at 60 Hz
 * (src/scenes' builder): what journaling costs a step (runs without and
 * with a journal alternated A B A B from the same state, medians), and the
 * bytes per step it records with no script calls, with a script that
 * nudges a few grains every step, and with one that also drops a new grain
 * every 10 steps (a new particle shifts every array after it in the
 * stream, so its delta is large). */
#include "bench.h"
#include "scenes/scene.h"
#include "tether.h"

#include <stdio.h>
#include <stdlib.h>

enum { WARM = 60, STEPS = 60, PAIRS = 5 };

typedef enum { SCRIPT_NONE, SCRIPT_NUDGE, SCRIPT_SPAWN } script;

static void calls(tt_world *w, const ts_tether *t, script sc, int s)
{
    if (sc == SCRIPT_NONE) return;
    for (int k = 0; k < 4; k++) /* a player's pushes: impulses on a few grains */
        tt_particle_apply_impulse(w, t->circles[(s * 977 + k * 2503) % t->circle_count], (tt_vec2){0.01, 0.02});
    if (sc == SCRIPT_SPAWN && s % 10 == 0) {
        tt_particle_def pd = tt_particle_def_default();
        pd.radius = 0.5;
        pd.position = (tt_vec2){-40 + (s % 80), 300};
        tt_particle_create(w, &pd);
    }
}

/* Steps from the saved state with or without a journal: median ms per step; *per_step the bytes recorded per step. */
static double run(tt_world *w, const unsigned char *s0, size_t n0, const ts_tether *t, script sc, bool journal, double *per_step)
{
    tt_world_restore(w, s0, n0);
    tt_journal *j = journal ? tt_journal_start(w, &(tt_journal_def){.max_bytes = (size_t)1 << 30}) : NULL;
    double ms[STEPS];
    for (int s = 0; s < STEPS; s++) {
        calls(w, t, sc, s);
        const double t0 = bench_now_ns();
        tt_world_step(w, 1.0 / 60);
        ms[s] = (bench_now_ns() - t0) * 1e-6;
    }
    if (j && per_step) {
        tt_journal_info i;
        tt_journal_get_info(j, &i);
        *per_step = (double)i.record_bytes / (double)i.steps;
    }
    tt_journal_destroy(j);
    return bench_median(ms, STEPS);
}

static void range(const double *v, int n, double *lo, double *hi)
{
    *lo = *hi = v[0];
    for (int i = 1; i < n; i++) {
        *lo = v[i] < *lo ? v[i] : *lo;
        *hi = v[i] > *hi ? v[i] : *hi;
    }
}

void bench_journal(const char *dir)
{
    printf("\n== replay journals: the 10 000-circle reference pour at 60 Hz (after %d steps), %d steps a run ==\n", WARM, STEPS);
    ts_scene sc;
    ts_scene_pour(&sc, 10000, 100);
    ts_tether t;
    const char *why = NULL;
    ts_tether_settings set = ts_tether_settings_default();
    if (ts_tether_build(&sc, &set, &t, &why) != TT_OK) { printf("journal: cannot build the pour: %s\n", why); ts_scene_free(&sc); return; }
    for (int s = 0; s < WARM; s++) tt_world_step(t.world, 1.0 / 60);
    size_t n0 = 0;
    tt_world_save(t.world, NULL, 0, &n0);
    unsigned char *s0 = malloc(n0);
    tt_world_save(t.world, s0, n0, &n0);
    double load1 = -1;
    FILE *la = fopen("/proc/loadavg", "r");
    if (la) {
        if (fscanf(la, "%lf", &load1) != 1) load1 = -1;
        fclose(la);
    }
    FILE *csv = bench_csv(dir, "journal.csv", "script,plain_ms,journal_ms,plain_lo,plain_hi,journal_lo,journal_hi,bytes_per_step");
    printf("%-34s %16s %16s %12s %14s\n", "script calls", "plain ms/step", "journaled", "overhead", "bytes/step");
    static const char *const names[] = {"none", "4 impulses a step", "4 impulses a step + a grain / 10"};
    for (int k = 0; k < 3; k++) {
        double a[PAIRS], b[PAIRS], bytes = 0;
        for (int p = 0; p < PAIRS; p++) {
            a[p] = run(t.world, s0, n0, &t, (script)k, false, NULL);
            b[p] = run(t.world, s0, n0, &t, (script)k, true, &bytes);
        }
        double alo, ahi, blo, bhi;
        range(a, PAIRS, &alo, &ahi);
        range(b, PAIRS, &blo, &bhi);
        const double am = bench_median(a, PAIRS), bm = bench_median(b, PAIRS);
        printf("%-34s %6.2f (%.2f-%.2f) %6.2f (%.2f-%.2f) %+8.2f ms %14.0f\n", names[k], am, alo, ahi, bm, blo, bhi, bm - am, bytes);
        fprintf(csv, "%s,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.1f\n", names[k], am, bm, alo, ahi, blo, bhi, bytes);
    }
    printf("(median ms per step of each run, then median and min-max of %d runs each, alternated A B A B from the same\n"
           " state; the stream is %zu bytes; load average %.2f at the start)\n", PAIRS, n0, load1);
    fclose(csv);
    free(s0);
    ts_tether_free(&t);
    ts_scene_free(&sc);
}
