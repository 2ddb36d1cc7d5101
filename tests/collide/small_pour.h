/* tether — the small pour the stacking and warm-start tests share
 * (small_pour.c). */
#ifndef TETHER_TEST_SMALL_POUR_H
#define TETHER_TEST_SMALL_POUR_H

#include <stdbool.h>
#include <stdint.h>

/* 1 000 circles poured into a box 20 m wide (the reference pour's scene,
 * smaller), jittered by ±0.05 m with seed, 1 × iterations, stacking 2,
 * with or without anchored friction, warm_start as given: the deepest
 * overlap (fraction of a radius) and KE (J/kg) at 15 s. False when a step
 * or the set-up failed. */
bool small_pour(uint64_t seed, bool anchored, uint32_t iterations, double warm, double *deepest_at_end, double *ke);

#endif
