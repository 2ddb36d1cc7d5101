/* tether — the reference pour onto the mask bowl (issue 19) from eleven
 * starts: as built, and the circles jittered by up to ±0.05 m with seeds
 * 1 to 10 (ts_tether_jitter), each poured 20 s at 1 × 8, sleeping off,
 * without and with anchored friction (tt_collision_settings.
 * anchored_friction), the two taking turns start by start. Per run: the
 * kinetic energy at 20 s and its mean over 10–20 s (every half second),
 * the deepest circle into the bowl, the circles' overlap at the end, and
 * the time per step. Target: KE <= 1e-3 J/kg at 20 s on every start. */
#include "bench.h"
#include "scenes/scene.h"

#include <math.h>
#include <stdlib.h>

enum { STARTS = 11 };

typedef struct run {
    double ke, ke_mean, ms;
    ts_bowl_figures f;
} run;

static bool pour(uint64_t seed, bool anchored, run *out)
{
    ts_bowl b;
    const char *why = NULL;
    if (ts_bowl_build(10000, 100, &b, &why) != TT_OK || ts_tether_jitter(&b.t, seed, 0.05) != TT_OK) {
        printf("  bowl: %s\n", why ? why : "failed");
        return false;
    }
    tt_collision_settings cs;
    tt_world_get_collision(b.t.world, &cs);
    cs.anchored_friction = anchored;
    tt_world_set_collision(b.t.world, &cs);
    double ns = 0.0, sum = 0.0;
    int samples = 0;
    for (uint32_t s = 1; s <= b.steps; s++) {
        const double a = bench_now_ns();
        tt_world_step(b.t.world, 1.0 / 60);
        ns += bench_now_ns() - a;
        if (s >= b.steps / 2 && s % 30 == 0) sum += ts_tether_kinetic_per_kg(&b.t), samples++;
    }
    ts_bowl_measure(&b, &out->f);
    out->ke = out->f.kinetic;
    out->ke_mean = samples ? sum / samples : 0.0;
    out->ms = ns * 1e-6 / b.steps;
    ts_bowl_free(&b);
    return true;
}

static int cmp(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

void bench_bowl_starts(const char *dir)
{
    printf("\n== The reference pour onto the mask bowl from 11 starts (the pour, and jittered +-0.05 m, seeds 1-10), "
           "20 s, 1 x 8, sleeping off ==\n");
    printf("target (issue 19): KE <= 1e-3 J/kg at 20 s, no centre in a solid pixel, penetration <= 10 %% of a radius\n");
    printf("%5s %9s %11s %13s %10s %9s %9s %8s\n", "start", "friction", "KE 20 s", "KE 10-20 s", "deepest", "ovl max",
           "ovl mean", "ms/step");
    FILE *csv = bench_csv(dir, "bowl_starts.csv", "seed,anchored,ke20,ke_mean,penetration,inside,max_overlap,mean_overlap,ms");
    run r[2][STARTS];
    for (int k = 0; k < STARTS; k++)
        for (int a = 0; a < 2; a++) {
            if (!pour((uint64_t)k, a, &r[a][k])) return;
            const run *x = &r[a][k];
            printf("%5d %9s %11.2e %13.2e %9.1f%% %8.1f%% %8.2f%% %8.2f%s\n", k, a ? "anchored" : "plain", x->ke, x->ke_mean,
                   100 * x->f.penetration, 100 * x->f.max_overlap, 100 * x->f.mean_overlap, x->ms, x->f.inside ? "  INSIDE" : "");
            fprintf(csv, "%d,%d,%.4e,%.4e,%.5f,%u,%.5f,%.5f,%.4f\n", k, a, x->ke, x->ke_mean, x->f.penetration, x->f.inside,
                    x->f.max_overlap, x->f.mean_overlap, x->ms);
            fflush(stdout);
        }
    for (int a = 0; a < 2; a++) {
        double lo = INFINITY, hi = 0.0, ms[STARTS];
        int over = 0;
        for (int k = 0; k < STARTS; k++) {
            lo = fmin(lo, r[a][k].ke), hi = fmax(hi, r[a][k].ke);
            over += r[a][k].ke > 1e-3;
            ms[k] = r[a][k].ms;
        }
        qsort(ms, STARTS, sizeof *ms, cmp);
        printf("  %s: KE at 20 s %.1e ... %.1e J/kg, over 1e-3 on %d of %d; %.2f ms/step (median; %.2f-%.2f)\n",
               a ? "anchored" : "plain", lo, hi, over, STARTS, ms[STARTS / 2], ms[0], ms[STARTS - 1]);
    }
    fclose(csv);
}
