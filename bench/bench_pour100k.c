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

/* A row: the world's substeps and sweeps, substeps by speed (0: off), and
 * whether the pile settings of `pourstarts` are on (stacking 2, anchored
 * friction, warm start 0.75). */
typedef struct row100k {
    uint32_t substeps, iterations;
    double travel;
    bool piled;
} row100k;

static void row_settings(ts_tether *t, const row100k *r)
{
    if (r->travel > 0.0) tt_world_set_travel(t->world, r->travel, 8);
    if (!r->piled) return;
    tt_collision_settings cs;
    tt_world_get_collision(t->world, &cs);
    bench_pile_settings(&cs);
    tt_world_set_collision(t->world, &cs);
}

void bench_pour100k(const char *dir)
{
    static const row100k rows[] = {{1, 8, 0.0, false}, {2, 8, 0.0, false}, {4, 8, 0.0, false}, {1, 8, 0.5, false}, {1, 4, 0.5, true}};
    printf("\n== The 100 k pour (100 000 circles r = 0.5 into a 316-wide box), 20 s of 1/60 s steps, sleeping off ==\n");
    printf("target (issue 21): at rest (KE <= 1e-4 J/kg), max overlap <= 1 %% of a radius over the run, <= 25 ms/step mean\n");
    printf("rows 'tr': substeps by speed, max_travel 0.5 radii (at most 8); 'pile': stacking 2, anchored friction, warm start 0.75\n");
    printf("%16s %10s %10s %10s %9s %9s\n", "setting", "mean ms", "median ms", "worst ms", "substeps", "target");
    bench_acc_head();
    FILE *csv = bench_csv(dir, "pour100k.csv", "substeps,iterations,travel,piled,mean_substeps,mean_ms,median_ms,worst_ms," BENCH_ACC_CSV);
    ts_scene sc;
    if (!ts_scene_named(&sc, "pour100k", false)) return;
    for (size_t r = 0; r < sizeof rows / sizeof rows[0]; r++) {
        ts_tether_settings set = ts_tether_settings_default();
        set.substeps = rows[r].substeps;
        set.iterations = rows[r].iterations;
        ts_tether t;
        const char *why = NULL;
        if (ts_tether_build(&sc, &set, &t, &why) != TT_OK) {
            printf("pour100k: %s\n", why ? why : "failed");
            break;
        }
        row_settings(&t, &rows[r]);
        bench_acc a;
        bench_acc_init(&a, t.world, ACC_OVERLAP, NULL, 0);
        double *ms = malloc(sc.steps * sizeof *ms), mean = 0, worst = 0, subs = 0;
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
            tt_stats st;
            tt_world_get_stats(t.world, &st);
            subs += (double)st.substeps / sc.steps;
            worst = ms[s] > worst ? ms[s] : worst;
            bench_acc_step(&a, t.world);
            if (s % 120 == 119) fprintf(stderr, "  pour100k row %zu: %u s\r", r + 1, (s + 1) / 60);
        }
        const double median = bench_median(ms, (int)sc.steps);
        const bool ok = a.ke_per_kg <= 1e-4 && a.max_overlap <= 0.01 && mean <= 25;
        char setting[32];
        snprintf(setting, sizeof setting, "%ux%u%s%s", rows[r].substeps, rows[r].iterations,
                 rows[r].travel > 0.0 ? " tr" : "", rows[r].piled ? " pile" : "");
        printf("%16s %10.2f %10.2f %10.2f %9.2f %9s\n", setting, mean, median, worst, subs,
               ok ? "met" : a.max_overlap > 0.01 || a.ke_per_kg > 1e-4 ? "ACCURACY" : "slow");
        bench_acc_print(&a);
        fprintf(csv, "%u,%u,%.2f,%d,%.4f,%.4f,%.4f,%.4f,", rows[r].substeps, rows[r].iterations, rows[r].travel,
                (int)rows[r].piled, subs, mean, median, worst);
        bench_acc_csv(csv, &a);
        free(ms);
        bench_acc_free(&a);
        ts_tether_free(&t);
    }
    ts_scene_free(&sc);
    fclose(csv);
}
