/* tether — cloth that does not stretch (issue 21): a 128² cloth hanging
 * from its top row, and from its two top corners, with and without the
 * long-range attachments (tt_cloth_def.long_range), at the sweeps that
 * hold it. Every step of 10 s is timed and measured: the strain is over
 * the structural links (the first 2n(n−1) a cloth makes), mean and max,
 * the worst step of the run. */
#include "bench.h"
#include "scenes/scene.h"
#include "tether.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>

enum { N = 128, STEPS = 600 };

typedef struct cloth_row {
    const char *pins;
    bool top_row, long_range;
    uint32_t iterations;
} cloth_row;

void bench_cloth_strain(const tt_world *w, const tt_constraint *cs, uint32_t n, double *mean, double *max)
{
    double sum = 0, mx = 0;
    for (uint32_t i = 0; i < n; i++) {
        tt_particle ps[2];
        uint32_t k;
        double rest;
        tt_constraint_get_particles(w, cs[i], ps, 2, &k);
        tt_distance_get_length(w, cs[i], &rest);
        tt_vec2 a, b;
        tt_particle_get_position(w, ps[0], &a);
        tt_particle_get_position(w, ps[1], &b);
        const double s = fabs(hypot(a.x - b.x, a.y - b.y) / rest - 1);
        sum += s;
        if (s > mx) mx = s;
    }
    *mean = sum / n;
    *max = mx;
}

void bench_cloth(const char *dir)
{
    const cloth_row rows[] = {
        {"top row", true, false, 10}, {"top row", true, true, 4}, {"top row", true, true, 2},
        {"corners", false, false, 10}, {"corners", false, true, 4}, {"corners", false, true, 3}, {"corners", false, true, 2},
    };
    printf("\n== Cloth that does not stretch: 128x128 (16k particles, 2 cm apart), 1 substep, 10 s, every step ==\n");
    printf("target (issue 21): mean |strain| <= 1 %% and max <= 5 %% at every step, <= 2 ms per step\n");
    printf("%8s %11s %7s %12s %10s %16s %16s %8s\n", "pinned", "long_range", "sweeps", "constraints", "step ms",
           "worst mean strain", "worst max strain", "target");
    FILE *csv = bench_csv(dir, "cloth_strain.csv", "pins,long_range,iterations,constraints,step_ms,worst_mean_strain,worst_max_strain");
    for (size_t r = 0; r < sizeof rows / sizeof rows[0]; r++) {
        ts_hung_cloth d = ts_hung_cloth_default();
        d.n = N;
        d.iterations = rows[r].iterations;
        d.top_row = rows[r].top_row;
        d.long_range = rows[r].long_range;
        tt_composite c;
        tt_world *w = ts_hung_cloth_build(&d, &c);
        uint32_t nc;
        tt_composite_get_constraints(w, c, NULL, 0, &nc);
        tt_constraint *cs = malloc(nc * sizeof *cs);
        tt_composite_get_constraints(w, c, cs, nc, &nc);
        double *ts = malloc(STEPS * sizeof *ts), worst_mean = 0, worst_max = 0;
        for (int s = 0; s < STEPS; s++) {
            double t0 = bench_now_ns();
            tt_world_step(w, 1.0 / 60);
            ts[s] = (bench_now_ns() - t0) * 1e-6;
            double mean, max;
            bench_cloth_strain(w, cs, 2 * N * (N - 1), &mean, &max);
            if (mean > worst_mean) worst_mean = mean;
            if (max > worst_max) worst_max = max;
        }
        const double ms = bench_median(ts, STEPS);
        const bool ok = worst_mean <= 0.01 && worst_max <= 0.05;
        printf("%8s %11s %7u %12u %10.3f %15.2f%% %15.2f%% %8s\n", rows[r].pins, rows[r].long_range ? "yes" : "no",
               rows[r].iterations, nc, ms, 100 * worst_mean, 100 * worst_max,
               ok ? (ms <= 2.0 ? "ok" : "slow") : "STRETCH");
        fprintf(csv, "%s,%d,%u,%u,%.4f,%.6f,%.6f\n", rows[r].pins, rows[r].long_range, rows[r].iterations, nc, ms,
                worst_mean, worst_max);
        free(cs);
        free(ts);
        tt_world_destroy(w);
    }
    fclose(csv);
}
