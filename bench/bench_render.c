/* tether — renderer benchmark: one 800x600 headless (OSMesa, software GL)
 * frame of n particles, split into the debug draw (canvas batches, through
 * the public API) and the GL drawing; the PNG encoding is timed apart. */
#include "bench.h"
#include "scenes/scene.h"
#include "tether.h"
#include "tether/render.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

/* CPU time of the whole process (llvmpipe's threads included), ms: with
 * other work on the machine, wall time grows and this does not. */
static double cpu_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec * 1e3 + (double)ts.tv_nsec * 1e-6;
}

void bench_render(const char *dir)
{
    printf("\n== Headless frame, 800x600, OSMesa (software GL): debug draw of n particles ==\n");
    printf("target: <= 50 ms per frame (draw + render) at 100 000 particles\n");
    printf("(wall-clock medians; 'frame cpu' is the process CPU time of draw + render, all threads)\n");
    printf("%10s %10s %10s %10s %10s %10s %10s\n", "particles", "draw ms", "render ms", "frame ms", "frame cpu", "PNG ms", "target");
    FILE *csv = bench_csv(dir, "render.csv", "particles,draw_ms,render_ms,frame_ms,png_ms,frame_cpu_ms");
    char err[256] = "";
    tt_headless *hl = tt_headless_create(800, 600, err, sizeof err);
    tt_canvas *c = tt_canvas_create(800, 600);
    if (!hl || !c) {
        printf("skipped: %s\n", err);
        fclose(csv);
        tt_canvas_destroy(c);
        return;
    }
    const int sizes[] = {1000, 10000, 100000, 300000};
    for (int s = 0; s < 4; s++) {
        int n = sizes[s];
        tt_world_def wd = tt_world_def_default();
        wd.capacity = (uint32_t)n;
        tt_world *w = tt_world_create(&wd);
        /* a square-ish lattice filling a 40 x 30 m view, radius half the spacing */
        int cols = (int)ceil(sqrt(n * 4.0 / 3.0));
        double h = 40.0 / cols;
        ts_grid g = ts_grid_default();
        g.count = (uint32_t)n;
        g.columns = (uint32_t)cols;
        g.corner = (tt_vec2){-20, -15};
        g.spacing = h;
        g.radius = 0.45 * h;
        ts_grid_add(w, &g);
        tt_canvas_fit(c, (tt_vec2){-20, -15}, (tt_vec2){20, 15}, 0);
        int reps = n >= 100000 ? 11 : 31;
        double *td = malloc(reps * sizeof *td), *tr = malloc(reps * sizeof *tr), *tf = malloc(reps * sizeof *tf);
        double *tc = malloc(reps * sizeof *tc);
        for (int r = -1; r < reps; r++) { /* r = -1: warm up (first upload, JIT) */
            double c0 = cpu_ms();
            double t0 = bench_now_ns();
            tt_canvas_clear(c, (tt_color){18, 20, 28, 255});
            tt_canvas_draw_world(c, w, NULL);
            double t1 = bench_now_ns();
            tt_headless_render(hl, c);
            double t2 = bench_now_ns();
            double c1 = cpu_ms();
            if (r >= 0) {
                tc[r] = c1 - c0;
                td[r] = (t1 - t0) * 1e-6;
                tr[r] = (t2 - t1) * 1e-6;
                tf[r] = (t2 - t0) * 1e-6;
            }
        }
        char path[1100];
        snprintf(path, sizeof path, "%s/render_%d.png", dir, n);
        double tp[3];
        for (int r = 0; r < 3; r++) {
            double t0 = bench_now_ns();
            tt_headless_write_png(hl, path);
            tp[r] = (bench_now_ns() - t0) * 1e-6;
        }
        double d = bench_median(td, reps), rr = bench_median(tr, reps), f = bench_median(tf, reps), p = bench_median(tp, 3);
        double cp = bench_median(tc, reps);
        printf("%10d %10.2f %10.2f %10.2f %10.2f %10.2f %10s\n", n, d, rr, f, cp, p,
               n == 100000 ? (f <= 50.0 ? "<= 50 ok" : "> 50 MISS") : "");
        fprintf(csv, "%d,%.3f,%.3f,%.3f,%.3f,%.3f\n", n, d, rr, f, p, cp);
        free(td); free(tr); free(tf); free(tc);
        tt_world_destroy(w);
    }
    fclose(csv);
    tt_canvas_destroy(c);
    tt_headless_destroy(hl);
}
