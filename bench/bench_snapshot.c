/* tether — snapshots of the 10 000-circle reference pour (src/scenes/, the
 * scene every comparison of piles uses): how long a save
 * (tt_world_save into a buffer the caller keeps), a restore in place and a
 * load into a new world take, and the world hash (the hash of the same
 * stream). Target: save and restore each ≤ 1 ms. */
#include "bench.h"
#include "scenes/scene.h"
#include "tether.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void report(FILE *csv, const char *what, double *ms, int n)
{
    double lo = ms[0], hi = ms[0];
    for (int i = 1; i < n; i++) {
        if (ms[i] < lo) lo = ms[i];
        if (ms[i] > hi) hi = ms[i];
    }
    double med = bench_median(ms, n);
    printf("%-28s %8.3f ms   (%.3f – %.3f over %d runs)\n", what, med, lo, hi, n);
    fprintf(csv, "%s,%.4f,%.4f,%.4f,%d\n", what, med, lo, hi, n);
}

void bench_snapshot(const char *dir)
{
    enum { RUNS = 21 };
    printf("\n== snapshots of the 10 000-circle reference pour (after 120 steps of 1/60 s) ==\n");
    printf("target: save <= 1 ms, restore in place <= 1 ms\n");
    ts_scene sc;
    ts_scene_pour(&sc, 10000, 100);
    ts_tether t;
    const char *why = NULL;
    ts_tether_settings set = ts_tether_settings_default();
    const tt_result built = ts_tether_build(&sc, &set, &t, &why);
    ts_scene_free(&sc);
    if (built != TT_OK) {
        printf("snapshot: cannot build the pour: %s\n", why);
        return;
    }
    tt_world *w = t.world;
    /* the builder switches sleeping off (the Box2D comparisons run without
     * it); a game's world has it on, and its stream holds the sleep section */
    const tt_world_def d = tt_world_def_default();
    tt_world_set_sleep(w, true, d.sleep_speed, d.sleep_time);
    for (int s = 0; s < 120; s++) tt_world_step(w, 1.0 / 60);
    size_t n = 0;
    tt_world_save(w, NULL, 0, &n);
    unsigned char *buf = malloc(n);
    if (!buf || tt_world_save(w, buf, n, &n) != TT_OK) {
        printf("snapshot: cannot save: %s\n", tt_last_error(w));
        free(buf);
        ts_tether_free(&t);
        return;
    }
    const uint64_t h0 = tt_world_hash(w);
    double save_ms[RUNS], restore_ms[RUNS], load_ms[RUNS], hash_ms[RUNS];
    bool exact = true;
    for (int r = 0; r < RUNS; r++) {
        double t0 = bench_now_ns();
        tt_world_save(w, buf, n, &n);
        double t1 = bench_now_ns();
        tt_world_restore(w, buf, n);
        double t2 = bench_now_ns();
        tt_world *c = tt_world_load(buf, n);
        double t3 = bench_now_ns();
        uint64_t h = tt_world_hash(w);
        double t4 = bench_now_ns();
        exact = exact && c && h == h0 && tt_world_hash(c) == h0;
        tt_world_destroy(c);
        save_ms[r] = (t1 - t0) * 1e-6;
        restore_ms[r] = (t2 - t1) * 1e-6;
        load_ms[r] = (t3 - t2) * 1e-6;
        hash_ms[r] = (t4 - t3) * 1e-6;
    }
    double load1 = 0, load5 = 0, load15 = 0;
    FILE *la = fopen("/proc/loadavg", "r");
    if (la) {
        if (fscanf(la, "%lf %lf %lf", &load1, &load5, &load15) != 3) load1 = load5 = load15 = -1;
        fclose(la);
    }
    printf("stream: %zu bytes (%.1f per particle); restored state identical: %s; load average %.2f %.2f %.2f\n", n,
           (double)n / 10000, exact ? "yes" : "NO", load1, load5, load15);
    FILE *csv = bench_csv(dir, "snapshot.csv", "what,median_ms,min_ms,max_ms,runs");
    report(csv, "save (tt_world_save)", save_ms, RUNS);
    report(csv, "restore in place", restore_ms, RUNS);
    report(csv, "load into a new world", load_ms, RUNS);
    report(csv, "hash (tt_world_hash)", hash_ms, RUNS);
    fclose(csv);
    free(buf);
    ts_tether_free(&t);
}
