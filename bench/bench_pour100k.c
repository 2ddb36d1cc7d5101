/* tether — the 100 k pour (issue 21): the reference pour at 100 000
 * circles in a box 316 wide (src/scenes/, "pour100k"), 20 s, sleeping off,
 * at the settings a game would try; every step timed and measured (outside
 * the timing): the deepest and mean overlap over the whole run and the
 * kinetic energy at its end. Target: at rest (KE <= 1e-4 J/kg), max
 * overlap <= 1 % of a radius, <= 25 ms per step as the mean over 20 s. */
#include "bench.h"
#include "bench_accuracy.h"
#include "scenes/scene.h"

#include <stdlib.h>

void bench_pour100k(const char *dir)
{
    static const ts_tether_settings rows[] = {{1, 8, 4, false, false}, {2, 8, 4, false, false}, {4, 8, 4, false, false}};
    printf("\n== The 100 k pour (100 000 circles r = 0.5 into a 316-wide box), 20 s of 1/60 s steps, sleeping off ==\n");
    printf("target (issue 21): at rest (KE <= 1e-4 J/kg), max overlap <= 1 %% of a radius over the run, <= 25 ms/step mean\n");
    printf("%8s %10s %10s %10s %9s\n", "setting", "mean ms", "median ms", "worst ms", "target");
    bench_acc_head();
    FILE *csv = bench_csv(dir, "pour100k.csv", "substeps,iterations,mean_ms,median_ms,worst_ms," BENCH_ACC_CSV);
    ts_scene sc;
    if (!ts_scene_named(&sc, "pour100k", false)) return;
    for (size_t r = 0; r < sizeof rows / sizeof rows[0]; r++) {
        ts_tether t;
        const char *why = NULL;
        if (ts_tether_build(&sc, &rows[r], &t, &why) != TT_OK) {
            printf("pour100k: %s\n", why ? why : "failed");
            break;
        }
        bench_acc a;
        bench_acc_init(&a, t.world, ACC_OVERLAP, NULL, 0);
        double *ms = malloc(sc.steps * sizeof *ms), mean = 0, worst = 0;
        if (!ms) {
            printf("pour100k: out of memory\n");
            bench_acc_free(&a);
            ts_tether_free(&t);
            break;
        }
        for (uint32_t s = 0; s < sc.steps; s++) {
            const double t0 = bench_now_ns();
            tt_world_step(t.world, sc.dt);
            ms[s] = (bench_now_ns() - t0) * 1e-6;
            mean += ms[s] / sc.steps;
            worst = ms[s] > worst ? ms[s] : worst;
            bench_acc_step(&a, t.world);
            if (s % 120 == 119) fprintf(stderr, "  pour100k %ux%u: %u s\r", rows[r].substeps, rows[r].iterations, (s + 1) / 60);
        }
        const double median = bench_median(ms, (int)sc.steps);
        const bool ok = a.ke_per_kg <= 1e-4 && a.max_overlap <= 0.01 && mean <= 25;
        char setting[16];
        snprintf(setting, sizeof setting, "%ux%u", rows[r].substeps, rows[r].iterations);
        printf("%8s %10.2f %10.2f %10.2f %9s\n", setting, mean, median, worst,
               ok ? "met" : a.max_overlap > 0.01 || a.ke_per_kg > 1e-4 ? "ACCURACY" : "slow");
        bench_acc_print(&a);
        fprintf(csv, "%u,%u,%.4f,%.4f,%.4f,", rows[r].substeps, rows[r].iterations, mean, median, worst);
        bench_acc_csv(csv, &a);
        free(ms);
        bench_acc_free(&a);
        ts_tether_free(&t);
    }
    ts_scene_free(&sc);
    fclose(csv);
}
