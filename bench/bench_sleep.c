/* tether — sleeping: the reference pour (src/scenes/) settled, asleep
 * against awake, then with 1 and 10 particles awake far from it, and a
 * ball dropped on the sleeping pile; waking one small island in a large
 * sleeping world (sleep-wake, for callgrind).
 *
 * Wall clock here; the instruction counts the README quotes come from the
 * same code under callgrind, each world's measured steps in their own
 * function (measure_awake, measure_asleep, measure_one_awake,
 * measure_ten_awake, measure_wake), read inclusive:
 *   valgrind --tool=callgrind build/bench DIR sleep-quick   (or sleep-wake)
 *   callgrind_annotate --inclusive=yes --threshold=100 callgrind.out.* | grep measure_ */
#include "bench.h"

#include "scenes/scene.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define DT (1.0 / 60.0)
enum { MEASURED = 60 };

static uint32_t sleeping(const tt_world *w)
{
    tt_stats st;
    tt_world_get_stats(w, &st);
    return st.sleeping;
}

static double height(const ts_tether *t)
{
    const uint32_t n = t->circle_count;
    double *xy = malloc(2 * (size_t)n * sizeof *xy);
    ts_pile p;
    tt_particles_get_positions(t->world, t->circles, n, xy);
    ts_pile_measure(xy, n, 0.5, &p);
    free(xy);
    return p.height;
}

/* Each world's measured steps in a function of its own (callgrind reads
 * them apart); the store keeps the compiler from folding them into one. */
static volatile int measuring;

static void timed_steps(tt_world *w, double *ms)
{
    for (int s = 0; s < MEASURED; s++) {
        double t0 = bench_now_ns();
        tt_world_step(w, DT);
        ms[s] = (bench_now_ns() - t0) * 1e-6;
    }
}

__attribute__((noinline)) static void measure_awake(tt_world *w, double *ms)
{
    measuring = 1;
    timed_steps(w, ms);
}

__attribute__((noinline)) static void measure_asleep(tt_world *w, double *ms)
{
    measuring = 2;
    timed_steps(w, ms);
}

/* The sleeping pile with one particle awake far from it. */
__attribute__((noinline)) static void measure_one_awake(tt_world *w, double *ms)
{
    measuring = 3;
    timed_steps(w, ms);
}

/* The same with ten, apart from each other. */
__attribute__((noinline)) static void measure_ten_awake(tt_world *w, double *ms)
{
    measuring = 4;
    timed_steps(w, ms);
}

static bool build(const ts_scene *sc, bool sleep, ts_tether *t)
{
    ts_tether_settings set = ts_tether_settings_default();
    const char *why = "";
    if (ts_tether_build(sc, &set, t, &why) != TT_OK) {
        printf("sleep: %s\n", why);
        return false;
    }
    const tt_world_def d = tt_world_def_default();
    if (sleep) tt_world_set_sleep(t->world, true, d.sleep_speed, d.sleep_time);
    else tt_world_set_sleep(t->world, false, 0.0, 0.0);
    return true;
}

static tt_particle drop_ball(tt_world *w, double y)
{
    tt_particle_def d = tt_particle_def_default();
    d.position = (tt_vec2){0.3, y};
    d.radius = 0.5;
    d.velocity = (tt_vec2){0.0, -5.0};
    return tt_particle_create(w, &d);
}

static void run(const char *dir, uint32_t n, double width, const char *label)
{
    ts_scene sc;
    ts_scene_pour(&sc, n, width);
    ts_tether on, off;
    if (!build(&sc, true, &on)) return;
    if (!build(&sc, false, &off)) return;
    ts_scene_free(&sc);
    int settle = 0;
    while (sleeping(on.world) < n && settle < 7200) tt_world_step(on.world, DT), settle++;
    for (int s = 0; s < settle; s++) tt_world_step(off.world, DT);
    double *a = malloc(MEASURED * sizeof *a), *b = malloc(MEASURED * sizeof *b);
    measure_awake(off.world, a);
    measure_asleep(on.world, b);
    const double ma = bench_median(a, MEASURED), mb = bench_median(b, MEASURED);
    const double h_off = height(&off), h_on = height(&on);
    printf("%-8s %8u %14d %12u %14.3f %14.3f %10.1f %%\n", label, n, settle, sleeping(on.world), ma, mb, 100 * mb / ma);
    /* one, then ten particles awake, falling far above the pile (5 m apart) for the measured steps */
    for (uint32_t k = 1; k <= 10; k += 9) {
        tt_particle lone[10];
        for (uint32_t j = 0; j < k; j++) {
            tt_particle_def d = tt_particle_def_default();
            d.position = (tt_vec2){5.0 * j, fmax(h_off, h_on) + 1e4};
            d.radius = 0.5;
            lone[j] = tt_particle_create(on.world, &d);
        }
        if (k == 1) measure_one_awake(on.world, b);
        else measure_ten_awake(on.world, b);
        const double m1 = bench_median(b, MEASURED);
        printf("%-8s %8u %14s %12u %14.3f %14.3f %10.1f %%   (%u awake far above; target <= 10 %%: %s by wall clock)\n",
               label, n + k, "", sleeping(on.world), ma, m1, 100 * m1 / ma, k, m1 <= 0.1 * ma ? "met" : "NOT met");
        for (uint32_t j = 0; j < k; j++) tt_particle_destroy(on.world, lone[j]);
    }
    /* the ball, on both */
    const double top = fmax(h_off, h_on) + 3.0;
    drop_ball(on.world, top);
    drop_ball(off.world, top);
    uint32_t woke = 0;
    int again = 0;
    while (again < 7200) {
        tt_world_step(on.world, DT);
        tt_world_step(off.world, DT);
        again++;
        uint32_t z = sleeping(on.world);
        if (n - (z < n ? z : n) > woke) woke = n - (z < n ? z : n);
        if (z == n + 1) break;
    }
    const double b_off = height(&off), b_on = height(&on);
    printf("ball     woke %u of %u; all asleep again after %d steps; pile height awake %.3f m, asleep %.3f m: "
           "%.2f r apart (target <= 0.5 r: %s)\n",
           woke, n, again, b_off, b_on, fabs(b_off - b_on) / 0.5, fabs(b_off - b_on) <= 0.25 ? "met" : "NOT met");
    FILE *csv = bench_csv(dir, "sleep.csv", "n,settle_steps,awake_ms,asleep_ms,height_awake,height_asleep,ball_woke,"
                                            "ball_resleep_steps,ball_height_awake,ball_height_asleep");
    fprintf(csv, "%u,%d,%.4f,%.4f,%.3f,%.3f,%u,%d,%.3f,%.3f\n", n, settle, ma, mb, h_off, h_on, woke, again, b_off, b_on);
    fclose(csv);
    free(a);
    free(b);
    ts_tether_free(&on);
    ts_tether_free(&off);
}

static void header(void)
{
    printf("\n== Sleeping: the reference pour settled, asleep vs awake (%d steps each, medians) ==\n", MEASURED);
    printf("target: a settled pile asleep costs <= 10 %% of the same pile awake per step (callgrind: see README)\n");
    printf("%-8s %8s %14s %12s %14s %14s %12s\n", "pour", "circles", "steps to sleep", "asleep", "awake ms/step",
           "asleep ms/step", "asleep/awake");
}

void bench_sleep(const char *dir)
{
    header();
    run(dir, 10000, 100, "ref");
}

/* The 1 000-circle pour (the cross-check's quick one), for callgrind. */
void bench_sleep_quick(const char *dir)
{
    header();
    run(dir, 1000, 31.6, "quick");
}

/* Waking one small island in a large sleeping world: 5 000 islands of two
 * touching circles on a floor (10 000 particles), asleep; 100 of them woken
 * by a script call each, measured apart for callgrind (measure_wake). */
__attribute__((noinline)) static uint32_t measure_wake(tt_world *w, const tt_particle *p, double *ms)
{
    measuring = 5;
    for (int k = 0; k < 100; k++) {
        double t0 = bench_now_ns();
        tt_particle_apply_impulse(w, p[(size_t)k * 100 + 1], (tt_vec2){0.0, 0.0});
        ms[k] = (bench_now_ns() - t0) * 1e-6;
    }
    return sleeping(w);
}

void bench_sleep_wake(const char *dir)
{
    (void)dir;
    enum { ISLANDS = 5000 };
    tt_world *w = tt_world_create(NULL);
    tt_collision_settings cs = tt_collision_settings_default();
    tt_world_set_collision(w, &cs);
    tt_shape_def g = tt_shape_def_default();
    g.type = TT_SHAPE_AABB;
    g.a = (tt_vec2){-1.0, -1.0}, g.b = (tt_vec2){ISLANDS * 1.0, 0.0};
    tt_shape_create(w, &g);
    tt_particle *p = malloc(2 * ISLANDS * sizeof *p);
    for (uint32_t k = 0; k < 2 * ISLANDS; k++) {
        tt_particle_def d = tt_particle_def_default();
        d.radius = 0.1;
        d.position = (tt_vec2){(k / 2) * 1.0 + (k % 2) * 0.2, 0.1};
        p[k] = tt_particle_create(w, &d);
    }
    int settle = 0;
    while (sleeping(w) < 2 * ISLANDS && settle < 600) tt_world_step(w, DT), settle++;
    double ms[100];
    const uint32_t before = sleeping(w), after = measure_wake(w, p, ms);
    printf("\n== Sleeping: waking one island of two in %u sleepers (asleep after %d steps), 100 times ==\n", before, settle);
    printf("woke %u particles; %.2f us per wake (median; callgrind: measure_wake, see README)\n", before - after,
           1e3 * bench_median(ms, 100));
    free(p);
    tt_world_destroy(w);
}
