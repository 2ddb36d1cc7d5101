/* tether — pay only for what is used: 100 000 free-falling particles, a
 * plain world against the same world with one feature switched on that has
 * nothing to do (a spring elsewhere, a shape 10⁶ m away, one bullet,
 * particle pairs with nothing touching, contact events with no contact,
 * pairs with every radius 0). Target: each costs ≤ 1.05× the plain world in
 * instructions (wall clock ≤ 1.10×); pairs with nothing touching ≤ 1.5×.
 *
 * Wall clock here, plain and feature stepped alternately (A B A B) so both
 * see the same machine. The instruction ratios come from the same worlds
 * under callgrind: `payonly-cg` dumps each world's measured steps apart
 * (CALLGRIND_DUMP_STATS_AT), bench/payonly_cg.sh reads the dumps:
 *   sh bench/payonly_cg.sh build/bench        (also run by `make bench`) */
#include "bench.h"
#include "scenes/scene.h"
#include "tether.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#if defined(__has_include)
#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#endif
#endif
#ifndef CALLGRIND_DUMP_STATS_AT /* no valgrind headers: payonly-cg only steps */
#define CALLGRIND_ZERO_STATS
#define CALLGRIND_DUMP_STATS_AT(label) (void)(label)
#endif

#define DT (1.0 / 60.0)
enum { N = 100000, COLS = 1000, WARM = 2, REPS = 41, CG_STEPS = 3 };

typedef enum { PLAIN, SPRING, FAR_SHAPE, BULLET, PAIRS, EVENTS, PAIRS_R0, ROWS } row;

static const char *const names[ROWS] = {
    "plain world", "one spring elsewhere", "static shape 1e6 m away", "one bullet particle",
    "pairs on, nothing touching", "contact events on", "pairs on, every radius 0",
};

/* Every world: the same lattice (1 m apart, radius 0.2: nothing touches) and
 * two particles elsewhere, which the spring joins and one of which is the
 * bullet; only the feature differs. */
static tt_world *make(row r)
{
    tt_world_def wd = tt_world_def_default();
    wd.capacity = N + 2;
    tt_world *w = tt_world_create(&wd);
    ts_grid g = ts_grid_default();
    g.count = N;
    g.columns = COLS;
    g.corner = (tt_vec2){-0.5, -0.5}; /* centres on whole metres */
    g.radius = r == PAIRS_R0 ? 0.0 : 0.2;
    ts_grid_add(w, &g);
    tt_particle_def pd = tt_particle_def_default();
    pd.radius = g.radius;
    pd.position = (tt_vec2){-1000.0, 0.0};
    tt_particle a = tt_particle_create(w, &pd);
    pd.position = (tt_vec2){-999.0, 0.0};
    tt_particle b = tt_particle_create(w, &pd);
    tt_collision_settings cs = tt_collision_settings_default();
    switch (r) {
    case SPRING: {
        tt_spring_def sd = tt_spring_def_default();
        sd.a = a;
        sd.b = b;
        tt_spring_create(w, &sd);
        break;
    }
    case FAR_SHAPE: {
        tt_shape_def sh = tt_shape_def_default();
        sh.position = (tt_vec2){1e6, 0.0};
        tt_shape_create(w, &sh);
        break;
    }
    case BULLET: tt_particle_set_bullet(w, a, true); break;
    case PAIRS:
    case PAIRS_R0: tt_world_set_collision(w, &cs); break;
    case EVENTS:
        cs.particles = false;
        cs.events = TT_EVENT_BEGIN | TT_EVENT_PERSIST | TT_EVENT_END;
        tt_world_set_collision(w, &cs);
        break;
    default: break;
    }
    for (int s = 0; s < WARM; s++) tt_world_step(w, DT);
    return w;
}

static double step_ms(tt_world *w)
{
    double t0 = bench_now_ns();
    tt_world_step(w, DT);
    return (bench_now_ns() - t0) * 1e-6;
}

static double minv(const double *v, int n)
{
    double m = v[0];
    for (int i = 1; i < n; i++) m = v[i] < m ? v[i] : m;
    return m;
}

static double maxv(const double *v, int n)
{
    double m = v[0];
    for (int i = 1; i < n; i++) m = v[i] > m ? v[i] : m;
    return m;
}

void bench_payonly(const char *dir)
{
    printf("\n== Pay only for what is used: %d free-falling particles, a plain world vs one feature with nothing to do ==\n", N);
    printf("target: each <= 1.05x the plain world in instructions (wall <= 1.10x); pairs on, nothing touching <= 1.5x\n");
    printf("(%d steps each, plain and feature alternating; instruction ratios: sh bench/payonly_cg.sh, run by make bench)\n", REPS);
    printf("%-28s %12s %20s %12s %20s %8s\n", "scene", "plain ms", "plain min-max", "feature ms", "feature min-max", "ratio");
    FILE *csv = bench_csv(dir, "payonly.csv", "scene,plain_ms,plain_min,plain_max,feature_ms,feature_min,feature_max,ratio");
    double *a = malloc(REPS * sizeof *a), *b = malloc(REPS * sizeof *b);
    for (int r = SPRING; r < ROWS; r++) {
        tt_world *p = make(PLAIN), *f = make((row)r);
        for (int k = 0; k < REPS; k++) {
            a[k] = step_ms(p);
            b[k] = step_ms(f);
        }
        const double alo = minv(a, REPS), ahi = maxv(a, REPS), blo = minv(b, REPS), bhi = maxv(b, REPS);
        const double ma = bench_median(a, REPS), mb = bench_median(b, REPS);
        printf("%-28s %12.3f %9.3f-%-10.3f %12.3f %9.3f-%-10.3f %7.2fx\n", names[r], ma, alo, ahi, mb, blo, bhi, mb / ma);
        fprintf(csv, "%s,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f\n", names[r], ma, alo, ahi, mb, blo, bhi, mb / ma);
        tt_world_destroy(p);
        tt_world_destroy(f);
    }
    fclose(csv);
    free(a);
    free(b);
}

/* Under callgrind: each world's CG_STEPS measured steps in a dump of their
 * own, named after the row (bench/payonly_cg.sh prints the ratios). */
void bench_payonly_cg(const char *dir)
{
    (void)dir;
    for (int r = PLAIN; r < ROWS; r++) {
        tt_world *w = make((row)r);
        CALLGRIND_ZERO_STATS;
        for (int s = 0; s < CG_STEPS; s++) tt_world_step(w, DT);
        char label[64];
        snprintf(label, sizeof label, "payonly-%d", r);
        CALLGRIND_DUMP_STATS_AT(label);
        tt_world_destroy(w);
        printf("%d %s\n", r, names[r]);
    }
}
