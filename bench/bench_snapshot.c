/* tether — snapshots of the 10 000-circle reference pour: how long a save
 * (tt_world_save into a buffer the caller keeps), a restore in place and a
 * load into a new world take, and the world hash (the hash of the same
 * stream). Target: save and restore each ≤ 1 ms. */
#include "bench.h"
#include "tether.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* 10 000 circles r 0.5, 89 a row 1.1 apart (odd rows +0.05), in a box 100
 * wide with walls to 400; g = 10, friction 0.3, restitution 0. */
static tt_world *reference_pour(void)
{
    tt_world_def wd = tt_world_def_default();
    wd.gravity = (tt_vec2){0, -10};
    tt_world *w = tt_world_create(&wd);
    tt_collision_settings cs = tt_collision_settings_default();
    cs.friction_static = cs.friction_kinetic = 0.3;
    cs.restitution = 0.0;
    tt_world_set_collision(w, &cs);
    tt_shape_def sd = tt_shape_def_default();
    sd.type = TT_SHAPE_AABB;
    sd.a = (tt_vec2){-51, -1}; sd.b = (tt_vec2){51, 0}; tt_shape_create(w, &sd);
    sd.a = (tt_vec2){-51, 0}; sd.b = (tt_vec2){-50, 400}; tt_shape_create(w, &sd);
    sd.a = (tt_vec2){50, 0}; sd.b = (tt_vec2){51, 400}; tt_shape_create(w, &sd);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = 0.5;
    for (int i = 0; i < 10000; i++) {
        int row = i / 89, col = i % 89;
        pd.position = (tt_vec2){-48.4 + col * 1.1 + (row % 2) * 0.05, 0.6 + row * 1.1};
        tt_particle_create(w, &pd);
    }
    return w;
}

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
    tt_world *w = reference_pour();
    for (int s = 0; s < 120; s++) tt_world_step(w, 1.0 / 60);
    size_t n = 0;
    tt_world_save(w, NULL, 0, &n);
    unsigned char *buf = malloc(n);
    if (!buf || tt_world_save(w, buf, n, &n) != TT_OK) {
        printf("snapshot: cannot save: %s\n", tt_last_error(w));
        free(buf);
        tt_world_destroy(w);
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
    tt_world_destroy(w);
}
