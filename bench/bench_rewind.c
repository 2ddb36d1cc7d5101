/* tether — the rewind ring on the 10 000-circle reference pour at 60 Hz
 * (src/scenes' builder): memory per second of history, what recording
 * costs a step, and how long rebuilding a step takes (decode the keyframe,
 * restore, re-simulate up to every − 1 steps). Targets: ≤ 4 MB per second
 * of history, any step rebuilt within one keyframe interval. */
#include "bench.h"
#include "scenes/scene.h"
#include "tether.h"

#include <stdio.h>
#include <stdlib.h>

enum { SECONDS = 10, HZ = 60, SAMPLES = 9 };

static double ms_since(double t0) { return (bench_now_ns() - t0) * 1e-6; }

static void one(FILE *csv, const ts_scene *sc, uint32_t every)
{
    ts_tether t;
    const char *why = NULL;
    ts_tether_settings set = ts_tether_settings_default();
    if (ts_tether_build(sc, &set, &t, &why) != TT_OK) { printf("rewind: cannot build the pour: %s\n", why); return; }
    tt_rewind *r = tt_rewind_create(&(tt_rewind_def){.every = every, .keep_steps = SECONDS * HZ, .max_bytes = (size_t)1 << 31});
    const uint32_t steps = SECONDS * HZ;
    double *rec = malloc(sizeof(double) * (steps / every + 1));
    uint64_t *hash = malloc(sizeof(uint64_t) * (steps + 1));
    uint32_t nrec = 0;
    tt_rewind_record(r, t.world);
    hash[0] = tt_world_hash(t.world);
    for (uint32_t s = 1; s <= steps; s++) {
        tt_world_step(t.world, sc->dt);
        double t0 = bench_now_ns();
        tt_rewind_record(r, t.world);
        if (s % every == 0) rec[nrec++] = ms_since(t0);
        hash[s] = tt_world_hash(t.world);
    }
    size_t one_stream = 0;
    tt_world_save(t.world, NULL, 0, &one_stream);
    const double mb_s = (double)tt_rewind_get_memory(r) / 1e6 / SECONDS;
    /* the worst steps to rebuild: the last of an interval (every − 1 steps to re-simulate), old and new */
    double seek[SAMPLES], total[SAMPLES];
    bool exact = true;
    for (int k = 0; k < SAMPLES; k++) {
        uint64_t target = (uint64_t)every * (1 + (uint64_t)k * (steps / every - 2) / (SAMPLES - 1)) + every - 1;
        if (target > steps) target = steps;
        uint64_t at = 0;
        double t0 = bench_now_ns();
        tt_rewind_seek(r, t.world, target, &at);
        seek[k] = ms_since(t0);
        for (uint64_t s = at; s < target; s++) tt_world_step(t.world, sc->dt);
        total[k] = ms_since(t0);
        exact = exact && tt_world_hash(t.world) == hash[target];
    }
    const double rec_med = bench_median(rec, (int)nrec), seek_med = bench_median(seek, SAMPLES);
    double worst = 0;
    for (int k = 0; k < SAMPLES; k++) worst = total[k] > worst ? total[k] : worst;
    const double total_med = bench_median(total, SAMPLES);
    printf("%6u %9u %10.2f %8.1f%% %11.2f %10.2f %11.1f %9.1f %6s\n", every, tt_rewind_get_count(r), mb_s,
           100.0 * (double)tt_rewind_get_memory(r) / ((double)one_stream * tt_rewind_get_count(r)), rec_med, seek_med,
           total_med, worst, exact ? "yes" : "NO");
    fprintf(csv, "%u,%u,%.4f,%.4f,%.4f,%.3f,%.3f,%d\n", every, tt_rewind_get_count(r), mb_s, rec_med, seek_med, total_med,
            worst, exact);
    free(rec);
    free(hash);
    tt_rewind_destroy(r);
    ts_tether_free(&t);
}

void bench_rewind(const char *dir)
{
    printf("\n== rewind ring: the 10 000-circle reference pour at 60 Hz, %d s of history ==\n", SECONDS);
    printf("target: <= 4 MB per second of history; any step rebuilt within one keyframe interval of re-simulation\n");
    ts_scene sc;
    ts_scene_pour(&sc, 10000, 100);
    double load1 = -1;
    FILE *la = fopen("/proc/loadavg", "r");
    if (la) {
        if (fscanf(la, "%lf", &load1) != 1) load1 = -1;
        fclose(la);
    }
    FILE *csv = bench_csv(dir, "rewind.csv", "every,keyframes,mb_per_s,record_ms,seek_ms,rebuild_median_ms,rebuild_worst_ms,exact");
    printf("%6s %9s %10s %9s %11s %10s %11s %9s %6s\n", "every", "keyframes", "MB/s hist", "of raw", "record ms",
           "seek ms", "rebuild ms", "worst ms", "exact");
    const uint32_t every[] = {5, 10, 20};
    for (unsigned i = 0; i < sizeof every / sizeof every[0]; i++) one(csv, &sc, every[i]);
    printf("(record: median over keyframe steps; seek: decode + restore; rebuild: seek + re-simulation to the last step of\n"
           " an interval, median and worst of %d spread over the history; exact: the rebuilt hash is the first pass's;\n"
           " load average %.2f at the start)\n", SAMPLES, load1);
    fclose(csv);
    ts_scene_free(&sc);
}
