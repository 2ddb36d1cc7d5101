/* tether — shared helpers for the benchmark sections (one bench_<feature>.c each). */
#ifndef TETHER_BENCH_H
#define TETHER_BENCH_H

#include <stdio.h>

#include "tether.h"

double bench_now_ns(void);
/* Sorts v in place and returns its median. */
double bench_median(double *v, int n);
/* Opens dir/name for writing and writes the CSV header line; exits on failure. */
FILE *bench_csv(const char *dir, const char *name, const char *header);

/* Sections: each prints a table (with its target) and writes CSV into dir. */
void bench_integrate(const char *dir);
void bench_tradeoff(const char *dir);
void bench_collide(const char *dir);
/* The reference pour against Box2D 2.4.1 (bench_pour.c): at the default
 * setting; with stacking and anchored friction from 11 starts. */
void bench_pour(const char *dir);
/* The pile settings issue 21's "<= 1 % at rest" is measured at (pourstarts,
 * and a pour100k row): stacking 2, anchored friction, warm start 0.75, on cs. */
void bench_pile_settings(tt_collision_settings *cs);
void bench_pour_starts(const char *dir);
void bench_pour100k(const char *dir);
void bench_render(const char *dir);
void bench_constraints(const char *dir);
void bench_cloth(const char *dir);
/* Distance links cs[0, n) now: mean and max of |d/rest − 1| (bench_cloth.c). */
void bench_cloth_strain(const tt_world *w, const tt_constraint *cs, uint32_t n, double *mean, double *max);
void bench_mask(const char *dir);
void bench_snapshot(const char *dir);
void bench_terrain(const char *dir);
void bench_bowl_starts(const char *dir);
void bench_rewind(const char *dir);
void bench_journal(const char *dir);
/* Sleeping: the settled reference pour asleep vs awake, a ball dropped on it (bench_sleep.c). */
void bench_sleep(const char *dir);
void bench_sleep_quick(const char *dir);
void bench_sleep_wake(const char *dir); /* for callgrind: waking one small island in a large sleeping world */
/* Unused features against a plain world, 100 000 particles (bench_payonly.c); _cg for callgrind. */
void bench_payonly(const char *dir);
void bench_payonly_cg(const char *dir);

#endif
