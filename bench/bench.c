/* tether — benchmarks. `make bench` runs them; every figure is a median of
 * repeated runs taken side by side in this one process, and each table says
 * its target. CSV files land in the output folder for the gnuplot scripts. */
#include "bench.h"
#include "bench_accuracy.h"
#include "tether.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

double bench_now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec * 1e9 + (double)ts.tv_nsec;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double bench_median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

FILE *bench_csv(const char *dir, const char *name, const char *header)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *f = fopen(path, "w");
    if (!f) {
        perror(path);
        exit(1);
    }
    fprintf(f, "%s\n", header);
    return f;
}

/* The yardstick: the same Verlet arithmetic on bare arrays, nothing else. */
static void bare_verlet(double *x, double *y, double *ox, double *oy, size_t n, double gdx, double gdy)
{
    for (size_t i = 0; i < n; i++) {
        double nx = x[i] + ((x[i] - ox[i]) + gdx);
        double ny = y[i] + ((y[i] - oy[i]) + gdy);
        ox[i] = x[i];
        oy[i] = y[i];
        x[i] = nx;
        y[i] = ny;
    }
}

void bench_integrate(const char *dir)
{
    printf("\n== Verlet integrate stage, gravity only: engine vs a bare struct-of-arrays loop ==\n");
    printf("target: engine within 2x of the bare loop at 100k and 1M particles; <= 64 bytes/particle\n");
    printf("%10s %14s %14s %14s %8s %12s\n", "particles", "bare ns/p", "stage ns/p", "step ns/p", "ratio", "bytes/p");
    bench_acc_head();
    FILE *csv = bench_csv(dir, "integrate.csv", "particles,bare_ns,stage_ns,step_ns,ratio,bytes_per_particle,steps," BENCH_ACC_CSV);
    const size_t sizes[] = {1000, 10000, 100000, 1000000};
    for (int s = 0; s < 4; s++) {
        size_t n = sizes[s];
        const double dt = 1.0 / 60, gdx = 0, gdy = -9.81 * dt * dt;
        double *x = malloc(n * sizeof *x), *y = malloc(n * sizeof *y), *ox = malloc(n * sizeof *ox), *oy = malloc(n * sizeof *oy);
        tt_world_def wd = tt_world_def_default();
        wd.capacity = (uint32_t)n;
        tt_world *w = tt_world_create(&wd);
        tt_particle_def pd = tt_particle_def_default();
        for (size_t i = 0; i < n; i++) {
            x[i] = ox[i] = (double)(i % 1000);
            y[i] = oy[i] = (double)(i / 1000);
            pd.position = (tt_vec2){x[i], y[i]};
            tt_particle_create(w, &pd);
        }
        bench_acc acc;
        bench_acc_init(&acc, w, ACC_ENERGY, NULL, 0);
        tt_world_step(w, dt); /* the first step, timed with the rest below only in the accuracy */
        bench_acc_step(&acc, w);
        bare_verlet(x, y, ox, oy, n, gdx, gdy);
        int reps = n >= 1000000 ? 31 : n >= 100000 ? 101 : 301;
        double *tb = malloc(reps * sizeof *tb), *ts = malloc(reps * sizeof *ts), *tw = malloc(reps * sizeof *tw);
        for (int r = 0; r < reps; r++) { /* interleaved, so both see the same machine */
            double t0 = bench_now_ns();
            bare_verlet(x, y, ox, oy, n, gdx, gdy);
            double t1 = bench_now_ns();
            tt_world_step(w, dt);
            double t2 = bench_now_ns();
            tt_stats st;
            tt_world_get_stats(w, &st);
            tb[r] = (t1 - t0) / (double)n;
            tw[r] = (t2 - t1) / (double)n;
            ts[r] = st.stage_ms[TT_STAGE_INTEGRATE] * 1e6 / (double)n;
            bench_acc_step(&acc, w);
        }
        tt_memory m;
        tt_world_get_memory(w, &m);
        double b = bench_median(tb, reps), st = bench_median(ts, reps), sp = bench_median(tw, reps);
        printf("%10zu %14.3f %14.3f %14.3f %8.2f %12.1f\n", n, b, st, sp, st / b, m.bytes_per_particle);
        bench_acc_print(&acc);
        fprintf(csv, "%zu,%.4f,%.4f,%.4f,%.3f,%.1f,%d,", n, b, st, sp, st / b, m.bytes_per_particle, acc.steps);
        bench_acc_csv(csv, &acc);
        fputc('\n', csv);
        bench_acc_free(&acc);
        free(tb); free(ts); free(tw);
        free(x); free(y); free(ox); free(oy);
        tt_world_destroy(w);
    }
    fclose(csv);
}

/* Many independent oscillators (unit mass, spring k = 1 to a pinned anchor):
 * error against the exact orbit after t = 10 s, and cost, per integrator × dt. */
void bench_tradeoff(const char *dir)
{
    printf("\n== Speed/accuracy trade: 1000 oscillators (spring to a pin), t = 10 s ==\n");
    printf("position error vs exact solution and cost per particle-step, per integrator and dt\n");
    printf("%18s %10s %14s %14s %16s %12s %8s\n", "integrator", "dt", "max error", "ns/particle", "energy drift", "worst rise", "flags");
    printf("(worst rise: the largest energy gain over one step, of the energy scale; flagged above %.0f %%)\n", 100 * ACC_ENERGY_RISE);
    FILE *csv = bench_csv(dir, "tradeoff.csv", "integrator,dt,error,ns_per_particle_step,ns_per_particle_to_t,energy_drift,worst_energy_rise,flags");
    const int n = 1000;
    const double t_end = 10.0;
    const double dts[] = {0.1, 0.05, 0.02, 0.01, 0.005, 0.002};
    for (int integ = 0; integ < TT_INTEGRATOR_COUNT; integ++) {
        for (int d = 0; d < 6; d++) {
            double dt = dts[d];
            tt_world_def wd = tt_world_def_default();
            wd.gravity = (tt_vec2){0, 0};
            wd.integrator = (tt_integrator)integ;
            tt_world *w = tt_world_create(&wd);
            tt_particle *ps = malloc(n * sizeof *ps);
            for (int i = 0; i < n; i++) {
                tt_particle_def pd = tt_particle_def_default();
                pd.pinned = true;
                pd.position = (tt_vec2){i * 10.0, 0};
                tt_particle anchor = tt_particle_create(w, &pd);
                pd.pinned = false;
                pd.position = (tt_vec2){i * 10.0 + 1, 0};
                pd.velocity = (tt_vec2){0, 0.5};
                ps[i] = tt_particle_create(w, &pd);
                tt_spring_def sd = tt_spring_def_default();
                sd.a = ps[i];
                sd.b = anchor;
                sd.stiffness = 1;
                sd.rest_length = 0;
                tt_spring_create(w, &sd);
            }
            tt_energy e0, e1;
            tt_world_get_energy(w, &e0);
            bench_acc acc;
            bench_acc_init(&acc, w, ACC_ENERGY, NULL, 0);
            int steps = (int)lround(t_end / dt);
            double *t = malloc(steps * sizeof *t);
            for (int s = 0; s < steps; s++) {
                double t0 = bench_now_ns();
                tt_world_step(w, dt);
                t[s] = (bench_now_ns() - t0) / n;
                bench_acc_step(&acc, w);
            }
            tt_world_get_energy(w, &e1);
            double err = 0;
            for (int i = 0; i < n; i++) {
                tt_vec2 x;
                tt_particle_get_position(w, ps[i], &x);
                err = fmax(err, hypot(x.x - i * 10.0 - cos(t_end), x.y - 0.5 * sin(t_end)));
            }
            double ns = bench_median(t, steps);
            double drift = e1.total / e0.total - 1;
            char fl[64];
            bench_acc_flags(&acc, fl, sizeof fl);
            printf("%18s %10.3f %14.3e %14.2f %+16.3e %+11.2f%% %8s\n", tt_integrator_name((tt_integrator)integ), dt, err, ns, drift,
                   100 * acc.worst_rise, fl);
            fprintf(csv, "%s,%g,%.6e,%.4f,%.4f,%.6e,%.6e,%s\n", tt_integrator_name((tt_integrator)integ), dt, err, ns, ns * steps, drift,
                    acc.worst_rise, fl);
            bench_acc_free(&acc);
            free(t);
            free(ps);
            tt_world_destroy(w);
        }
    }
    fclose(csv);
}

/* `bench DIR [SECTION]`: every section, or the one named. */
static const struct {
    const char *name;
    void (*run)(const char *dir);
} sections[] = {
    {"integrate", bench_integrate},
    {"tradeoff", bench_tradeoff},
    {"collide", bench_collide},
    {"pour", bench_pour},
    {"pourstarts", bench_pour_starts},
    {"pour100k", bench_pour100k},
    {"render", bench_render},
    {"constraints", bench_constraints},
    {"cloth", bench_cloth},
    {"mask", bench_mask},
    {"snapshot", bench_snapshot},
    {"terrain", bench_terrain},
    {"bowlstarts", bench_bowl_starts},
    {"rewind", bench_rewind},
    {"journal", bench_journal},
    {"sleep", bench_sleep},
    {"payonly", bench_payonly},
};

int main(int argc, char **argv)
{
    const char *dir = argc > 1 ? argv[1] : "build"; /* not the checkout's root: make bench passes its folder */
    const char *only = argc > 2 ? argv[2] : NULL;
    printf("tether %s benchmarks (medians; CSV in %s)\n", tt_version(), dir);
    for (size_t k = 0; k < sizeof sections / sizeof sections[0]; k++)
        if (!only || strcmp(only, sections[k].name) == 0) sections[k].run(dir);
    if (only && strcmp(only, "sleep-quick") == 0) bench_sleep_quick(dir); /* for callgrind: not in the full run */
    if (only && strcmp(only, "sleep-wake") == 0) bench_sleep_wake(dir);   /* likewise */
    if (only && strcmp(only, "payonly-cg") == 0) bench_payonly_cg(dir);   /* likewise (bench/payonly_cg.sh) */
    return 0;
}
