/* tether — the accuracy every bench figure carries (issue 16): measured at
 * every step of the whole timed run, outside the timed part, and flagged by
 * fixed thresholds. */
#ifndef TETHER_BENCH_ACCURACY_H
#define TETHER_BENCH_ACCURACY_H

#include <stdbool.h>
#include <stdio.h>

#include "tether.h"

/* The flags' thresholds, fixed (README "What the figures mean"). */
#define ACC_MAX_OVERLAP 0.25 /* deepest overlap, fraction of the smaller radius, at any step */
#define ACC_MEAN_STRAIN 0.05 /* mean |strain| of the links, at any step */
#define ACC_ENERGY_RISE 0.01 /* total energy up over one step, fraction of the scene's energy scale */

enum { ACC_OVERLAP = 1, ACC_STRETCH = 2, ACC_ENERGY = 4 };

typedef struct bench_acc {
    unsigned what;
    /* overlap: of every pair of particles, depth / the smaller radius */
    double *r;            /* radii in slot order, read once */
    double *xy;
    unsigned n;
    double max_overlap;   /* deepest at any step */
    double mean_overlap;  /* mean over steps of the mean over overlapping pairs */
    /* links: |length / rest − 1| over the distance constraints given */
    tt_constraint *links;
    double *rest;
    unsigned nlinks;
    double strain_mean;   /* the largest mean over the run */
    double strain_max;    /* the largest single link at any step */
    /* energy */
    double e_prev, e_scale, worst_rise, ke_per_kg, mass;
    double e_first, e_last;
    int steps;
} bench_acc;

/* Starts measuring w (its particles as they are now); links may be NULL. */
void bench_acc_init(bench_acc *a, tt_world *w, unsigned what, const tt_constraint *links, unsigned nlinks);
/* After each step of the run (not timed by the caller). */
void bench_acc_step(bench_acc *a, tt_world *w);
void bench_acc_free(bench_acc *a);
/* "ok" or the flags it raised: "COLLAPSE" (overlap), "STRETCH", "ENERGY+". */
const char *bench_acc_flags(const bench_acc *a, char *buf, size_t n);
/* The columns every table adds, and their CSV header and values. */
void bench_acc_head(void);
void bench_acc_print(const bench_acc *a);
#define BENCH_ACC_CSV "max_overlap,mean_overlap,ke_per_kg,strain_mean,strain_max,energy_drift,worst_energy_rise,flags"
void bench_acc_csv(FILE *f, const bench_acc *a);
/* Every distance constraint of composite c: *n of them, malloc'ed. */
tt_constraint *bench_acc_composite_links(const tt_world *w, tt_composite c, unsigned *n);

#endif
