/* tether — collision benchmarks: ms/step against particle count (grid and
 * brute force, equal radii and a 1:4 mix), the grid's scaling slope and
 * broadphase memory per particle (the reference pour against Box2D:
 * bench_pour.c). */
#include "bench.h"
#include "bench_accuracy.h"
#include "tether.h"
#include "scenes/scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Walls of a box `width` wide (inner faces at ±width/2, floor top at 0). */
static void box(tt_world *w, double width)
{
    tt_shape_def sd = tt_shape_def_default();
    sd.type = TT_SHAPE_AABB;
    double h = width / 2;
    sd.a = (tt_vec2){-h - 1, -1}; sd.b = (tt_vec2){h + 1, 0}; tt_shape_create(w, &sd);
    sd.a = (tt_vec2){-h - 1, 0}; sd.b = (tt_vec2){-h, 1e4}; tt_shape_create(w, &sd);
    sd.a = (tt_vec2){h, 0}; sd.b = (tt_vec2){h + 1, 1e4}; tt_shape_create(w, &sd);
}

/* n particles packed on a square lattice in a box, touching (equal radii r =
 * 0.5) or, for the mix, radii 0.25 and 1 (one in four big) at spacing 2. */
static tt_world *packed(uint32_t n, bool mix, tt_broadphase bp, uint32_t iterations)
{
    tt_world_def wd = tt_world_def_default();
    wd.capacity = n;
    wd.iterations = iterations;
    tt_world *w = tt_world_create(&wd);
    tt_collision_settings cs = tt_collision_settings_default();
    cs.broadphase = bp;
    tt_world_set_collision(w, &cs);
    double spacing = mix ? 2.0 : 1.0;
    uint32_t cols = (uint32_t)ceil(sqrt((double)n));
    box(w, cols * spacing);
    ts_grid g = ts_grid_default();
    g.count = n;
    g.columns = cols;
    g.corner = (tt_vec2){-(cols * spacing) / 2, 0};
    g.spacing = spacing;
    g.radius = mix ? 0.25 : 0.5;
    g.big_radius = 1.0;
    g.big_every = mix ? 4 : 0;
    ts_grid_add(w, &g);
    return w;
}

/* One timed step: ms of the whole step, of its detection stage (the grid
 * build, its pairs and the shape tests) and of the grid alone (build and
 * pair search). */
static void timed_step(tt_world *w, double *step, double *detect, double *bp)
{
    const double t0 = bench_now_ns();
    tt_world_step(w, 1.0 / 60);
    *step = (bench_now_ns() - t0) * 1e-6;
    tt_stats st;
    tt_world_get_stats(w, &st);
    *detect = st.stage_ms[TT_STAGE_COLLIDE];
    tt_collision_stats cst;
    tt_world_get_collision_stats(w, &cst);
    *bp = cst.broadphase_ms;
}

/* Medians over the four sizes of one radii mix, each a whole run of
 * RUN_STEPS steps from the packed start, every step timed and measured (the
 * accuracy outside the timing), the sizes in turns: a step of each, then
 * the next round. A shared machine's load drifts over seconds; in turns it
 * falls on every size alike instead of tilting the slope. */
#define RUN_STEPS 60
static void sizes_in_turns(const uint32_t sizes[4], bool mix, double grid[4], double detect[4], double bp[4],
                           tt_collision_stats cst[4], bench_acc acc[4])
{
    tt_world *w[4];
    double *t[4][3];
    for (int k = 0; k < 4; k++) {
        w[k] = packed(sizes[k], mix, TT_BROADPHASE_GRID, 1);
        bench_acc_init(&acc[k], w[k], ACC_OVERLAP | ACC_ENERGY, NULL, 0);
        for (int j = 0; j < 3; j++) t[k][j] = malloc(RUN_STEPS * sizeof(double));
    }
    for (int r = 0; r < RUN_STEPS; r++)
        for (int k = 0; k < 4; k++) {
            timed_step(w[k], &t[k][0][r], &t[k][1][r], &t[k][2][r]);
            bench_acc_step(&acc[k], w[k]);
        }
    for (int k = 0; k < 4; k++) {
        grid[k] = bench_median(t[k][0], RUN_STEPS);
        detect[k] = bench_median(t[k][1], RUN_STEPS);
        bp[k] = bench_median(t[k][2], RUN_STEPS);
        tt_world_get_collision_stats(w[k], &cst[k]);
        tt_world_destroy(w[k]);
        for (int j = 0; j < 3; j++) free(t[k][j]);
    }
}

/* Median ms of a whole step. */
static double step_ms(tt_world *w, int warm, int reps)
{
    for (int s = 0; s < warm; s++) tt_world_step(w, 1.0 / 60);
    double *t = malloc((size_t)reps * sizeof *t), d, b;
    for (int r = 0; r < reps; r++) timed_step(w, &t[r], &d, &b);
    double m = bench_median(t, reps);
    free(t);
    return m;
}

/* Log-log slope of ms against the four sizes, least squares: one noisy end cannot tip it. */
static double slope(const uint32_t *sizes, const double *ms)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int k = 0; k < 4; k++) {
        const double x = log((double)sizes[k]), y = log(ms[k]);
        sx += x; sy += y; sxx += x * x; sxy += x * y;
    }
    return (4 * sxy - sx * sy) / (4 * sxx - sx * sx);
}

/* The 100 k target as a whole run long enough to see whether the pile
 * holds, at the target's settings and at settings that hold it. */
static void bench_100k(const char *dir)
{
    enum { STEPS = 300 };
    static const uint32_t set[][2] = {{1, 1}, {2, 2}, {4, 2}};
    printf("\n== 100k colliding particles packed in a box, whole runs of %d steps (%.0f s) from the start ==\n", STEPS, STEPS / 60.0);
    printf("target: <= 5 ms/step at 1 substep x 1 iteration, and it must not be flagged\n");
    printf("%9s %11s %12s %12s %12s %8s\n", "substeps", "iterations", "median ms", "mean ms", "worst ms", "target");
    bench_acc_head();
    FILE *csv = bench_csv(dir, "collide_100k.csv", "substeps,iterations,steps,median_ms,mean_ms,worst_ms," BENCH_ACC_CSV);
    for (int k = 0; k < 3; k++) {
        tt_world *w = packed(100000, false, TT_BROADPHASE_GRID, set[k][1]);
        tt_world_set_substeps(w, set[k][0]);
        bench_acc acc;
        bench_acc_init(&acc, w, ACC_OVERLAP | ACC_ENERGY, NULL, 0);
        double t[STEPS], d, b, mean = 0, worst = 0;
        for (int s = 0; s < STEPS; s++) {
            timed_step(w, &t[s], &d, &b);
            mean += t[s] / STEPS;
            worst = fmax(worst, t[s]);
            bench_acc_step(&acc, w);
        }
        const double med = bench_median(t, STEPS);
        char fl[64];
        const bool target = k == 0;
        const bool met = med <= 5 && strcmp(bench_acc_flags(&acc, fl, sizeof fl), "ok") == 0;
        printf("%9u %11u %12.3f %12.3f %12.3f %8s\n", set[k][0], set[k][1], med, mean, worst, target ? (met ? "met" : "NOT met") : "");
        bench_acc_print(&acc);
        fprintf(csv, "%u,%u,%d,%.4f,%.4f,%.4f,", set[k][0], set[k][1], STEPS, med, mean, worst);
        bench_acc_csv(csv, &acc);
        fputc('\n', csv);
        bench_acc_free(&acc);
        tt_world_destroy(w);
        fflush(stdout);
    }
    fclose(csv);
}

void bench_collide(const char *dir)
{
    printf("\n== Collisions: colliding particles packed in a box under gravity (1 substep, 1 iteration), %d steps from the start ==\n", RUN_STEPS);
    printf("target: 100k particles <= 5 ms/step (grid); grid cost linear in N, log-log slope 1 +- 0.1 from 1k to 1M\n");
    printf("(grid ms: whole steps; bp ms: the grid itself, its build and pair search, whose growth with N is\n"
           " the slope; detect ms: the detection stage, which adds the shape tests at the box's walls, fewer per\n"
           " particle in a bigger box; the rest of a step depends on how far each pile has settled)\n");
    printf("%9s %6s %10s %10s %10s %12s %12s %10s %12s\n", "particles", "radii", "grid ms", "bp ms", "detect ms", "brute ms",
           "ns/particle", "grid B/p", "collide B/p");
    FILE *csv = bench_csv(dir, "collide.csv",
                          "particles,radii,grid_ms,brute_ms,grid_bytes_per_particle,collide_bytes_per_particle,detect_ms,bp_ms,steps," BENCH_ACC_CSV);
    bench_acc_head();
    const uint32_t sizes[] = {1000, 10000, 100000, 1000000};
    double grid_ms[2][4], detect_ms[2][4], bp_ms[2][4];
    for (int mix = 0; mix < 2; mix++) {
        tt_collision_stats cst[4];
        bench_acc acc[4];
        sizes_in_turns(sizes, mix, grid_ms[mix], detect_ms[mix], bp_ms[mix], cst, acc);
        bool brute_on = true;
        for (int k = 0; k < 4; k++) {
            const uint32_t n = sizes[k];
            const double g = grid_ms[mix][k], total_bp = (double)cst[k].total_bytes / n;
            double b = NAN;
            if (brute_on) { /* until one brute-force step passes a second */
                tt_world *wb = packed(n, mix, TT_BROADPHASE_BRUTE, 1);
                b = step_ms(wb, 1, n >= 100000 ? 1 : 5);
                tt_world_destroy(wb);
                if (b > 1000.0) brute_on = false;
            }
            printf("%9u %6s %10.3f %10.3f %10.3f %12.3f %12.1f %10.1f %12.1f\n", n, mix ? "1:4" : "equal", g, bp_ms[mix][k],
                   detect_ms[mix][k], b, g * 1e6 / n, cst[k].broadphase_bytes_per_particle, total_bp);
            bench_acc_print(&acc[k]);
            fprintf(csv, "%u,%s,%.4f,%.4f,%.1f,%.1f,%.4f,%.4f,%d,", n, mix ? "mix" : "equal", g, b,
                    cst[k].broadphase_bytes_per_particle, total_bp, detect_ms[mix][k], bp_ms[mix][k], acc[k].steps);
            bench_acc_csv(csv, &acc[k]);
            fputc('\n', csv);
            bench_acc_free(&acc[k]);
            fflush(stdout);
        }
    }
    fclose(csv);
    for (int mix = 0; mix < 2; mix++) {
        const double g = slope(sizes, bp_ms[mix]), d = slope(sizes, detect_ms[mix]);
        printf("grid log-log slope 1k..1M (%s radii): %.3f   target 1 +- 0.1: %s   (detection stage: %.3f)\n",
               mix ? "1:4" : "equal", g, fabs(g - 1) <= 0.1 ? "met" : "NOT met", d);
    }
    bench_100k(dir);

}
