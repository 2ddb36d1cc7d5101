/* tether — collision benchmarks: ms/step against particle count (grid and
 * brute force, equal radii and a 1:4 mix), the grid's scaling slope,
 * broadphase memory per particle, and the reference pour (src/scenes/)
 * against Box2D 2.4.1 doing the same (through src/box2d/). */
#include "bench.h"
#include "tether.h"
#include "box2d/box2d_scene.h"

#include <math.h>
#include <stdlib.h>

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
    tt_particle_def pd = tt_particle_def_default();
    for (uint32_t i = 0; i < n; i++) {
        pd.radius = mix ? (i % 4 == 0 ? 1.0 : 0.25) : 0.5;
        pd.position = (tt_vec2){-(cols * spacing) / 2 + spacing * (0.5 + i % cols), spacing * (0.5 + i / cols)};
        tt_particle_create(w, &pd);
    }
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

/* Medians over the four sizes of one radii mix, measured in turns: each
 * round steps every size untimed, so its data is back in cache, then
 * timed. A shared machine's load drifts over seconds; in turns it falls on
 * every size alike instead of tilting the slope. The 100k world takes
 * steps 10 to 55: with one sweep a column of 316 rows cannot hold its own
 * weight; it compresses, a step costs more as it does (about 5.5 ms by
 * step 150), and from there its pairs grow from 200 k to 900 k by step 300. */
#define ROUNDS 15
static void sizes_in_turns(const uint32_t sizes[4], bool mix, double grid[4], double detect[4], double bp[4],
                           tt_collision_stats cst[4])
{
    static const int per_round[4] = {5, 3, 2, 1};
    tt_world *w[4];
    double *t[4][3];
    for (int k = 0; k < 4; k++) {
        w[k] = packed(sizes[k], mix, TT_BROADPHASE_GRID, 1);
        for (int s = 0; s < 10; s++) tt_world_step(w[k], 1.0 / 60);
        for (int j = 0; j < 3; j++) t[k][j] = malloc(ROUNDS * (size_t)per_round[k] * sizeof(double));
    }
    for (int r = 0; r < ROUNDS; r++)
        for (int k = 0; k < 4; k++) {
            tt_world_step(w[k], 1.0 / 60);
            for (int i = r * per_round[k]; i < (r + 1) * per_round[k]; i++) timed_step(w[k], &t[k][0][i], &t[k][1][i], &t[k][2][i]);
        }
    for (int k = 0; k < 4; k++) {
        grid[k] = bench_median(t[k][0], ROUNDS * per_round[k]);
        detect[k] = bench_median(t[k][1], ROUNDS * per_round[k]);
        bp[k] = bench_median(t[k][2], ROUNDS * per_round[k]);
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

void bench_collide(const char *dir)
{
    printf("\n== Collisions: colliding particles packed in a box under gravity (1 substep, 1 iteration) ==\n");
    printf("target: 100k particles <= 5 ms/step (grid); grid cost linear in N, log-log slope 1 +- 0.1 from 1k to 1M\n");
    printf("(grid ms: whole steps; bp ms: the grid itself, its build and pair search, whose growth with N is\n"
           " the slope; detect ms: the detection stage, which adds the shape tests at the box's walls, fewer per\n"
           " particle in a bigger box; the rest of a step depends on how far each pile has settled)\n");
    printf("%9s %6s %10s %10s %10s %12s %12s %10s %12s\n", "particles", "radii", "grid ms", "bp ms", "detect ms", "brute ms",
           "ns/particle", "grid B/p", "collide B/p");
    FILE *csv = bench_csv(dir, "collide.csv",
                          "particles,radii,grid_ms,brute_ms,grid_bytes_per_particle,collide_bytes_per_particle,detect_ms,bp_ms");
    const uint32_t sizes[] = {1000, 10000, 100000, 1000000};
    double grid_ms[2][4], detect_ms[2][4], bp_ms[2][4];
    for (int mix = 0; mix < 2; mix++) {
        tt_collision_stats cst[4];
        sizes_in_turns(sizes, mix, grid_ms[mix], detect_ms[mix], bp_ms[mix], cst);
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
            fprintf(csv, "%u,%s,%.4f,%.4f,%.1f,%.1f,%.4f,%.4f\n", n, mix ? "mix" : "equal", g, b,
                    cst[k].broadphase_bytes_per_particle, total_bp, detect_ms[mix][k], bp_ms[mix][k]);
            fflush(stdout);
        }
    }
    fclose(csv);
    for (int mix = 0; mix < 2; mix++) {
        const double g = slope(sizes, bp_ms[mix]), d = slope(sizes, detect_ms[mix]);
        printf("grid log-log slope 1k..1M (%s radii): %.3f   target 1 +- 0.1: %s   (detection stage: %.3f)\n",
               mix ? "1:4" : "equal", g, fabs(g - 1) <= 0.1 ? "met" : "NOT met", d);
    }
    printf("100k equal radii: %.3f ms/step   target <= 5 ms: %s\n", grid_ms[0][2], grid_ms[0][2] <= 5 ? "met" : "NOT met");

}

/* The reference pour (src/scenes/, the scene `make crosscheck` uses) in
 * both engines for its first 5 s, sleeping off in both. */
void bench_pour(const char *dir)
{
    printf("\n== The reference pour (10 000 circles r = 0.5 into a 100-wide box), 300 steps of 1/60 s: tether vs Box2D 2.4.1 ==\n");
    printf("Box2D: 8 velocity / 3 position iterations, continuous off, sleeping off. tether: Verlet, 1 substep, 8 iterations\n");
    printf("(the two take turns, 30 steps each, timing only the step; means over the run; `make crosscheck` for 20 s)\n");
    printf("target: tether >= 20x faster than Box2D\n");
    const int steps = 300;
    ts_scene sc;
    ts_scene_pour(&sc, 10000, 100);
    ts_tether_settings set = ts_tether_settings_default();
    tb_world_def bd = tb_world_def_default();
    bd.sleep = bd.continuous = false;
    cc_pair p;
    const char *why = "";
    const bool opened = cc_pair_open(&p, &sc, &set, &bd, &why);
    ts_scene_free(&sc);
    if (!opened || !cc_pair_step(&p, steps, 30, &why)) {
        printf("pour: %s\n", why);
        if (opened) cc_pair_close(&p);
        return;
    }
    double b2 = 0, tt = 0, b2max = 0, worst = 0;
    for (int s = 0; s < steps; s++) {
        b2 += p.t_b2[s] / steps;
        tt += p.t_tt[s] / steps;
        b2max = fmax(b2max, p.t_b2[s]);
        worst = fmax(worst, p.t_tt[s]);
    }
    const uint32_t n = p.tt.circle_count;
    double *xy = malloc(2 * (size_t)n * sizeof *xy);
    ts_pile pb, pt;
    tb_positions(p.b2, 3, (int)n, xy); /* bodies 0–2 are the floor and the walls */
    ts_pile_measure(xy, n, 0.5, &pb);
    tt_particles_get_positions(p.tt.world, p.tt.circles, n, xy);
    ts_pile_measure(xy, n, 0.5, &pt);
    free(xy);
    cc_pair_close(&p);
    printf("%10s %14s %14s %14s %16s %14s\n", "engine", "mean ms/step", "worst ms", "pile height m", "max overlap", "mean overlap");
    printf("%10s %14.3f %14.3f %14.2f %14.1f %%r %12.2f %%r\n", "Box2D", b2, b2max, pb.height, 100 * pb.max_overlap, 100 * pb.mean_overlap);
    printf("%10s %14.3f %14.3f %14.2f %14.1f %%r %12.2f %%r\n", "tether", tt, worst, pt.height, 100 * pt.max_overlap, 100 * pt.mean_overlap);
    printf("speed-up %.1fx   target >= 20x: %s\n", b2 / tt, b2 / tt >= 20 ? "met" : "NOT met");
    FILE *c2 = bench_csv(dir, "collide_box2d.csv", "engine,mean_ms,worst_ms,height,max_overlap,mean_overlap");
    fprintf(c2, "box2d,%.4f,%.4f,%.3f,%.4f,%.4f\ntether,%.4f,%.4f,%.3f,%.4f,%.4f\n", b2, b2max, pb.height, pb.max_overlap,
            pb.mean_overlap, tt, worst, pt.height, pt.max_overlap, pt.mean_overlap);
    fclose(c2);
}
